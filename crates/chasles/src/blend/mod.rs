//! Blending of rigid transformations with convex weights (Kavan et al. 2006, §2–5 and
//! Appendices A–B): [`lin`], [`dec`] (with the spherical average of [`mean`]), [`qlb`],
//! [`log`] (Alexa's log-matrix blend and its iterative version), [`sclerp`], [`dlb`],
//! [`dib`]; and past the paper's blends (its §7), [`average`]: the rigid mean of measured
//! poses (DIB's fixed point, weighted) and a robust mean that ignores outliers.
//!
//! [`blend_matrices`] and [`blend_dual_quats`] run any [`Method`] on 4×4 rigid matrices or
//! unit dual quaternions; the weights go through [`weights::convex_weights`] (typed errors
//! for negative, non-finite or non-positive-sum weights; scaled to sum to 1).

pub mod average;
pub mod dec;
pub mod dib;
pub mod dlb;
pub mod lin;
pub mod log;
pub mod mean;
pub mod qlb;
pub mod sclerp;
pub mod weights;

use crate::{DualQuat, Error, Mat4, Real, Result, Vec3};

/// A blending method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Linear combination of matrices.
    Lin,
    /// Decomposition: spherical average of rotations, linear translations (about a centre).
    Dec,
    /// Alexa's log-matrix blending.
    Log,
    /// The iterative log-matrix blending of §5.
    LogIter,
    /// Quaternion linear blending of rotations, linear translations (about a centre).
    Qlb,
    /// Screw linear interpolation (two transforms).
    ScLerp,
    /// Dual quaternion linear blending.
    Dlb,
    /// Dual quaternion iterative blending.
    Dib,
}

impl Method {
    /// All methods, in the order of the paper's Table 1 (with QLB and iterative Log added).
    pub const ALL: [Method; 8] = [
        Method::Lin,
        Method::Dec,
        Method::Log,
        Method::LogIter,
        Method::Qlb,
        Method::ScLerp,
        Method::Dlb,
        Method::Dib,
    ];
    /// The command-line name: lin, dec, log, log-iter, qlb, sclerp, dlb, dib.
    pub fn name(self) -> &'static str {
        match self {
            Method::Lin => "lin",
            Method::Dec => "dec",
            Method::Log => "log",
            Method::LogIter => "log-iter",
            Method::Qlb => "qlb",
            Method::ScLerp => "sclerp",
            Method::Dlb => "dlb",
            Method::Dib => "dib",
        }
    }
    /// The method of a command-line name.
    pub fn from_name(s: &str) -> Option<Method> {
        Method::ALL.into_iter().find(|m| m.name() == s)
    }
    /// Whether the method iterates (and reports its iteration count).
    pub fn iterates(self) -> bool {
        matches!(self, Method::Dec | Method::LogIter | Method::Dib)
    }
}

/// Settings of the iterative methods and the decompositions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options<T> {
    /// Stop when the update is smaller than this (DIB, iterative Log, the spherical average).
    pub precision: T,
    /// At most this many updates.
    pub max_iterations: usize,
    /// The centre of the decomposition for Dec and QLB.
    pub center: Vec3<T>,
}

/// An iteration whose update no longer shrinks while within this factor of the precision
/// stops: rounding, not the blend, is setting the update then. The CPU kernels and the GPU
/// shader (as a WGSL override constant) read this one value.
pub const STALL_FACTOR: f64 = 100.0;

/// `norm`, the size of an iteration's update, if it is finite; else the error naming the
/// update (`what`): an update that overflowed (inputs near the top of T's range, whose
/// squares are not finite) is an error, never a silent stop at the start value.
pub(crate) fn finite_update<T: Real>(norm: T, what: &'static str) -> Result<T> {
    if norm.is_finite() {
        Ok(norm)
    } else {
        Err(Error::NonFinite { what })
    }
}

/// Whether an iteration should go on: the update `norm` is still above `precision`, and
/// not stuck near it (no smaller than the `last` while within [`STALL_FACTOR`] × the
/// precision, or within 16 ε, where rounding sets every update: a precision asked for
/// below what T resolves, 5e-324 say, stops there instead of running all its iterations).
pub(crate) fn keep_going<T: Real>(norm: T, last: T, precision: T) -> bool {
    let converged = norm < precision;
    let zone = (precision * T::from_f64(STALL_FACTOR)).max(T::EPSILON * T::from_f64(16.0));
    let stuck = norm >= last && norm < zone;
    !converged && !stuck && norm.is_finite()
}

impl<T: Real> Default for Options<T> {
    /// Precision `max(√ε/100, 100ε)` (1.5e-10 in f64, 1.2e-5 in f32), 50 iterations, the
    /// origin as centre.
    fn default() -> Self {
        Self {
            precision: (T::EPSILON.sqrt() * T::from_f64(1e-2)).max(T::EPSILON * T::from_f64(100.0)),
            max_iterations: 50,
            center: Vec3::zero(),
        }
    }
}

/// A blended transformation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Blended<T> {
    /// The result as a 4×4 matrix (for Lin, possibly not rigid).
    pub matrix: Mat4<T>,
    /// The result as a unit dual quaternion (for a non-rigid Lin result: of its nearest
    /// rotation and its translation).
    pub dq: DualQuat<T>,
    /// Whether `matrix` is rigid (within [`crate::default_tolerance`]).
    pub rigid: bool,
    /// Updates made, for the iterative methods.
    pub iterations: Option<usize>,
}

fn rigid_result<T: Real>(dq: DualQuat<T>, iterations: Option<usize>) -> Blended<T> {
    Blended {
        matrix: dq.to_matrix4(),
        dq,
        rigid: true,
        iterations,
    }
}

fn sclerp_parameter<T: Real>(n: usize, w: &[T]) -> Result<T> {
    if n != 2 {
        return Err(Error::BlendInput {
            what: format!("ScLERP blends exactly two transforms, got {n}"),
        });
    }
    let w = weights::convex_weights(w, 2)?;
    Ok(w[1])
}

/// Checks that every matrix is rigid (a typed error naming the first that is not).
pub fn check_rigid<T: Real>(m: &[Mat4<T>]) -> Result<()> {
    for (index, mi) in m.iter().enumerate() {
        DualQuat::from_matrix4(mi).map_err(|e| Error::BlendInput {
            what: format!("transform {index}: {e}"),
        })?;
    }
    Ok(())
}

/// Blends rigid 4×4 matrices (checked for rigidity; matrix methods work on them directly,
/// the others through dual quaternions, as the paper's Table 1 assumes).
pub fn blend_matrices<T: Real>(
    method: Method,
    m: &[Mat4<T>],
    w: &[T],
    opt: &Options<T>,
) -> Result<Blended<T>> {
    check_rigid(m)?;
    blend_rigid_matrices(method, m, w, opt)
}

fn blend_rigid_matrices<T: Real>(
    method: Method,
    m: &[Mat4<T>],
    w: &[T],
    opt: &Options<T>,
) -> Result<Blended<T>> {
    match method {
        Method::Lin => {
            let b = lin::lin(m, w)?;
            let dev = b.linear_part().rotation_deviation();
            let rigid = dev <= crate::default_tolerance::<T>() * T::from_i32(4);
            let r = crate::interp::lin_mat::rotation_part(&b.linear_part())
                .unwrap_or(crate::Quat::identity());
            Ok(Blended {
                matrix: b,
                dq: DualQuat::from_rotation_translation(r, b.translation()),
                rigid,
                iterations: None,
            })
        }
        Method::Log => {
            let b = log::log_blend(m, w)?;
            Ok(rigid_result(DualQuat::from_matrix4_unchecked(&b), None))
        }
        Method::LogIter => {
            let (b, it) = log::log_blend_iterative(m, w, opt.precision, opt.max_iterations)?;
            Ok(rigid_result(DualQuat::from_matrix4_unchecked(&b), Some(it)))
        }
        _ => {
            let q: Vec<DualQuat<T>> = m.iter().map(DualQuat::from_matrix4_unchecked).collect();
            blend_dual_quats(method, &q, w, opt)
        }
    }
}

/// Blends unit dual quaternions (matrix methods convert to matrices first).
pub fn blend_dual_quats<T: Real>(
    method: Method,
    q: &[DualQuat<T>],
    w: &[T],
    opt: &Options<T>,
) -> Result<Blended<T>> {
    match method {
        Method::Lin | Method::Log | Method::LogIter => {
            let m: Vec<Mat4<T>> = q.iter().map(|d| d.to_matrix4()).collect();
            blend_rigid_matrices(method, &m, w, opt)
        }
        Method::Dec => {
            let (b, it) = dec::dec(q, w, opt.center, opt.precision, opt.max_iterations)?;
            Ok(rigid_result(b, Some(it)))
        }
        Method::Qlb => Ok(rigid_result(qlb::qlb(q, w, opt.center)?, None)),
        Method::ScLerp => {
            let t = sclerp_parameter(q.len(), w)?;
            Ok(rigid_result(sclerp::sclerp(q[0], q[1], t)?, None))
        }
        Method::Dlb => Ok(rigid_result(dlb::dlb(q, w)?, None)),
        Method::Dib => {
            let (b, it) = dib::dib(q, w, opt.precision, opt.max_iterations)?;
            Ok(rigid_result(b, Some(it)))
        }
    }
}
