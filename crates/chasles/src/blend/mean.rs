//! The weighted spherical average of rotations (Buss & Fillmore 2001, "Spherical averages
//! and applications to spherical splines and interpolation"; cited in Kavan et al. 2006,
//! §2.2 and §5 as the rotation part of Dec).
//!
//! The average is the rotation q minimizing `Σ wᵢ angle(q, qᵢ)²`. Start from QLB, then
//! repeat `u = Σ wᵢ log(q* qᵢ)`, `q ← q exp(u)` until `‖u‖ < precision`: the fixed point has
//! `Σ wᵢ log(q* qᵢ) = 0`, the condition for the minimum. Each `q* qᵢ` is taken in its
//! positive hemisphere, so every input counts by its shorter rotation. For two rotations
//! the average is Slerp, reached in one step.

use super::qlb::qlb_rotation;
use crate::{Quat, Real, Result};

/// The spherical average and the number of update steps taken.
pub fn spherical_average<T: Real>(
    q: &[Quat<T>],
    w: &[T],
    precision: T,
    max_iterations: usize,
) -> Result<(Quat<T>, usize)> {
    let mut m = qlb_rotation(q, w)?;
    let mut steps = 0;
    let mut last = T::from_f64(f64::INFINITY);
    while steps < max_iterations {
        let mut u = Quat::zero();
        for (qi, wi) in q.iter().zip(w) {
            u += (m.conjugate() * *qi).to_positive_hemisphere().log()? * *wi;
        }
        u.w = T::ZERO;
        let norm = u.norm();
        let norm = super::finite_update(
            norm,
            "the spherical-average update (the inputs overflow its squares)",
        )?;
        if !super::keep_going(norm, last, precision) {
            break;
        }
        last = norm;
        m = (m * u.exp()).normalize()?;
        steps += 1;
    }
    Ok((m, steps))
}
