//! Angular velocity of a frame sequence (Dam et al. 1998, §5.2).
//!
//! * [`velocity_chord`]: eq. 5.1, `V(q_i) = (‖q_i − q_{i−1}‖ + ‖q_i − q_{i+1}‖) / 2`, the
//!   report's estimate (distances in quaternion space).
//! * [`velocity_angle`]: the same centred average of the exact rotation angle between
//!   consecutive frames (radians per frame), independent of the signs of the quaternions
//!   and of their norms.
//!
//! The report leaves the first and last frame out of its graphs; here they get the
//! one-sided value so that every frame has a number.

use crate::{Quat, Real};

fn centred<T: Real>(steps: &[T]) -> Vec<T> {
    let n = steps.len() + 1;
    (0..n)
        .map(
            |i| match (i.checked_sub(1).map(|j| steps[j]), steps.get(i)) {
                (Some(a), Some(b)) => (a + *b) * T::HALF,
                (Some(a), None) => a,
                (None, Some(b)) => *b,
                (None, None) => T::ZERO,
            },
        )
        .collect()
}

/// Eq. 5.1 for every frame (one-sided at the ends); empty for no frames.
pub fn velocity_chord<T: Real>(frames: &[Quat<T>]) -> Vec<T> {
    if frames.is_empty() {
        return Vec::new();
    }
    let steps: Vec<T> = frames.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
    centred(&steps)
}

/// The centred rotation angle between consecutive frames; frames that are zero or not
/// finite count as no rotation.
pub fn velocity_angle<T: Real>(frames: &[Quat<T>]) -> Vec<T> {
    if frames.is_empty() {
        return Vec::new();
    }
    let steps: Vec<T> = frames
        .windows(2)
        .map(|w| w[0].angle_to(w[1]).unwrap_or(T::ZERO))
        .collect();
    centred(&steps)
}
