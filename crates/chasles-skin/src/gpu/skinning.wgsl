// Kavan et al. 2006, §6: the per-vertex math of linear blend skinning and dual quaternion
// skinning, written once. The compute shaders (skin.wgsl) and the viewer's vertex shaders
// (chasles-view, translated to GLSL ES 3.00 by naga) put this file before their own and
// call these functions on the four joints they fetched — from storage buffers there, from
// a texture in the viewer — the heaviest influence first (DQS's antipodality pivot).

// C_j's top three rows (LBS's joint, chasles_skin::fast::Affine3x4).
struct Rows {
    a: vec4<f32>,
    b: vec4<f32>,
    c: vec4<f32>,
};

// A dual quaternion (real, dual), quaternions (w, x, y, z) (DQS's joint,
// chasles_skin::fast::UnitDualQuat).
struct Dq {
    r: vec4<f32>,
    d: vec4<f32>,
};

// A skinned position and normal.
struct Moved {
    p: vec3<f32>,
    n: vec3<f32>,
};

// A unit vector along v, or the fallback when v is zero (as the CPU reference does).
fn unit_or(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let l = length(v);
    if (l > 0.0) {
        return v / l;
    }
    return fallback;
}

// LBS: the weighted sum of the joints' rows.
fn lbs_blend(joints: array<Rows, 4>, weights: vec4<f32>) -> Rows {
    var m = joints;
    var a = vec4<f32>(0.0);
    var b = vec4<f32>(0.0);
    var c = vec4<f32>(0.0);
    for (var k = 0u; k < 4u; k = k + 1u) {
        let w = weights[k];
        a = a + m[k].a * w;
        b = b + m[k].b * w;
        c = c + m[k].c * w;
    }
    return Rows(a, b, c);
}

// A vertex moved by LBS's blended rows; its normal by the cofactor matrix, whose rows are
// b×c, c×a, a×b.
fn lbs_move(m: Rows, p: vec3<f32>, n: vec3<f32>) -> Moved {
    let p4 = vec4<f32>(p, 1.0);
    let cn = vec3<f32>(
        dot(cross(m.b.xyz, m.c.xyz), n),
        dot(cross(m.c.xyz, m.a.xyz), n),
        dot(cross(m.a.xyz, m.b.xyz), n),
    );
    return Moved(vec3<f32>(dot(m.a, p4), dot(m.b, p4), dot(m.c, p4)), unit_or(cn, n));
}

// r p r* for a unit quaternion r = (w, x, y, z).
fn rotate(r: vec4<f32>, p: vec3<f32>) -> vec3<f32> {
    let u = r.yzw;
    return p + 2.0 * cross(u, cross(u, p) + r.x * p);
}

// DQS (DLB, §4): the joints' dual quaternions blended with the antipodality fix against
// the heaviest influence (a joint whose rotation is more than 180° from the pivot's
// enters with the opposite sign), then divided by the real part's norm.
fn dqs_blend(joints: array<Dq, 4>, weights: vec4<f32>) -> Dq {
    var q = joints;
    let pivot = q[0].r;
    var real = vec4<f32>(0.0);
    var dual = vec4<f32>(0.0);
    for (var k = 0u; k < 4u; k = k + 1u) {
        let r = q[k].r;
        var w = weights[k];
        if (dot(r, pivot) < 0.0) {
            w = -w;
        }
        real = real + r * w;
        dual = dual + q[k].d * w;
    }
    let len = length(real);
    return Dq(real / len, dual / len);
}

// A vertex moved by the unit dual quaternion b: rotation, then the translation 2 d r*
// (its vector part); the normal turned by r.
fn rigid_move(b: Dq, p: vec3<f32>, n: vec3<f32>) -> Moved {
    let r = b.r;
    let d = b.d;
    let t = 2.0 * (r.x * d.yzw - d.x * r.yzw + cross(r.yzw, d.yzw));
    return Moved(rotate(r, p) + t, unit_or(rotate(r, n), n));
}
