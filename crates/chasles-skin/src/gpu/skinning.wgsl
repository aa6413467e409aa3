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

// LBS: the weighted sum of the joints' rows (joint k with weight w[k]). Written out joint by
// joint: no array to index, which software rasterizers run much faster.
fn lbs_blend(j0: Rows, j1: Rows, j2: Rows, j3: Rows, w: vec4<f32>) -> Rows {
    var m = Rows(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0));
    m = lbs_add(m, j0, w.x);
    m = lbs_add(m, j1, w.y);
    m = lbs_add(m, j2, w.z);
    m = lbs_add(m, j3, w.w);
    return m;
}

fn lbs_add(sum: Rows, j: Rows, w: f32) -> Rows {
    return Rows(sum.a + j.a * w, sum.b + j.b * w, sum.c + j.c * w);
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
// the heaviest influence j0 (a joint whose rotation is more than 180° from the pivot's
// enters with the opposite sign), then divided by the real part's norm.
fn dqs_blend(j0: Dq, j1: Dq, j2: Dq, j3: Dq, w: vec4<f32>) -> Dq {
    let pivot = j0.r;
    var sum = Dq(vec4<f32>(0.0), vec4<f32>(0.0));
    sum = dqs_add(sum, j0, w.x, pivot);
    sum = dqs_add(sum, j1, w.y, pivot);
    sum = dqs_add(sum, j2, w.z, pivot);
    sum = dqs_add(sum, j3, w.w, pivot);
    let len = length(sum.r);
    return Dq(sum.r / len, sum.d / len);
}

fn dqs_add(sum: Dq, j: Dq, weight: f32, pivot: vec4<f32>) -> Dq {
    var w = weight;
    if (dot(j.r, pivot) < 0.0) {
        w = -w;
    }
    return Dq(sum.r + j.r * w, sum.d + j.d * w);
}

// A vertex moved by the unit dual quaternion b: rotation, then the translation 2 d r*
// (its vector part); the normal turned by r.
fn rigid_move(b: Dq, p: vec3<f32>, n: vec3<f32>) -> Moved {
    let r = b.r;
    let d = b.d;
    let t = 2.0 * (r.x * d.yzw - d.x * r.yzw + cross(r.yzw, d.yzw));
    return Moved(rotate(r, p) + t, unit_or(rotate(r, n), n));
}
