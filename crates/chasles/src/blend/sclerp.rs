//! *ScLERP*: screw linear interpolation, `ScLERP(t; p̂, q̂) = p̂ (p̂* q̂)^t` (Kavan et al. 2006,
//! §4). The generalization of Slerp to rigid motions: a screw motion about a fixed axis
//! (shortest path) turning and sliding linearly in t (constant speed), bi-invariant
//! (Lemma 2). Only for two transforms.
//!
//! The shorter screw is taken: when `p̂* q̂` has a negative scalar part, −q̂ (the same
//! transformation) is used, so the rotation never exceeds π. At exactly π the two screws
//! are equally short and the one of q̂ as given is used: the result is defined on every
//! input (nalgebra's `sclerp` returns `None` there).

use crate::{DualQuat, Real, Result};

/// ScLERP from `p` to `q` (unit dual quaternions) at `t`, the shorter way.
pub fn sclerp<T: Real>(p: DualQuat<T>, q: DualQuat<T>, t: T) -> Result<DualQuat<T>> {
    let rel = (p.conjugate() * q).to_positive_hemisphere();
    Ok(p * rel.powf(t)?)
}
