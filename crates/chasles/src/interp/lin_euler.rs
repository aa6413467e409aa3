//! *LinEuler*: linear interpolation of Euler angles (Dam et al. 1998, §6.1.1, eq. 6.1),
//! `LinEuler(v0, v1, h) = v0(1 − h) + v1 h` on the angle triples.
//!
//! Its frames are rotations, but the curve leaves the great arc between the keys and slows
//! down or speeds up (Figure 6.1); the angle triples of the keys are taken in the report's
//! convention ([`EulerOrder::DAM`], angles in ]−π, π]) unless another order is given.

use crate::{EulerOrder, Quat, Real, Result};

/// Eq. 6.1 on raw angle triples.
#[inline]
pub fn lin_euler<T: Real>(v0: [T; 3], v1: [T; 3], h: T) -> [T; 3] {
    core::array::from_fn(|k| v0[k] * (T::ONE - h) + v1[k] * h)
}

/// Eq. 6.1 between two rotations: both are converted to Euler angles in `order`, the
/// triples are interpolated, and the result converted back. Errors: zero or non-finite keys.
pub fn lin_euler_quat<T: Real>(
    order: EulerOrder,
    q0: Quat<T>,
    q1: Quat<T>,
    h: T,
) -> Result<Quat<T>> {
    let v0 = q0.to_euler(order)?.angles;
    let v1 = q1.to_euler(order)?.angles;
    Ok(Quat::from_euler(order, lin_euler(v0, v1, h)))
}
