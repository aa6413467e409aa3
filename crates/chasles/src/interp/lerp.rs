//! *Lerp*: linear interpolation of quaternions (Dam et al. 1998, §6.1.3, eq. 6.3),
//! `Lerp(q0, q1, h) = q0(1 − h) + q1 h`.
//!
//! The raw curve is the chord through the sphere: its points are not unit quaternions.
//! The report normalizes it for Figure 6.3 ([`nlerp`]), which puts it back on the great arc
//! but with a speed that peaks in the middle of the interval (the "short cut" of §6.1.3).

use crate::{Quat, Real};

/// Eq. 6.3, raw: `q0(1 − h) + q1 h` (not unit for 0 < h < 1 unless q0 = q1).
#[inline]
pub fn lerp<T: Real>(q0: Quat<T>, q1: Quat<T>, h: T) -> Quat<T> {
    q0 * (T::ONE - h) + q1 * h
}

/// Eq. 6.3 normalized onto the unit sphere (Figure 6.3). When the chord passes through the
/// origin (q1 = −q0 at h = ½) there is no direction; q0 is returned there.
#[inline]
pub fn nlerp<T: Real>(q0: Quat<T>, q1: Quat<T>, h: T) -> Quat<T> {
    lerp(q0, q1, h).normalize().unwrap_or(q0)
}
