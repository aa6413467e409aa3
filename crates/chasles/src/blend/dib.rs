//! *DIB*: dual quaternion iterative blending (Kavan et al. 2006, §4, the algorithm box):
//!
//! ```text
//! b̂ = DLB(w; q̂1, …, q̂n)
//! repeat  x̂ = Σ wᵢ log(b̂* q̂ᵢ);  b̂ = b̂ exp(x̂)  until ‖x̂‖ < p
//! ```
//!
//! Bi-invariant, constant speed and shortest path; for two transforms it equals ScLERP
//! after one update (Lemma 3). Here the loop stops *before* an update when `‖x̂‖ < p`
//! (the paper's second pass "performs no update"), so the count returned is the number of
//! updates made: 1 for two transforms. Each `b̂* q̂ᵢ` is taken in its positive hemisphere
//! (the shorter screw), and `‖x̂‖` is the Euclidean norm of the eight numbers. b̂ is
//! renormalized after each update (otherwise rounding drifts it off the unit dual
//! quaternions, most visibly in f32). The loop also stops after `max_iterations` updates,
//! and when `‖x̂‖` stops decreasing within 100× the precision — rounding, not the blend,
//! then sets the updates.

use super::dlb::dlb_convex;
use super::weights::convex_weights;
use crate::{DualQuat, Quat, Real, Result};

/// DIB: the blend and the number of updates.
pub fn dib<T: Real>(
    q: &[DualQuat<T>],
    w: &[T],
    precision: T,
    max_iterations: usize,
) -> Result<(DualQuat<T>, usize)> {
    dib_convex(q, &convex_weights(w, q.len())?, precision, max_iterations)
}

/// DIB with weights that are already convex (non-negative, summing to 1; only the lengths
/// are checked) and no allocation: for callers that blend once per vertex (skinning).
pub fn dib_convex<T: Real>(
    q: &[DualQuat<T>],
    w: &[T],
    precision: T,
    max_iterations: usize,
) -> Result<(DualQuat<T>, usize)> {
    dib_convex_observed(q, w, precision, max_iterations, |_| {})
}

/// [`dib_convex`], calling `observe` with the DLB start and with every iterate after it
/// (each unit): for pictures and studies of the convergence (Kavan et al. Figure 4).
pub fn dib_convex_observed<T: Real>(
    q: &[DualQuat<T>],
    w: &[T],
    precision: T,
    max_iterations: usize,
    mut observe: impl FnMut(&DualQuat<T>),
) -> Result<(DualQuat<T>, usize)> {
    let mut b = dlb_convex(q, w)?;
    observe(&b);
    let mut steps = 0;
    let mut last = T::from_f64(f64::INFINITY);
    while steps < max_iterations {
        let bc = b.conjugate();
        let mut x = DualQuat::new(Quat::zero(), Quat::zero());
        for (qi, wi) in q.iter().zip(w) {
            x = x + (bc * *qi).to_positive_hemisphere().log()? * *wi;
        }
        let norm = (x.real.norm_squared() + x.dual.norm_squared()).sqrt();
        let norm = super::finite_update(norm, "the DIB update (the inputs overflow its squares)")?;
        if !super::keep_going(norm, last, precision) {
            break;
        }
        last = norm;
        b = (b * x.exp()).normalize()?;
        observe(&b);
        steps += 1;
    }
    Ok((b.normalize()?, steps))
}
