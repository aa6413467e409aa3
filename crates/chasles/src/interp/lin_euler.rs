//! *LinEuler*: linear interpolation of Euler angles (Dam et al. 1998, §6.1.1, eq. 6.1),
//! `LinEuler(v0, v1, h) = v0(1 − h) + v1 h` on the angle triples.
//!
//! Its frames are rotations, but the curve leaves the great arc between the keys and slows
//! down or speeds up (Figure 6.1). Keys given as Euler triples
//! ([`KeyFrames::from_euler`](super::KeyFrames::from_euler)) are interpolated as given, in
//! their order — `(0, 0, 0)` to `(0, 0, 4)` passes 2 rad about z halfway, whatever the
//! principal angles of the key rotations; other keys' triples are extracted in the order
//! asked for ([`EulerOrder::DAM`], the report's, angles in ]−π, π]).

use super::KeyFrames;
use crate::{EulerOrder, Quat, Real, Result};

/// Eq. 6.1 on raw angle triples.
#[inline]
pub fn lin_euler<T: Real>(v0: [T; 3], v1: [T; 3], h: T) -> [T; 3] {
    core::array::from_fn(|k| v0[k] * (T::ONE - h) + v1[k] * h)
}

/// The keys' angle triples in `order`: as given when the keys were given in that order,
/// else extracted from the rotations. Errors: a key that cannot be converted.
pub fn key_angles<T: Real>(order: EulerOrder, keys: &KeyFrames<T>) -> Result<Vec<[T; 3]>> {
    match keys.euler() {
        Some((given, angles)) if given == order => Ok(angles.to_vec()),
        _ => keys
            .quats()
            .iter()
            .map(|q| Ok(q.to_euler(order)?.angles))
            .collect(),
    }
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
