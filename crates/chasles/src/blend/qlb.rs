//! *QLB*: quaternion linear blending, `Σ wᵢ qᵢ / ‖Σ wᵢ qᵢ‖` (Kavan & Žára 2005; Kavan et al.
//! 2006, §4). Shortest path and coordinate invariant for rotations, not constant speed (its
//! angle differs from Slerp's by less than 8.15°). Each qᵢ is first brought into the
//! hemisphere of the pivot (the largest weight), so the sum never cancels.
//!
//! For rigid transformations the rotations are blended by QLB and the translations
//! linearly, about a chosen centre — a decomposition like Dec, and coordinate dependent for
//! the same reason.

use super::weights::{convex_weights, pivot};
use crate::{DualQuat, Quat, Real, Result, Vec3};

/// QLB of rotations (weights made convex).
pub fn qlb_rotation<T: Real>(q: &[Quat<T>], w: &[T]) -> Result<Quat<T>> {
    let w = convex_weights(w, q.len())?;
    let p = q[pivot(&w)];
    let mut sum = Quat::zero();
    for (qi, wi) in q.iter().zip(&w) {
        let s = if qi.dot(p) < T::ZERO { -*wi } else { *wi };
        sum += *qi * s;
    }
    sum.normalize()
}

/// Rigid transformations: rotation by QLB, translation of `center` blended linearly.
pub fn qlb<T: Real>(x: &[DualQuat<T>], w: &[T], center: Vec3<T>) -> Result<DualQuat<T>> {
    let w = convex_weights(w, x.len())?;
    let rotations: Vec<Quat<T>> = x.iter().map(|d| d.real).collect();
    let r = qlb_rotation(&rotations, &w)?;
    Ok(super::dec::recompose(x, &w, r, center))
}
