//! *Dec*: decomposition into rotation and translation (Kavan et al. 2006, §2.2 and §5).
//!
//! Each rigid motion `x ↦ Rᵢ x + tᵢ` is split, *about a centre c*, into its rotation Rᵢ and
//! the displacement of the centre, `dᵢ = Rᵢ c + tᵢ − c`. The rotations are blended by the
//! spherical average of Buss & Fillmore ([`super::mean`]), the displacements linearly, and
//! the result is `x ↦ R (x − c) + c + Σ wᵢ dᵢ`. The result depends on c — Dec is not
//! coordinate invariant, which is why the centre is a parameter (origin by default);
//! Kavan & Žára 2005 compute a good one by least squares.

use super::mean::spherical_average;
use super::weights::convex_weights;
use crate::{DualQuat, Quat, Real, Result, Vec3};

/// Dec about `center`: the blend and the iterations of the spherical average.
pub fn dec<T: Real>(
    x: &[DualQuat<T>],
    w: &[T],
    center: Vec3<T>,
    precision: T,
    max_iterations: usize,
) -> Result<(DualQuat<T>, usize)> {
    let w = convex_weights(w, x.len())?;
    let rotations: Vec<Quat<T>> = x.iter().map(|d| d.real).collect();
    let (r, steps) = spherical_average(&rotations, &w, precision, max_iterations)?;
    Ok((recompose(x, &w, r, center), steps))
}

/// `x ↦ r (x − c) + c + Σ wᵢ (xᵢ(c) − c)`: the blended rotation r about the centre, moved by
/// the blended displacement of the centre. Weights must already be convex.
pub(crate) fn recompose<T: Real>(
    x: &[DualQuat<T>],
    w: &[T],
    r: Quat<T>,
    c: Vec3<T>,
) -> DualQuat<T> {
    let mut d = Vec3::zero();
    for (xi, wi) in x.iter().zip(w) {
        d += (xi.transform_point(c) - c) * *wi;
    }
    let t = c + d - r.rotate(c);
    DualQuat::from_rotation_translation(r, t)
}
