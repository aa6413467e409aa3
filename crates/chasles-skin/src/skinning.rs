//! Skinning a posed rig with a rigid-transformation blend per vertex (Kavan et al. 2006, §6):
//! every vertex v with influences `(j, wⱼ)` moves by the blend B of its joints' transforms
//! `Cⱼ`, `v' = B v`.
//!
//! * [`Method::Lbs`] — linear blend skinning: `B = Σ wⱼ Cⱼ` (matrices); normals by the
//!   inverse transpose of the blended 3×3 (its cofactor matrix, renormalized).
//! * [`Method::Dqs`] — dual quaternion skinning: DLB with the antipodality fix against a
//!   pivot influence (the heaviest; Kavan's reference `dqsAntipod` takes the first), the
//!   point moved by the normalized blend, the normal rotated by its real part.
//! * [`Method::Dib`] — DIB per vertex (precision [`DIB_PRECISION`], at most
//!   [`DIB_UPDATES`] updates).
//! * [`Method::Log`] — Alexa's log-matrix blend per vertex; the joints' logarithms are
//!   computed once per pose.
//! * [`Method::Qlb`] — decomposed QLB about the joints (Hejl 2004): rotations by QLB,
//!   translations blended linearly about the weighted bind-pose joint centre of the vertex
//!   ([`crate::rotation_centre::joint_centres`]).
//! * [`Method::Sbs`] — spherical blend skinning (Kavan & Žára 2005): rotations by QLB about
//!   a *rotation centre* per cluster of vertices that share the same joints, solved once
//!   per pose by least squares ([`crate::rotation_centre`]).
//!
//! This is the reference path: plain per-vertex loops in f32, easy to check ([`crate::fast`]
//! is the fast one). Scaled joints
//! (non-rigid `Cⱼ`) are exact in LBS only; the other methods use the nearest rotation (see
//! [`crate::pose::joint_transforms`]).

use crate::error::{Result, SkinError};
use crate::pose::{joint_transforms, JointTransforms, Pose};
use crate::rig::Rig;
use crate::rotation_centre::{joint_centres, Clusters};
use chasles::blend::{dib::dib, log, qlb::qlb};
use chasles::{DualQuat, Mat3, Mat4, Quat, Vec3};

/// A skinning method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Linear blend skinning.
    Lbs,
    /// Dual quaternion skinning.
    Dqs,
    /// Dual quaternion iterative blending.
    Dib,
    /// Log-matrix blending (Alexa).
    Log,
    /// Decomposed quaternion linear blending about the joints (Hejl).
    Qlb,
    /// Spherical blend skinning (Kavan & Žára 2005).
    Sbs,
}

impl Method {
    /// All methods.
    pub const ALL: [Method; 6] = [
        Method::Lbs,
        Method::Dqs,
        Method::Dib,
        Method::Log,
        Method::Qlb,
        Method::Sbs,
    ];
    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Method::Lbs => "lbs",
            Method::Dqs => "dqs",
            Method::Dib => "dib",
            Method::Log => "log",
            Method::Qlb => "qlb",
            Method::Sbs => "sbs",
        }
    }
    /// The method of a command-line name.
    pub fn from_name(s: &str) -> Option<Method> {
        Method::ALL.into_iter().find(|m| m.name() == s)
    }
}

/// A deformed mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct Skinned {
    /// Deformed positions.
    pub positions: Vec<Vec3<f32>>,
    /// Deformed unit normals.
    pub normals: Vec<Vec3<f32>>,
}

/// The cofactor matrix of A (= det(A) · A⁻ᵀ): transforms normals, singular A included.
fn cofactor(a: &Mat3<f32>) -> Mat3<f32> {
    let m = &a.m;
    let c =
        |r0: usize, r1: usize, c0: usize, c1: usize| m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    Mat3::from_rows([
        [c(1, 2, 1, 2), -c(1, 2, 0, 2), c(1, 2, 0, 1)],
        [-c(0, 2, 1, 2), c(0, 2, 0, 2), -c(0, 2, 0, 1)],
        [c(0, 1, 1, 2), -c(0, 1, 0, 2), c(0, 1, 0, 1)],
    ])
}

fn unit(v: Vec3<f32>, fallback: Vec3<f32>) -> Vec3<f32> {
    v.normalize().unwrap_or(fallback)
}

/// Skins the rig in the pose with the method.
pub fn skin(rig: &Rig, pose: &Pose, method: Method) -> Result<Skinned> {
    skin_joints(rig, &joint_transforms(rig, pose)?, method)
}

/// Skins the rig with given joint transforms (e.g. [`JointTransforms::identity`], the
/// bind pose).
pub fn skin_joints(rig: &Rig, jt: &JointTransforms, method: Method) -> Result<Skinned> {
    if jt.matrices.len() != rig.joints.len() || jt.dual_quats.len() != rig.joints.len() {
        return Err(SkinError::Count {
            rig: rig.name.clone(),
            what: "joint transforms",
            expected: rig.joints.len(),
            got: jt.matrices.len().min(jt.dual_quats.len()),
        });
    }
    crate::reach::check_joints(&rig.name, &jt.matrices, Some(&jt.dual_quats))?;
    let n = rig.mesh.positions.len();
    let mut positions = Vec::with_capacity(n);
    let mut normals = Vec::with_capacity(n);
    let twists = if method == Method::Log {
        twists(jt)?
    } else {
        Vec::new()
    };
    // Bind-pose joint centres (for the decomposed QLB), and the SBS clusters' rotation
    // centres for this pose.
    let centres = joint_centres(&rig.inverse_bind);
    let (clusters, rotation_centres) = if method == Method::Sbs {
        let c = Clusters::new(n, |v| rig.influences.of(v).map(|(j, _)| j as u16));
        let r = c.centres(&jt.dual_quats, &centres, false);
        (c, r)
    } else {
        (Clusters::default(), Vec::new())
    };
    for v in 0..n {
        let p = rig.mesh.positions[v];
        let nrm = rig.mesh.normals[v];
        match method {
            Method::Lbs => {
                let mut m = Mat4::from_rows([[0.0f32; 4]; 4]);
                for (j, w) in rig.influences.of(v) {
                    for r in 0..3 {
                        for c in 0..4 {
                            m.m[r][c] += jt.matrices[j].m[r][c] * w;
                        }
                    }
                }
                positions.push(m.transform_point(p));
                normals.push(unit(cofactor(&m.linear_part()).mul_vec(nrm), nrm));
            }
            Method::Dqs => {
                let (pivot, _) = rig
                    .influences
                    .of(v)
                    .fold(
                        (0usize, -1.0f32),
                        |best, (j, w)| if w > best.1 { (j, w) } else { best },
                    );
                let pr = jt.dual_quats[pivot].real;
                let mut b = DualQuat::new(Quat::zero(), Quat::zero());
                for (j, w) in rig.influences.of(v) {
                    let d = jt.dual_quats[j];
                    let s = if d.real.dot(pr) < 0.0 { -w } else { w };
                    b = b + d * s;
                }
                let (p, n) = dual_quat_vertex(&b.normalize()?, p, nrm);
                positions.push(p);
                normals.push(n);
            }
            Method::Dib | Method::Qlb | Method::Sbs => {
                let (q, w): (Vec<DualQuat<f32>>, Vec<f32>) = rig
                    .influences
                    .of(v)
                    .map(|(j, w)| (jt.dual_quats[j], w))
                    .unzip();
                let b = match method {
                    Method::Dib => dib(&q, &w, DIB_PRECISION, DIB_UPDATES)?.0,
                    Method::Qlb => qlb(
                        &q,
                        &w,
                        weighted_centre(rig.influences.of(v), |j| centres[j]),
                    )?,
                    _ => qlb(&q, &w, rotation_centres[clusters.of_vertex()[v] as usize])?,
                };
                let (p, n) = dual_quat_vertex(&b, p, nrm);
                positions.push(p);
                normals.push(n);
            }
            Method::Log => {
                let mut x = log::Twist {
                    w: Vec3::zero(),
                    v: Vec3::zero(),
                };
                for (j, w) in rig.influences.of(v) {
                    x.w += twists[j].w * w;
                    x.v += twists[j].v * w;
                }
                let (p, n) = exp_twist_vertex(&x, p, nrm);
                positions.push(p);
                normals.push(n);
            }
        }
    }
    // The rule every path (reference, fast, GPU) keeps: a vertex whose position or normal
    // is not finite is an error naming it.
    if let Some(vertex) = positions
        .iter()
        .zip(&normals)
        .position(|(p, n)| !p.is_finite() || !n.is_finite())
    {
        return Err(SkinError::NonFiniteOutput {
            rig: rig.name.clone(),
            method: method.name(),
            vertex,
        });
    }
    Ok(Skinned { positions, normals })
}

/// The joints' twists for Log skinning: `log` of each joint matrix's nearest rigid
/// transform (a scaled or sheared joint is made rigid first).
pub fn twists(jt: &JointTransforms) -> Result<Vec<log::Twist<f32>>> {
    twists_of(&jt.matrices)
}

/// [`twists`] of skinning matrices.
pub fn twists_of(matrices: &[Mat4<f32>]) -> Result<Vec<log::Twist<f32>>> {
    matrices.iter().map(twist_of).collect()
}

/// One skinning matrix's twist: `log` of its nearest rigid transform. `log_rigid` takes
/// the rotation from the 3×3 block as the normalized quaternion of Shepperd's method (for a
/// scaled or sheared joint, a nearby rotation), so the matrix goes in as it is: remaking it
/// rigid first, with that rotation, only took the quaternion twice (Log's palette for
/// RiggedFigure's 19 joints: 4.4 → 3.3 µs a pose, `examples/pose_cost`, the two builds in
/// turn).
pub fn twist_of(m: &Mat4<f32>) -> Result<log::Twist<f32>> {
    log::log_rigid(m).map_err(Into::into)
}

/// A vertex moved by `exp(x)`, `x` its blended twist: the position, and the normal turned
/// and made unit (itself where that fails). Log skinning's last step, on both paths.
pub(crate) fn exp_twist_vertex(
    x: &log::Twist<f32>,
    p: Vec3<f32>,
    n: Vec3<f32>,
) -> (Vec3<f32>, Vec3<f32>) {
    let m = log::exp_twist(x);
    (m.transform_point(p), unit(m.linear_part().mul_vec(n), n))
}

/// DIB skinning's precision and most updates per vertex, on both CPU paths and on the GPU
/// (set as the shader's override constants: `gpu/skin.wgsl` writes no number of its own).
pub const DIB_PRECISION: f32 = 1e-5;
/// See [`DIB_PRECISION`].
pub const DIB_UPDATES: usize = 8;

/// `Σ wⱼ cⱼ` over a vertex's influences: the centre decomposed QLB rotates it about (both
/// paths sum in the influences' order).
pub(crate) fn weighted_centre(
    influences: impl Iterator<Item = (usize, f32)>,
    centre: impl Fn(usize) -> Vec3<f32>,
) -> Vec3<f32> {
    influences.fold(Vec3::zero(), |c, (j, w)| c + centre(j) * w)
}

/// A vertex moved by a unit dual quaternion: the position, and the normal rotated by the
/// real part and made unit (itself where that fails). The last step of DQS, DIB, QLB and
/// SBS, on both paths.
pub(crate) fn dual_quat_vertex(
    b: &DualQuat<f32>,
    p: Vec3<f32>,
    n: Vec3<f32>,
) -> (Vec3<f32>, Vec3<f32>) {
    (b.transform_point(p), unit(b.real.rotate(n), n))
}
