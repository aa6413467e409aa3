// Kavan et al. 2006, §6: linear blend skinning and dual quaternion skinning on the GPU.
// One invocation per vertex. Each vertex carries up to four influences, the heaviest first
// (it is DQS's antipodality pivot). Joint transforms: 3 rows of the 4×4 matrix (12 floats)
// for LBS, the unit dual quaternion (8 floats, w x y z) for DQS.

struct Vertex {
    p: vec4<f32>,
    n: vec4<f32>,
    j: vec4<u32>,
    w: vec4<f32>,
};

struct Skinned {
    p: vec4<f32>,
    n: vec4<f32>,
};

struct Params {
    count: u32,
    stride: u32,
    pad0: u32,
    pad1: u32,
};

@group(0) @binding(0) var<storage, read> vertices: array<Vertex>;
@group(0) @binding(1) var<storage, read> matrices: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> dual_quats: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> skinned: array<Skinned>;
@group(0) @binding(4) var<uniform> params: Params;

// A unit vector along v, or the fallback when v is zero (as the CPU reference does).
fn unit_or(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let l = length(v);
    if (l > 0.0) {
        return v / l;
    }
    return fallback;
}

@compute @workgroup_size(64)
fn lbs(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x + id.y * params.stride;
    if (i >= params.count) {
        return;
    }
    let v = vertices[i];
    var a = vec4<f32>(0.0);
    var b = vec4<f32>(0.0);
    var c = vec4<f32>(0.0);
    for (var k = 0u; k < 4u; k = k + 1u) {
        let j = v.j[k] * 3u;
        let w = v.w[k];
        a = a + matrices[j] * w;
        b = b + matrices[j + 1u] * w;
        c = c + matrices[j + 2u] * w;
    }
    let p = vec4<f32>(v.p.xyz, 1.0);
    // Normals by the cofactor matrix, whose rows are b×c, c×a, a×b.
    let nrm = v.n.xyz;
    let cn = vec3<f32>(
        dot(cross(b.xyz, c.xyz), nrm),
        dot(cross(c.xyz, a.xyz), nrm),
        dot(cross(a.xyz, b.xyz), nrm),
    );
    skinned[i] = Skinned(
        vec4<f32>(dot(a, p), dot(b, p), dot(c, p), 1.0),
        vec4<f32>(unit_or(cn, nrm), 0.0),
    );
}

// r p r* for a unit quaternion r = (w, x, y, z).
fn rotate(r: vec4<f32>, p: vec3<f32>) -> vec3<f32> {
    let u = r.yzw;
    return p + 2.0 * cross(u, cross(u, p) + r.x * p);
}

@compute @workgroup_size(64)
fn dqs(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x + id.y * params.stride;
    if (i >= params.count) {
        return;
    }
    let v = vertices[i];
    let pivot = dual_quats[v.j[0] * 2u];
    var real = vec4<f32>(0.0);
    var dual = vec4<f32>(0.0);
    for (var k = 0u; k < 4u; k = k + 1u) {
        let j = v.j[k] * 2u;
        let r = dual_quats[j];
        var w = v.w[k];
        if (dot(r, pivot) < 0.0) {
            w = -w;
        }
        real = real + r * w;
        dual = dual + dual_quats[j + 1u] * w;
    }
    let len = length(real);
    let r = real / len;
    let d = dual / len;
    // Translation 2 d r*: its vector part.
    let t = 2.0 * (r.x * d.yzw - d.x * r.yzw + cross(r.yzw, d.yzw));
    skinned[i] = Skinned(
        vec4<f32>(rotate(r, v.p.xyz) + t, 1.0),
        vec4<f32>(unit_or(rotate(r, v.n.xyz), v.n.xyz), 0.0),
    );
}
