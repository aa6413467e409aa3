//! Interpolation of rotations along key frames (Dam et al. 1998, chapters 5–7).
//!
//! Two-key methods, applied interval by interval: [`lin_euler`] (eq. 6.1), [`lin_mat`]
//! (eq. 6.2), [`lerp`] (eq. 6.3), [`slerp`] (eq. 6.4 and 6.13). Curves over many keys:
//! [`squad`] (Definition 17, eq. 6.14–6.16) and [`spring`](mod@spring) (§6.3.7: curvature minimized by
//! gradient descent). [`timing`] shares the frames among the intervals (§6.2). The
//! report's example key sets are in [`examples`].
//!
//! Past the report (issue 21, §8.2's "more specialized curves"): [`catmull_rom`] (Schlag's
//! spherical Catmull–Rom, C¹), [`tcb`] (Kochanek–Bartels: tension, continuity and bias per
//! key; all 0 is Catmull–Rom), [`bezier`] (Shoemake's spherical Bézier by de Casteljau),
//! [`c2_spline`] (continuous angular acceleration, SciPy's `RotationSpline`), and
//! [`horizon`]: camera paths whose frames never roll, after any method.
//!
//! Rigid motions (issue 22, Kavan et al. §7): [`rigid`] — key frames that carry a rotation
//! and a translation, by piecewise ScLERP, the dual-quaternion Squad ([`rigid_squad`]) or
//! Spring on the dual quaternions ([`rigid_spring`](mod@rigid_spring)).
//!
//! [`interpolate`] samples a whole curve: every key appears exactly once among the frames,
//! flagged in [`Frame::key`].

pub mod bezier;
pub mod c2_spline;
pub mod catmull_rom;
pub mod examples;
pub mod horizon;
pub mod keys;
pub mod lerp;
pub mod lin_euler;
pub mod lin_mat;
pub mod rigid;
pub mod rigid_spring;
pub mod rigid_squad;
pub mod slerp;
pub mod spring;
mod spring_converged;
pub mod squad;
pub mod tcb;
pub mod timing;

pub use bezier::Bezier;
pub use c2_spline::C2Spline;
pub use catmull_rom::CatmullRom;
pub use horizon::Up;
pub use keys::{Hemisphere, KeyFrames};
pub use rigid::{interpolate_rigid, RigidFrame, RigidKeys, RigidMethod};
pub use rigid_spring::{rigid_spring, RigidEnergy, RigidSpringConfig, RigidSpringResult};
pub use rigid_squad::RigidSquad;
pub use spring::{spring, Level, Solver, SpringConfig, SpringResult, Start, StepRule, Stopped};
pub use squad::Squad;
pub use tcb::{KochanekBartels, Tcb, TcbKey};
pub use timing::Timing;

use crate::{Error, EulerOrder, Mat3, Quat, Real, Result};

/// One frame of an interpolated curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame<T> {
    /// The rotation (unit, except for the raw curves of [`Method::Lerp`]).
    pub q: Quat<T>,
    /// The curve parameter: key time interpolated linearly, or `interval + h`.
    pub t: T,
    /// Which key this frame is, if it is one.
    pub key: Option<usize>,
}

/// A piecewise method (Spring, being global, is [`spring()`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Eq. 6.1 on Euler angles in the given order (the report: [`EulerOrder::DAM`]).
    LinEuler(EulerOrder),
    /// Eq. 6.2 on rotation matrices; frames are the rotation part of the raw matrices.
    LinMat,
    /// Eq. 6.3, raw: frames are not unit quaternions.
    Lerp,
    /// Eq. 6.3 normalized (Figure 6.3).
    Nlerp,
    /// Eq. 6.13.
    Slerp,
    /// Definition 17.
    Squad,
    /// Schlag's spherical Catmull–Rom spline ([`catmull_rom`]).
    CatmullRom,
    /// Kochanek–Bartels ([`tcb`]): these parameters for every key that has none of its own
    /// ([`KeyFrames::with_tcb`]).
    KochanekBartels(Tcb),
    /// Shoemake's spherical Bézier spline ([`bezier`]).
    Bezier,
    /// The C² spline of [`c2_spline`] (SciPy's `RotationSpline`).
    C2,
}

/// A many-key curve, built once per call of [`interpolate`].
enum Curve<T> {
    Squad(Squad<T>),
    CatmullRom(CatmullRom<T>),
    KochanekBartels(KochanekBartels<T>),
    Bezier(Bezier<T>),
    C2(C2Spline<T>),
}

impl<T: Real> Curve<T> {
    fn new(method: Method, keys: &KeyFrames<T>) -> Result<Option<Self>> {
        Ok(Some(match method {
            Method::Squad => Curve::Squad(Squad::new(keys)?),
            Method::CatmullRom => Curve::CatmullRom(CatmullRom::new(keys)?),
            Method::KochanekBartels(p) => Curve::KochanekBartels(KochanekBartels::new(keys, p)?),
            Method::Bezier => Curve::Bezier(Bezier::new(keys)?),
            Method::C2 => Curve::C2(C2Spline::new(keys)?),
            _ => return Ok(None),
        }))
    }
    fn eval(&self, interval: usize, h: T) -> Quat<T> {
        match self {
            Curve::Squad(c) => c.eval(interval, h),
            Curve::CatmullRom(c) => c.eval(interval, h),
            Curve::KochanekBartels(c) => c.eval(interval, h),
            Curve::Bezier(c) => c.eval(interval, h),
            Curve::C2(c) => c.eval(interval, h),
        }
    }
}

/// Samples `frames` frames of a piecewise curve through the keys. Errors: fewer frames
/// than keys; LinMat through keys 180° apart (singular matrix); Kochanek–Bartels
/// parameters out of range; the C² spline through keys a full turn apart or with a system
/// that does not settle; a frame that comes out not finite (LinEuler on angles near the top
/// of T's range, key times too far apart in scale).
pub fn interpolate<T: Real>(
    method: Method,
    keys: &KeyFrames<T>,
    frames: usize,
    timing: Timing,
) -> Result<Vec<Frame<T>>> {
    let counts = timing::distribute(keys, frames, timing)?;
    // The output and the grid reserved first: an absurd count is an error, not an abort.
    let mut out: Vec<Frame<T>> = Vec::new();
    let mut probe: Vec<timing::Sample<T>> = Vec::new();
    if out.try_reserve_exact(frames).is_err() || probe.try_reserve_exact(frames).is_err() {
        return Err(Error::TooManyFrames { frames });
    }
    drop(probe);
    let grid = timing::samples::<T>(&counts);
    let q = keys.quats();
    let curve = Curve::new(method, keys)?;
    let mats: Vec<Mat3<T>> = match method {
        Method::LinMat => q.iter().map(|k| k.to_rotation_matrix()).collect(),
        _ => Vec::new(),
    };
    let triples = match method {
        Method::LinEuler(order) => lin_euler::key_angles(order, keys)?,
        _ => Vec::new(),
    };
    for s in &grid {
        out.push({
            let (a, b) = (q[s.interval], q[s.interval + 1]);
            let r = match (s.key, method) {
                // LinEuler's keys as its angle triples make them: the path from_euler(v(h))
                // is then continuous through every key (the stored key may be its antipode,
                // when the triples turn the long way, e.g. (0, 0, 0) → (0, 0, 4)).
                (Some(k), Method::LinEuler(order)) => Quat::from_euler(order, triples[k]),
                (Some(k), _) => q[k],
                (None, Method::LinEuler(order)) => Quat::from_euler(
                    order,
                    lin_euler::lin_euler(triples[s.interval], triples[s.interval + 1], s.h),
                ),
                (None, Method::LinMat) => {
                    let m = lin_mat::lin_mat(&mats[s.interval], &mats[s.interval + 1], s.h);
                    let r = lin_mat::rotation_part(&m)?;
                    // Keep the sign continuous with the keys.
                    if r.dot(a * (T::ONE - s.h) + b * s.h) < T::ZERO {
                        -r
                    } else {
                        r
                    }
                }
                (None, Method::Lerp) => lerp::lerp(a, b, s.h),
                (None, Method::Nlerp) => lerp::nlerp(a, b, s.h),
                (None, Method::Slerp) => slerp::slerp(a, b, s.h),
                (None, _) => curve.as_ref().map_or(a, |c| c.eval(s.interval, s.h)),
            };
            Frame {
                q: r,
                t: keys.parameter(s.interval, s.h),
                key: s.key,
            }
        });
    }
    // Finite keys can still give a frame that is not (LinEuler's weighted sum of angles
    // near the top of T's range rounds past it): an error, never a NaN frame.
    if out.iter().any(|f| !f.q.is_finite() || !f.t.is_finite()) {
        return Err(Error::NonFinite {
            what: "an interpolated frame (the keys are too large to interpolate in this precision)",
        });
    }
    Ok(out)
}
