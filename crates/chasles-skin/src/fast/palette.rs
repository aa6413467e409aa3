//! Palettes: per method, exactly what its kernel reads of each joint for one pose — Kavan
//! et al. 2006, §6's "list L of joint displacements", in the form each blend needs (the
//! register saving they note: 8 floats a dual quaternion against 12 a matrix). Each entry is
//! a named `#[repr(C)]` type that can be handed to a GPU or an engine as it is
//! (`bytemuck::Pod`):
//!
//! * LBS: [`Affine3x4`], `C_j`'s top three rows;
//! * DQS and DIB: [`UnitDualQuat`], `C_j` as a unit dual quaternion (eq. 1; its nearest
//!   rotation where `C_j` scales);
//! * Log: [`Twist`], the logarithm of `C_j`'s nearest rigid motion (§5.1);
//! * QLB and SBS: [`QlbJoint`], rotation quaternion, rigid `[R | t]` and bind origin; SBS also
//!   one [`RotationCentre`] per vertex cluster (Kavan & Žára 2005), solved for the pose.
//!
//! A [`Palette`] is made from a pose's skinning matrices (or a [`JointTransforms`]) without
//! building what its method does not read, and [`Palette::update`] refills one in place, so
//! a clip played frame after frame allocates nothing once the first frame has sized it.

use super::antipodes::Antipodes;
use super::log::row as twist_row;
use super::qlb::row as qlb_row;
use super::{simd, FastRig};
use crate::error::{same_count, Result, FAST_RIG};
use crate::pose::{rigid_of, JointTransforms};
use crate::skinning::{twist_of, Method};
use bytemuck::{Pod, Zeroable};
use chasles::{DualQuat, Mat4, Vec3};

/// `C_j`'s top three rows, row-major: `[r00 r01 r02 t0; r10 r11 r12 t1; r20 r21 r22 t2]`.
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct Affine3x4 {
    /// The rows.
    pub rows: [[f32; 4]; 3],
}

/// A unit dual quaternion `q0 + ε qε`, as 8 floats `[w, x, y, z, wε, xε, yε, zε]`.
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct UnitDualQuat {
    /// `q0 = [w, x, y, z]`, the rotation.
    pub real: [f32; 4],
    /// `qε = ½ t q0`.
    pub dual: [f32; 4],
}

/// A rigid motion's logarithm `(ω, v)` (rotation vector and the translation's twist), padded
/// to 8 floats.
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct Twist {
    /// ω, the rotation vector.
    pub omega: [f32; 3],
    /// v.
    pub v: [f32; 3],
    /// Zeros (two floats, so that a twist is one 8-float register).
    pub pad: [f32; 2],
}

/// A joint for decomposed QLB and SBS: its rotation `[w, x, y, z]`, the rows of its rigid
/// `[R | t]`, its bind origin, then zeros (three 8-float registers).
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct QlbJoint {
    /// The rotation quaternion.
    pub rotation: [f32; 4],
    /// `[R | t]`, row-major.
    pub rigid: [[f32; 4]; 3],
    /// The joint's origin in the bind pose.
    pub origin: [f32; 3],
    /// Zeros.
    pub pad: [f32; 5],
}

/// A vertex cluster's centre of rotation for SBS, padded to 4 floats (16 bytes: a table of
/// one per cluster is gathered from at random on a rig of many clusters, so it is kept small).
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct RotationCentre {
    /// The centre.
    pub centre: [f32; 3],
    /// Zero.
    pub pad: f32,
}

/// One pose's joint data for one skinning method, entry by entry.
#[derive(Debug, Clone, PartialEq)]
pub enum Joints {
    /// Linear blend skinning.
    Lbs(Vec<Affine3x4>),
    /// Dual quaternion skinning.
    Dqs(Vec<UnitDualQuat>),
    /// Dual quaternion iterative blending.
    Dib(Vec<UnitDualQuat>),
    /// Log-matrix skinning.
    Log(Vec<Twist>),
    /// Decomposed quaternion linear blending about the joints.
    Qlb(Vec<QlbJoint>),
    /// Spherical blend skinning: the joints and each vertex cluster's centre of rotation
    /// (the clusters of [`FastRig::clusters`]).
    Sbs {
        /// The joints.
        joints: Vec<QlbJoint>,
        /// One centre per cluster.
        centres: Vec<RotationCentre>,
    },
}

impl Joints {
    /// An empty list for `method`.
    pub fn new(method: Method) -> Self {
        match method {
            Method::Lbs => Joints::Lbs(Vec::new()),
            Method::Dqs => Joints::Dqs(Vec::new()),
            Method::Dib => Joints::Dib(Vec::new()),
            Method::Log => Joints::Log(Vec::new()),
            Method::Qlb => Joints::Qlb(Vec::new()),
            Method::Sbs => Joints::Sbs {
                joints: Vec::new(),
                centres: Vec::new(),
            },
        }
    }

    /// The method they are for.
    pub fn method(&self) -> Method {
        match self {
            Joints::Lbs(_) => Method::Lbs,
            Joints::Dqs(_) => Method::Dqs,
            Joints::Dib(_) => Method::Dib,
            Joints::Log(_) => Method::Log,
            Joints::Qlb(_) => Method::Qlb,
            Joints::Sbs { .. } => Method::Sbs,
        }
    }

    /// How many joints.
    pub fn len(&self) -> usize {
        match self {
            Joints::Lbs(a) => a.len(),
            Joints::Dqs(d) | Joints::Dib(d) => d.len(),
            Joints::Log(t) => t.len(),
            Joints::Qlb(j) | Joints::Sbs { joints: j, .. } => j.len(),
        }
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A pose's [`Joints`] for one method, with what its kernel derives from them once per
/// pose (the antipodality table against each pivot joint: the signed copies of DQS's dual
/// quaternions, or of QLB's and SBS's rows).
#[derive(Debug, Clone, PartialEq)]
pub struct Palette {
    joints: Joints,
    antipodes: Antipodes,
}

impl Palette {
    /// An empty palette for `method`, to be filled by [`Palette::update`].
    pub fn new(method: Method) -> Self {
        Palette {
            joints: Joints::new(method),
            antipodes: Antipodes::default(),
        }
    }

    /// A palette from joint data made elsewhere (an engine's own matrices or dual
    /// quaternions): checked against `rig`'s joint count (and, for SBS, its cluster count).
    /// DIB's joints off unit length by more than rounding are normalized, as
    /// [`Palette::update`] does (its SIMD kernels' logarithm takes them as unit).
    pub fn from_joints<const K: usize>(rig: &FastRig<K>, mut joints: Joints) -> Result<Self> {
        check(rig, joints.len())?;
        // The range every path keeps finite (crate::reach), on the data as laid out.
        let laid_out = |what: &str, floats: &[f32], per: usize, linear: &[usize]| {
            crate::reach::check_laid_out(FAST_RIG, what, floats, per, linear)
        };
        match &joints {
            Joints::Lbs(j) => laid_out(
                "LBS joint",
                bytemuck::cast_slice(j),
                12,
                &[0, 1, 2, 4, 5, 6, 8, 9, 10],
            )?,
            Joints::Dqs(j) | Joints::Dib(j) => {
                laid_out("dual-quaternion joint", bytemuck::cast_slice(j), 8, &[])?
            }
            Joints::Log(j) => laid_out(
                "twist",
                bytemuck::cast_slice(j),
                std::mem::size_of::<Twist>() / 4,
                &[],
            )?,
            Joints::Qlb(j) => laid_out(
                "QLB joint",
                bytemuck::cast_slice(j),
                std::mem::size_of::<QlbJoint>() / 4,
                &[],
            )?,
            Joints::Sbs { joints, centres } => {
                laid_out(
                    "SBS joint",
                    bytemuck::cast_slice(joints),
                    std::mem::size_of::<QlbJoint>() / 4,
                    &[],
                )?;
                laid_out(
                    "rotation centre",
                    bytemuck::cast_slice(centres),
                    std::mem::size_of::<RotationCentre>() / 4,
                    &[],
                )?;
            }
        }
        if let Joints::Dib(j) = &mut joints {
            for x in j.iter_mut() {
                *x = dib_unit(&DualQuat::from_array(bytemuck::cast(*x)));
            }
        }
        if let Joints::Sbs { centres, .. } = &joints {
            same_count(
                FAST_RIG,
                "rotation centres",
                rig.clusters().len(),
                centres.len(),
            )?;
        }
        let mut p = Palette {
            joints,
            antipodes: Antipodes::default(),
        };
        p.tabulate(rig);
        Ok(p)
    }

    /// The joint data.
    pub fn data(&self) -> &Joints {
        &self.joints
    }

    /// The method this palette is for.
    pub fn method(&self) -> Method {
        self.joints.method()
    }

    /// How many joints it holds.
    pub fn joints(&self) -> usize {
        self.joints.len()
    }

    /// The antipodality table the SIMD kernels read (empty where it would not pay).
    pub(super) fn antipodes(&self) -> &Antipodes {
        &self.antipodes
    }

    /// Remakes the antipodality table for the joints now held (DQS's copies of the dual
    /// quaternions, QLB's and SBS's of the rows, on the SIMD path).
    fn tabulate<const K: usize>(&mut self, rig: &FastRig<K>) {
        let n = if simd(K) { rig.vertices().len() } else { 0 };
        match &self.joints {
            Joints::Dqs(d) => self.antipodes.refill_copies(bytemuck::cast_slice(d), n),
            Joints::Qlb(j) | Joints::Sbs { joints: j, .. } => {
                self.antipodes.refill_rows(bytemuck::cast_slice(j), n)
            }
            _ => self.antipodes.refill_copies(&[], 0),
        }
    }

    /// `method`'s palette for `rig` from skinning matrices `C_j` (one per joint; see
    /// [`crate::pose::skinning_matrices`]); SBS's centres are solved on all threads when
    /// `parallel`.
    pub fn from_matrices<const K: usize>(
        method: Method,
        rig: &FastRig<K>,
        matrices: &[Mat4<f32>],
        parallel: bool,
    ) -> Result<Self> {
        let mut p = Palette::new(method);
        p.update(rig, matrices, parallel)?;
        Ok(p)
    }

    /// `method`'s palette for `rig` from joint transforms that hold both forms already
    /// (the dual quaternions are used as they are, not made again from the matrices).
    pub fn from_joint_transforms<const K: usize>(
        method: Method,
        rig: &FastRig<K>,
        jt: &JointTransforms,
        parallel: bool,
    ) -> Result<Self> {
        check(rig, jt.dual_quats.len())?;
        let mut p = Palette::new(method);
        p.fill(rig, &jt.matrices, Some(&jt.dual_quats), parallel)?;
        Ok(p)
    }

    /// Refills this palette, in place, from skinning matrices `C_j` of `rig`'s joints:
    /// only what its method reads is made (no dual quaternions for LBS, no matrices kept
    /// for the others), into vectors whose capacity is reused from the last pose — no
    /// allocation once the first pose has sized them, except SBS's centre solve (the
    /// joints' dual quaternions and per-joint sums, some kilobytes; on the first pose, each
    /// cluster's prior, 12 bytes a cluster, kept by the rig's clusters). SBS's centres are
    /// solved on all threads when `parallel`. On an error the palette is left empty (no job
    /// takes it) rather than half filled.
    pub fn update<const K: usize>(
        &mut self,
        rig: &FastRig<K>,
        matrices: &[Mat4<f32>],
        parallel: bool,
    ) -> Result<()> {
        self.fill(rig, matrices, None, parallel)
    }

    /// [`Palette::update`], with the joints' dual quaternions taken from `given` where the
    /// caller has them (one per matrix) instead of made from the matrices.
    fn fill<const K: usize>(
        &mut self,
        rig: &FastRig<K>,
        matrices: &[Mat4<f32>],
        given: Option<&[DualQuat<f32>]>,
        parallel: bool,
    ) -> Result<()> {
        check(rig, matrices.len())?;
        crate::reach::check_joints(FAST_RIG, matrices, given)?;
        let centres = rig.centres();
        let dual = |i: usize| given.map_or_else(|| rigid_of(&matrices[i]).0, |d| d[i]);
        let n = matrices.len();
        match &mut self.joints {
            Joints::Lbs(a) => refill(a, matrices.iter().map(affine)),
            Joints::Dqs(d) => refill(d, (0..n).map(|i| unit(&dual(i)))),
            Joints::Dib(d) => refill(d, (0..n).map(|i| dib_unit(&dual(i)))),
            Joints::Log(t) => {
                t.clear();
                for m in matrices {
                    match twist_of(m) {
                        Ok(x) => t.push(bytemuck::cast(twist_row(&x))),
                        Err(e) => {
                            t.clear(); // an empty palette, which no job takes
                            return Err(e);
                        }
                    }
                }
            }
            Joints::Qlb(j) => refill(j, (0..n).map(|i| qlb_joint(&dual(i), centres[i]))),
            Joints::Sbs { joints, centres: c } => {
                let made: Vec<DualQuat<f32>>;
                let d = match given {
                    Some(d) => d,
                    None => {
                        made = (0..n).map(dual).collect();
                        &made
                    }
                };
                refill(joints, d.iter().zip(centres).map(|(d, c)| qlb_joint(d, *c)));
                // Every entry written once, with no zeros first (`centres_vec`): the zeros of a
                // fresh palette's 2.4 MB of centres at 2·10⁵ synthetic vertices cost 30–70 µs
                // back to back, within the noise of a whole pose, but about 220 in `chasles
                // skin --bench`'s rounds once the solve asked for its tables ahead
                // (`rotation_centre`'s module docs; 2026-12-05).
                rig.clusters().centres_vec(d, centres, parallel, c);
            }
        }
        self.tabulate(rig);
        Ok(())
    }
}

/// `v` emptied and filled from `items`, keeping its capacity.
fn refill<T>(v: &mut Vec<T>, items: impl Iterator<Item = T>) {
    v.clear();
    v.extend(items);
}

/// The joint count `rig` needs.
fn check<const K: usize>(rig: &FastRig<K>, joints: usize) -> Result<()> {
    same_count(FAST_RIG, "joint transforms", rig.joints(), joints)
}

/// `C_j`'s top three rows: LBS's joint.
pub(crate) fn affine(m: &Mat4<f32>) -> Affine3x4 {
    Affine3x4 {
        rows: [m.m[0], m.m[1], m.m[2]],
    }
}

/// A dual quaternion as DQS's and DIB's joint.
pub(crate) fn unit(d: &DualQuat<f32>) -> UnitDualQuat {
    bytemuck::cast(d.to_array())
}

/// How far from 1 the squared length of a joint's rotation part may be for DIB to take it
/// as it is: a few times f32's rounding of a normalized quaternion.
const DIB_UNIT_SLACK: f32 = 1e-6;

/// A dual quaternion as DIB's joint, of unit length as the SIMD kernels' logarithm needs it
/// (`fast::lane::dib`: it takes ‖b̂* q̂ᵢ‖ as 1). A joint off unit length by more than
/// rounding — a `JointTransforms` made by hand — is normalized (DIB blends rigid motions,
/// whatever their scale); a unit one, as `joint_transforms` makes it, is kept bit for bit,
/// and one that cannot be normalized (zero, non-finite) as it is, for the kernels to
/// refuse.
pub(crate) fn dib_unit(d: &DualQuat<f32>) -> UnitDualQuat {
    if (d.real.norm_squared() - 1.0).abs() <= DIB_UNIT_SLACK {
        unit(d)
    } else {
        unit(&d.normalize().unwrap_or(*d))
    }
}

/// A joint's rigid motion `d` and bind origin `c` as QLB's and SBS's joint.
fn qlb_joint(d: &DualQuat<f32>, c: Vec3<f32>) -> QlbJoint {
    bytemuck::cast(qlb_row(d, c))
}
