//! Key-frame curves of rigid motions: keys that carry a rotation and a translation, as
//! unit dual quaternions (Kavan et al. 2006, §3, eq. 1), interpolated by the constructions
//! Dam et al. 1998 use for rotations, carried from the unit quaternions to the unit dual
//! quaternions through the dual-quaternion log and exp. Kavan et al. §7 lists this
//! ("spatial keyframing") among the uses of their blends.
//!
//! * [`RigidMethod::ScLerp`]: piecewise ScLERP (Kavan et al. §4, `p̂ (p̂* q̂)^h`): in each
//!   interval the screw motion from key to key, turning and sliding at constant speed
//!   (the rigid analogue of Slerp, Dam et al. eq. 6.13). C⁰ at the keys.
//! * [`RigidMethod::Squad`]: Dam et al.'s Definition 17 (eq. 6.14–6.16) with ScLERP in place
//!   of Slerp and the dual-quaternion log/exp in eq. 6.15 ([`super::rigid_squad`]). C¹ at
//!   the keys.
//! * [`RigidMethod::Spring`]: the curve of least curvature energy through the keys (Dam et
//!   al. §6.3.7 carried to rigid motions, [`super::rigid_spring`](mod@super::rigid_spring)): by default the
//!   quaternion Spring of the rotations with the natural spline of the translations; or the
//!   dual-quaternion curve's own curvature energy ([`super::RigidEnergy::Screw`]).
//!
//! **Bi-invariance.** ScLERP and the dual-quaternion Squad are made of products, logs and
//! exps of relative motions `q̂_i* q̂_j`, so moving every key by one rigid motion a on the
//! left (`a q̂_i`: a change of world frame) or on the right (`q̂_i a`: a change of the body's
//! frame) moves every frame the same way. No positive energy on the rigid motions is
//! invariant on both sides (SE(3) has no bi-invariant metric), so Spring is invariant on the
//! left and, on the right, under rotations only (see [`super::rigid_spring`](mod@super::rigid_spring)).
//!
//! **Reductions.** Keys without translation give Slerp, Squad and the quaternion Spring
//! (width 1, c_k = 1) exactly: every dual part stays 0. Keys without rotation give
//! Euclidean curves of the translations (Spring with its default energy; the screw energy
//! turns the frames, see [`super::rigid_spring`](mod@super::rigid_spring)): ScLERP the polygon through them, Squad the uniform
//! Catmull–Rom spline (the cubic Hermite curve with tangents `(t_{i+1} − t_{i−1})/2`, and
//! `t_1 − t_0`, `t_N − t_{N−1}` at the ends — `s_i` becomes `t_i − (t_{i−1} − 2t_i +
//! t_{i+1})/4`, and eq. 6.14 a cubic with those end tangents), Spring the discrete natural
//! spline that minimizes `Σ ‖t_{i−1} − 2t_i + t_{i+1}‖²`.
//!
//! Keys are chained to one hemisphere (`q0_i · q0_{i−1} ≥ 0`, as [`super::Hemisphere::Chain`]):
//! every interval takes the shorter screw. Frames are shared among intervals uniformly, or
//! in proportion to the key times ([`super::Timing::Uniform`]).

use super::rigid_spring::{rigid_spring, RigidSpringConfig};
use super::rigid_squad::RigidSquad;
use super::timing::{self, Timing};
use super::{Hemisphere, KeyFrames};
use crate::{DualQuat, Error, Real, Result};

/// Validated rigid key frames: unit dual quaternions (at least two) chained to one
/// hemisphere, and optional strictly increasing times.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidKeys<T> {
    dq: Vec<DualQuat<T>>,
    /// The rotation parts with the times (shared timing code).
    rot: KeyFrames<T>,
}

impl<T: Real> RigidKeys<T> {
    /// Keys from unit dual quaternions and optional times. Errors: fewer than two keys, a key
    /// that is not finite or not unit (naming its index), times of the wrong count, not
    /// finite or not strictly increasing.
    pub fn new(keys: &[DualQuat<T>], times: Option<&[T]>) -> Result<Self> {
        for (index, k) in keys.iter().enumerate() {
            k.check_unit().map_err(|e| Error::BadKey {
                index,
                source: Box::new(e),
            })?;
        }
        let real: Vec<_> = keys.iter().map(|k| k.real).collect();
        let rot = KeyFrames::new(&real, times, Hemisphere::Chain)?;
        let dq = keys
            .iter()
            .zip(rot.quats())
            .map(|(k, q)| if k.real.dot(*q) < T::ZERO { -*k } else { *k })
            .collect();
        Ok(Self { dq, rot })
    }
    /// The keys (chained).
    pub fn dual_quats(&self) -> &[DualQuat<T>] {
        &self.dq
    }
    /// The key times, if given.
    pub fn times(&self) -> Option<&[T]> {
        self.rot.times()
    }
    /// The number of keys.
    pub fn len(&self) -> usize {
        self.dq.len()
    }
    /// Never true (at least two keys).
    pub fn is_empty(&self) -> bool {
        self.dq.is_empty()
    }
    /// The parameter value at `h` into interval `i` (the key times, or `i + h`).
    pub fn parameter(&self, interval: usize, h: T) -> T {
        self.rot.parameter(interval, h)
    }
    /// The rotation parts as quaternion keys (the same times).
    pub fn rotations(&self) -> &KeyFrames<T> {
        &self.rot
    }
}

/// One frame of a rigid curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidFrame<T> {
    /// The pose (unit dual quaternion).
    pub dq: DualQuat<T>,
    /// The curve parameter: key time interpolated linearly, or `interval + h`.
    pub t: T,
    /// Which key this frame is, if it is one.
    pub key: Option<usize>,
}

/// How the keys are interpolated.
#[derive(Debug, Clone, PartialEq)]
pub enum RigidMethod {
    /// Piecewise ScLERP.
    ScLerp,
    /// The dual-quaternion Squad.
    Squad,
    /// Least curvature energy.
    Spring(RigidSpringConfig),
}

/// ScLERP from `p` to `q` as written, `p (p* q)^h`: the shorter screw when the keys are
/// chained. Exact at h = 0 and h = 1.
pub(crate) fn screw<T: Real>(p: DualQuat<T>, q: DualQuat<T>, h: T) -> Result<DualQuat<T>> {
    if h == T::ZERO {
        return Ok(p);
    }
    if h == T::ONE {
        return Ok(q);
    }
    let l = (p.conjugate() * q).log()?;
    Ok(p * (l * h).exp())
}

/// The frame grid of `frames` frames (uniform timing), with an error for too few frames
/// or too many to hold.
pub(crate) fn grid<T: Real>(keys: &RigidKeys<T>, frames: usize) -> Result<Vec<timing::Sample<T>>> {
    let mut probe: Vec<RigidFrame<T>> = Vec::new();
    if frames >= keys.len() && probe.try_reserve_exact(frames).is_err() {
        return Err(Error::TooManyFrames { frames });
    }
    drop(probe);
    let counts = timing::distribute(&keys.rot, frames, Timing::Uniform)?;
    Ok(timing::samples(&counts))
}

/// Samples `frames` frames of the curve through the keys by `method`; every key is one of
/// them, exactly. Errors: fewer frames than keys, too many to hold, a Spring setting out of
/// range, a frame that comes out not finite.
pub fn interpolate_rigid<T: Real>(
    method: &RigidMethod,
    keys: &RigidKeys<T>,
    frames: usize,
) -> Result<Vec<RigidFrame<T>>> {
    let out = match method {
        RigidMethod::Spring(cfg) => rigid_spring(keys, frames, cfg)?.frames,
        _ => {
            let g = grid(keys, frames)?;
            let squad = match method {
                RigidMethod::Squad => Some(RigidSquad::new(keys)?),
                _ => None,
            };
            let q = &keys.dq;
            let mut out = Vec::with_capacity(g.len());
            for s in g {
                let dq = match (s.key, &squad) {
                    (Some(k), _) => q[k],
                    (None, Some(sq)) => sq.eval(s.interval, s.h)?,
                    (None, None) => screw(q[s.interval], q[s.interval + 1], s.h)?,
                };
                out.push(RigidFrame {
                    dq,
                    t: keys.parameter(s.interval, s.h),
                    key: s.key,
                });
            }
            out
        }
    };
    if out.iter().any(|f| !f.dq.is_finite() || !f.t.is_finite()) {
        return Err(Error::NonFinite {
            what: "an interpolated pose (the keys are too large to interpolate in this precision)",
        });
    }
    Ok(out)
}
