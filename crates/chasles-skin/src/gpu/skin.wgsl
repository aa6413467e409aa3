// Kavan et al. 2006, §6: linear blend skinning and dual quaternion skinning on the GPU.
// The per-vertex math is skinning.wgsl's (put before this file), shared with the viewer's
// vertex shaders; here each entry point fetches a vertex's joints and stores the result.
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

@compute @workgroup_size(64)
fn lbs(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x + id.y * params.stride;
    if (i >= params.count) {
        return;
    }
    let v = vertices[i];
    let m = lbs_blend(rows(v.j.x), rows(v.j.y), rows(v.j.z), rows(v.j.w), v.w);
    store(i, lbs_move(m, v.p.xyz, v.n.xyz));
}

// Joint j's rows.
fn rows(j: u32) -> Rows {
    return Rows(matrices[j * 3u], matrices[j * 3u + 1u], matrices[j * 3u + 2u]);
}

@compute @workgroup_size(64)
fn dqs(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x + id.y * params.stride;
    if (i >= params.count) {
        return;
    }
    let v = vertices[i];
    let b = dqs_blend(dq(v.j.x), dq(v.j.y), dq(v.j.z), dq(v.j.w), v.w);
    store(i, rigid_move(b, v.p.xyz, v.n.xyz));
}

// Joint j's dual quaternion.
fn dq(j: u32) -> Dq {
    return Dq(dual_quats[j * 2u], dual_quats[j * 2u + 1u]);
}

fn store(i: u32, m: Moved) {
    skinned[i] = Skinned(vec4<f32>(m.p, 1.0), vec4<f32>(m.n, 0.0));
}

// Dual quaternion iterative blending (Kavan et al. §5): a vertex of at most two influences
// takes ScLERP in closed form (Lemma 3); the others start at DLB, then repeatedly move
// b by exp(Σ wᵢ log(b* qᵢ)), at most dib_updates times, stopping as the CPU does (below
// dib_precision, or stuck under dib_stall times that). The three are the CPU's own
// constants (chasles_skin::skinning::DIB_PRECISION, DIB_UPDATES and
// chasles::blend::STALL_FACTOR), set from Rust when the pipeline is made: none is written
// here. Dual quaternions as (real, dual), quaternions (w, x, y, z).
override dib_precision: f32;
override dib_stall: f32;
override dib_updates: u32;

fn qmul(a: vec4<f32>, b: vec4<f32>) -> vec4<f32> {
    return vec4<f32>(a.x * b.x - dot(a.yzw, b.yzw), a.x * b.yzw + b.x * a.yzw + cross(a.yzw, b.yzw));
}

fn qconj(a: vec4<f32>) -> vec4<f32> {
    return vec4<f32>(a.x, -a.yzw);
}

fn dqmul(a: Dq, b: Dq) -> Dq {
    return Dq(qmul(a.r, b.r), qmul(a.r, b.d) + qmul(a.d, b.r));
}

fn dqnormalize(a: Dq) -> Dq {
    let n = length(a.r);
    let r = a.r / n;
    let d = a.d / n;
    return Dq(r, d - r * dot(r, d));
}

// log of a dual quaternion with w ≥ 0 (DualQuat::log's main branch).
fn dqlog(q: Dq) -> Dq {
    let n2 = dot(q.r, q.r);
    let n2du = 2.0 * dot(q.r, q.d);
    let a = q.r.yzw;
    let b = q.d.yzw;
    let w = q.r.x;
    let s = dot(a, a);
    let s_du = 2.0 * dot(a, b);
    let n = sqrt(s);
    var h: f32;
    var h_s: f32;
    if (s < 1e-6 * w * w) {
        // atan2(n, w)/n = (1/w)(1 − s/(3w²) + s²/(5w⁴) − …)
        let w2 = w * w;
        h = (1.0 - s / (3.0 * w2) + s * s / (5.0 * w2 * w2)) / w;
        h_s = (-1.0 / (3.0 * w2) + 2.0 * s / (5.0 * w2 * w2)) / w;
    } else {
        let phi = atan2(n, w);
        h = phi / n;
        h_s = w / (2.0 * s * (s + w * w)) - phi / (2.0 * s * n);
    }
    let h_w = -1.0 / (s + w * w);
    let h_du = h_s * s_du + h_w * q.d.x;
    return Dq(
        vec4<f32>(0.5 * log(n2), a * h),
        vec4<f32>(0.5 * n2du / n2, b * h + a * h_du),
    );
}

// exp of any dual quaternion (DualQuat::exp).
fn dqexp(x: Dq) -> Dq {
    let a = x.r.yzw;
    let b = x.d.yzw;
    let s = dot(a, a);
    let s_du = 2.0 * dot(a, b);
    let t = sqrt(s);
    var k: f32;
    var dk: f32;
    if (s < 1e-6) {
        k = 1.0 - s / 6.0 + s * s / 120.0;
        dk = -1.0 / 6.0 + s / 60.0;
    } else {
        k = sin(t) / t;
        dk = (t * cos(t) - sin(t)) / (2.0 * s * t);
    }
    let c_re = cos(t);
    let c_du = -k * 0.5 * s_du;
    let k_du = dk * s_du;
    let e = exp(x.r.x);
    let e_du = x.d.x * e;
    let ur = vec4<f32>(c_re, a * k);
    let ud = vec4<f32>(c_du, a * k_du + b * k);
    return Dq(ur * e, ud * e + ur * e_du);
}

@compute @workgroup_size(64)
fn dib(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x + id.y * params.stride;
    if (i >= params.count) {
        return;
    }
    let v = vertices[i];
    let total = v.w.x + v.w.y + v.w.z + v.w.w;
    let wn = v.w / total;
    // DLB against the pivot, the first of the heaviest influences (as on the CPU: a layout
    // built by hand may put a weight of 0 first); and the count of positive weights and the
    // slots of the first two, wherever they sit.
    var q: array<Dq, 4>;
    var heaviest = 0u;
    var used = 0u;
    var first = 0u;
    var second = 0u;
    for (var k = 0u; k < 4u; k = k + 1u) {
        let j = v.j[k] * 2u;
        q[k] = Dq(dual_quats[j], dual_quats[j + 1u]);
        if (wn[k] > wn[heaviest]) {
            heaviest = k;
        }
        if (wn[k] > 0.0) {
            if (used == 0u) {
                first = k;
            } else if (used == 1u) {
                second = k;
            }
            used = used + 1u;
        }
    }
    let pivot = q[heaviest].r;
    var sum = Dq(vec4<f32>(0.0), vec4<f32>(0.0));
    for (var k = 0u; k < 4u; k = k + 1u) {
        var w = wn[k];
        if (dot(q[k].r, pivot) < 0.0) {
            w = -w;
        }
        sum = Dq(sum.r + q[k].r * w, sum.d + q[k].d * w);
    }
    var b = dqnormalize(sum);
    if (used <= 2u) {
        // Lemma 3: DIB of two is ScLERP, qa (qa* qb)^wb with qa* qb in its positive
        // hemisphere, in closed form (one influence: that joint itself).
        let qa = q[first];
        if (used == 2u) {
            var rel = dqmul(Dq(qconj(qa.r), qconj(qa.d)), q[second]);
            if (rel.r.x < 0.0) {
                rel = Dq(-rel.r, -rel.d);
            }
            let l = dqlog(rel);
            let t = wn[second];
            let x = Dq(vec4<f32>(0.0, l.r.yzw * t), vec4<f32>(0.0, l.d.yzw * t));
            b = dqnormalize(dqmul(qa, dqexp(x)));
        } else {
            b = dqnormalize(qa);
        }
        store(i, rigid_move(b, v.p.xyz, v.n.xyz));
        return;
    }
    var last = 3.0e38;
    for (var step = 0u; step < dib_updates; step = step + 1u) {
        let bc = Dq(qconj(b.r), qconj(b.d));
        var x = Dq(vec4<f32>(0.0), vec4<f32>(0.0));
        for (var k = 0u; k < 4u; k = k + 1u) {
            if (wn[k] == 0.0) {
                continue;
            }
            var rel = dqmul(bc, q[k]);
            if (rel.r.x < 0.0) {
                rel = Dq(-rel.r, -rel.d);
            }
            let l = dqlog(rel);
            x = Dq(x.r + l.r * wn[k], x.d + l.d * wn[k]);
        }
        let norm = sqrt(dot(x.r, x.r) + dot(x.d, x.d));
        let converged = norm < dib_precision;
        let stuck = norm >= last && norm < dib_precision * dib_stall;
        if (converged || stuck) {
            break;
        }
        last = norm;
        b = dqnormalize(dqmul(b, dqexp(x)));
    }
    b = dqnormalize(b);
    store(i, rigid_move(b, v.p.xyz, v.n.xyz));
}
