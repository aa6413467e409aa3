//! Skinning as careful users of glam and nalgebra write it: the baselines our fast paths
//! ([`crate::fast`], Kavan et al. 2006 §6) are measured against, in one place for the
//! benchmarks, `chasles skin --bench` and the test that checks each against an f64
//! reference (`tests/peers.rs`, on a single-influence mesh).
//!
//! * LBS with glam: the weighted sum of the joints' `Mat3A` blocks and `Vec3A`
//!   translations (SIMD columns), the point by the blended matrix; the normal either by the
//!   blended matrix itself (what most engines ship: exact for rotations and uniform scale)
//!   or by its cofactor matrix (the inverse transpose up to a positive factor, exact under
//!   any scale), then normalized.
//! * DQS with glam: the joints' dual quaternions as pairs of `Vec4`, blended with the sign
//!   fix against the first joint (Kavan et al. 2006, §5.1) — branch-free, each weight
//!   given the sign of its joint's dot product with the pivot's (an `if` there mispredicts
//!   on far-apart rotations: 43 against 70 M vertices/s at 2·10⁵ vertices with uniform
//!   rotations, measured by an independent harness) — one reciprocal of ‖real‖ for
//!   both parts, and the standard fast transform `p + 2 r⃗ × (r⃗ × p + w p) + 2 (w t⃗ − t_w r⃗ +
//!   r⃗ × t⃗)` with `(w, r⃗)` the real part and `(t_w, t⃗)` the dual part.
//! * DQS and LBS with nalgebra as its documentation has users call it:
//!   `UnitDualQuaternion::new_normalize` of the sum and `transform_point` /
//!   `transform_vector`; `Matrix4` sums, `transform_point`, normals by
//!   `try_inverse().transpose()`.
use crate::fast::{Out, Vertex};
use glam::{Mat3A, Vec3A, Vec4};

mod rounds;
pub use rounds::{
    cache_notes, last_level_cache, markdown, measure, measure_posed, measure_rig, order, repeats,
    Load, Role, Rotations, Row, Spread, Table, SYNTHETIC, SYNTHETIC_UNIFORM, TRAFFIC,
    UNGROUPED_DIB,
};

/// Every baseline's joints for one pose.
pub struct Joints {
    /// glam LBS's.
    pub glam: Vec<GlamJoint>,
    /// glam DQS's.
    pub glam_dq: Vec<(Vec4, Vec4)>,
    /// nalgebra LBS's.
    pub nalgebra: Vec<nalgebra::Matrix4<f32>>,
    /// nalgebra DQS's.
    pub nalgebra_dq: Vec<nalgebra::UnitDualQuaternion<f32>>,
}

impl Joints {
    /// The joints of `jt` in every baseline's form.
    pub fn of(jt: &crate::JointTransforms) -> Self {
        Joints {
            glam: glam_joints(jt),
            glam_dq: glam_dual_quats(jt),
            nalgebra: nalgebra_matrices(jt),
            nalgebra_dq: nalgebra_dual_quats(jt),
        }
    }
}

/// A baseline: its name and the whole-mesh kernel on one thread.
pub type Baseline = (&'static str, fn(&[Vertex<4>], &Joints, &mut [Out]));

/// Every baseline, the LBS ones first (their names say which method each is).
pub const BASELINES: [Baseline; 5] = [
    ("glam lbs, normals by M", |v, j, o| {
        glam_lbs_by_m(v, &j.glam, o)
    }),
    ("glam lbs, cofactor normals", |v, j, o| {
        glam_lbs_cofactor(v, &j.glam, o)
    }),
    ("nalgebra lbs", |v, j, o| nalgebra_lbs(v, &j.nalgebra, o)),
    ("glam dqs (Vec4, careful)", |v, j, o| {
        glam_dqs(v, &j.glam_dq, o)
    }),
    ("nalgebra dqs", |v, j, o| nalgebra_dqs(v, &j.nalgebra_dq, o)),
];

/// The bandwidth bound: `src` copied into `dst`, `half` bytes a vertex read and as many
/// written — half the bytes each skinned vertex moves: with four influences 36 + 36 for
/// its 48 read and 24 written, with eight 48 + 48 for 72 and 24 — on one thread or on
/// all in chunks of 4096 vertices (as the fast paths' are, about: theirs start where a
/// streamed output is aligned).
pub fn copy_bound(src: &[u8], dst: &mut [u8], half: usize, parallel: bool) {
    use rayon::prelude::*;
    let src = std::hint::black_box(src);
    let chunk = 4096 * half.max(1);
    if parallel {
        dst.par_chunks_mut(chunk)
            .zip(src.par_chunks(chunk))
            .for_each(|(d, s)| d.copy_from_slice(s));
    } else {
        dst.copy_from_slice(src);
    }
}

/// `f` over the mesh `v` and its output on one thread, or on all in chunks of 4096 vertices
/// (as the fast paths' are, about).
pub fn run(
    v: &[Vertex<4>],
    out: &mut [Out],
    parallel: bool,
    f: &(dyn Fn(&[Vertex<4>], &mut [Out]) + Sync),
) {
    use rayon::prelude::*;
    if parallel {
        out.par_chunks_mut(4096)
            .zip(v.par_chunks(4096))
            .for_each(|(o, v)| f(v, o));
    } else {
        f(v, out)
    }
}

/// A joint for the glam LBS baselines: the 3×3 block as SIMD columns and the translation.
#[derive(Clone, Copy)]
pub struct GlamJoint {
    /// The 3×3 block.
    pub m: Mat3A,
    /// The translation.
    pub t: Vec3A,
}

/// The joints of `jt` for glam's LBS.
pub fn glam_joints(jt: &crate::JointTransforms) -> Vec<GlamJoint> {
    jt.matrices
        .iter()
        .map(|m| GlamJoint {
            m: Mat3A::from_cols(
                Vec3A::new(m.m[0][0], m.m[1][0], m.m[2][0]),
                Vec3A::new(m.m[0][1], m.m[1][1], m.m[2][1]),
                Vec3A::new(m.m[0][2], m.m[1][2], m.m[2][2]),
            ),
            t: Vec3A::new(m.m[0][3], m.m[1][3], m.m[2][3]),
        })
        .collect()
}

/// The blended block and translation of `v`.
#[inline(always)]
fn glam_blend(v: &Vertex<4>, m: &[GlamJoint]) -> (Mat3A, Vec3A) {
    let j0 = &m[usize::from(v.j[0])];
    let (mut a, mut t) = (j0.m * v.w[0], j0.t * v.w[0]);
    for k in 1..4 {
        let j = &m[usize::from(v.j[k])];
        a += j.m * v.w[k];
        t += j.t * v.w[k];
    }
    (a, t)
}

/// LBS with glam, normals by the blended matrix.
pub fn glam_lbs_by_m(v: &[Vertex<4>], m: &[GlamJoint], out: &mut [Out]) {
    for (o, v) in out.iter_mut().zip(v) {
        let (a, t) = glam_blend(v, m);
        let p = a * Vec3A::from_array(v.p) + t;
        let n = (a * Vec3A::from_array(v.n)).normalize_or_zero();
        *o = [p.x, p.y, p.z, n.x, n.y, n.z];
    }
}

/// LBS with glam, normals by the blended matrix's cofactor matrix (columns `c₁ × c₂`,
/// `c₂ × c₀`, `c₀ × c₁`).
pub fn glam_lbs_cofactor(v: &[Vertex<4>], m: &[GlamJoint], out: &mut [Out]) {
    for (o, v) in out.iter_mut().zip(v) {
        let (a, t) = glam_blend(v, m);
        let p = a * Vec3A::from_array(v.p) + t;
        let cof = Mat3A::from_cols(
            a.y_axis.cross(a.z_axis),
            a.z_axis.cross(a.x_axis),
            a.x_axis.cross(a.y_axis),
        );
        let n = (cof * Vec3A::from_array(v.n)).normalize_or_zero();
        *o = [p.x, p.y, p.z, n.x, n.y, n.z];
    }
}

/// The joints of `jt` for glam's DQS: (real, dual) as `Vec4` (x, y, z, w).
pub fn glam_dual_quats(jt: &crate::JointTransforms) -> Vec<(Vec4, Vec4)> {
    jt.dual_quats
        .iter()
        .map(|d| {
            (
                Vec4::new(d.real.x, d.real.y, d.real.z, d.real.w),
                Vec4::new(d.dual.x, d.dual.y, d.dual.z, d.dual.w),
            )
        })
        .collect()
}

/// DQS with glam: `Vec4` sums with the sign fix, one reciprocal, the fast transform.
pub fn glam_dqs(v: &[Vertex<4>], d: &[(Vec4, Vec4)], out: &mut [Out]) {
    for (o, v) in out.iter_mut().zip(v) {
        let (pivot, _) = d[usize::from(v.j[0])];
        let (mut r, mut e) = (Vec4::ZERO, Vec4::ZERO);
        for k in 0..4 {
            let (qr, qe) = d[usize::from(v.j[k])];
            // Branch-free: a branch on the sign mispredicts half the time where the joints'
            // rotations are far apart (uniform ones), and cost this baseline 1.6× its time.
            let w = v.w[k].copysign(qr.dot(pivot));
            r += qr * w;
            e += qe * w;
        }
        let inv = r.length_recip();
        let (r, e) = (r * inv, e * inv);
        let (rv, rw) = (Vec3A::from_vec4(r), r.w);
        let (ev, ew) = (Vec3A::from_vec4(e), e.w);
        let turn = |x: Vec3A| x + 2.0 * rv.cross(rv.cross(x) + rw * x);
        let p = turn(Vec3A::from_array(v.p)) + 2.0 * (rw * ev - ew * rv + rv.cross(ev));
        let n = turn(Vec3A::from_array(v.n));
        *o = [p.x, p.y, p.z, n.x, n.y, n.z];
    }
}

/// The joints of `jt` as nalgebra's unit dual quaternions.
pub fn nalgebra_dual_quats(jt: &crate::JointTransforms) -> Vec<nalgebra::UnitDualQuaternion<f32>> {
    jt.dual_quats
        .iter()
        .map(|d| {
            nalgebra::UnitDualQuaternion::new_unchecked(
                nalgebra::DualQuaternion::from_real_and_dual(
                    nalgebra::Quaternion::new(d.real.w, d.real.x, d.real.y, d.real.z),
                    nalgebra::Quaternion::new(d.dual.w, d.dual.x, d.dual.y, d.dual.z),
                ),
            )
        })
        .collect()
}

/// DQS with nalgebra as users call it.
pub fn nalgebra_dqs(v: &[Vertex<4>], d: &[nalgebra::UnitDualQuaternion<f32>], out: &mut [Out]) {
    for (o, v) in out.iter_mut().zip(v) {
        let pivot = d[usize::from(v.j[0])];
        let mut sum = nalgebra::DualQuaternion::from_real_and_dual(
            nalgebra::Quaternion::new(0.0, 0.0, 0.0, 0.0),
            nalgebra::Quaternion::new(0.0, 0.0, 0.0, 0.0),
        );
        for k in 0..4 {
            let q = d[usize::from(v.j[k])];
            let w = if q.as_ref().real.dot(&pivot.as_ref().real) < 0.0 {
                -v.w[k]
            } else {
                v.w[k]
            };
            sum += q.into_inner() * w;
        }
        let b = nalgebra::UnitDualQuaternion::new_normalize(sum);
        let p = b.transform_point(&nalgebra::Point3::new(v.p[0], v.p[1], v.p[2]));
        let n = b.transform_vector(&nalgebra::Vector3::new(v.n[0], v.n[1], v.n[2]));
        *o = [p.x, p.y, p.z, n.x, n.y, n.z];
    }
}

/// The joints of `jt` as nalgebra's 4×4 matrices.
pub fn nalgebra_matrices(jt: &crate::JointTransforms) -> Vec<nalgebra::Matrix4<f32>> {
    jt.matrices
        .iter()
        .map(|m| nalgebra::Matrix4::from_fn(|r, c| m.m[r][c]))
        .collect()
}

/// LBS with nalgebra as users call it: `Matrix4` sums, `transform_point`, normals by the
/// inverse transpose of the blended 3×3 block.
pub fn nalgebra_lbs(v: &[Vertex<4>], m: &[nalgebra::Matrix4<f32>], out: &mut [Out]) {
    for (o, v) in out.iter_mut().zip(v) {
        let mut a = m[usize::from(v.j[0])] * v.w[0];
        for k in 1..4 {
            a += m[usize::from(v.j[k])] * v.w[k];
        }
        let p = a.transform_point(&nalgebra::Point3::new(v.p[0], v.p[1], v.p[2]));
        let block = a.fixed_view::<3, 3>(0, 0).into_owned();
        let nt = block.try_inverse().map_or(block, |i| i.transpose())
            * nalgebra::Vector3::new(v.n[0], v.n[1], v.n[2]);
        let n = nt.try_normalize(0.0).unwrap_or(nt);
        *o = [p.x, p.y, p.z, n.x, n.y, n.z];
    }
}
