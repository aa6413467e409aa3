//! *QLB*: quaternion linear blending, `Σ wᵢ qᵢ / ‖Σ wᵢ qᵢ‖` (Kavan & Žára 2005; Kavan et al.
//! 2006, §4). Shortest path and coordinate invariant for rotations, not constant speed (its
//! angle differs from Slerp's by less than 8.15°). Each qᵢ is first brought into the
//! hemisphere of the pivot (the largest weight), so the sum never cancels.
//!
//! For rigid transformations the rotations are blended by QLB and the translations
//! linearly, about a chosen centre — a decomposition like Dec, and coordinate dependent for
//! the same reason.

use super::weights::{check_lengths, convex_weights, pivot};
use crate::{DualQuat, Quat, Real, Result, Vec3};

/// QLB of rotations (weights made convex).
pub fn qlb_rotation<T: Real>(q: &[Quat<T>], w: &[T]) -> Result<Quat<T>> {
    let w = convex_weights(w, q.len())?;
    rotation_sum(q.iter().copied(), &w).normalize()
}

/// `Σ ±wᵢ qᵢ`, each sign putting qᵢ in the pivot's hemisphere. Weights convex, lengths equal
/// and not zero.
fn rotation_sum<T: Real>(q: impl Iterator<Item = Quat<T>> + Clone, w: &[T]) -> Quat<T> {
    let p = q.clone().nth(pivot(w)).unwrap_or_else(Quat::zero);
    let mut sum = Quat::zero();
    for (qi, wi) in q.zip(w) {
        let s = if qi.dot(p) < T::ZERO { -*wi } else { *wi };
        sum += qi * s;
    }
    sum
}

/// Rigid transformations: rotation by QLB, translation of `center` blended linearly.
pub fn qlb<T: Real>(x: &[DualQuat<T>], w: &[T], center: Vec3<T>) -> Result<DualQuat<T>> {
    qlb_convex(x, &convex_weights(w, x.len())?, center)
}

/// [`qlb`] with weights that are already convex (non-negative, summing to 1; only the
/// lengths are checked) and no allocation: for callers that blend once per vertex
/// (skinning).
pub fn qlb_convex<T: Real>(x: &[DualQuat<T>], w: &[T], center: Vec3<T>) -> Result<DualQuat<T>> {
    check_lengths(x.len(), w.len())?;
    let r = rotation_sum(x.iter().map(|d| d.real), w).normalize()?;
    Ok(super::dec::recompose(x, w, r, center))
}
