//! Distributing frames over the intervals between key frames (Dam et al. 1998, §6.2 and
//! the end of §6.2.1).
//!
//! A curve of N frames over K keys has every key as one frame and N − K in-between frames.
//! [`Timing::Uniform`] gives every interval the same share (or, when the keys carry times,
//! a share in proportion to the interval's duration); [`Timing::Angle`] gives each interval
//! a share in proportion to its angle `θ_i`, `cos θ_i = |q_i · q_{i+1}|` — the
//! reparameterization that makes Slerp's speed (nearly) constant across intervals
//! (Figure 6.8). Shares are rounded by the largest-remainder method, so the counts add up
//! exactly.

use super::KeyFrames;
use crate::{Error, Real, Result};

/// How frames are shared among intervals.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Timing {
    /// Equal shares (or in proportion to key-time spans when times are given).
    #[default]
    Uniform,
    /// In proportion to the angle of each interval (§6.2).
    Angle,
}

/// One output frame's place: `h ∈ [0, 1]` into `interval`, and the key it is, if any.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample<T> {
    /// Interval index (key `interval` to key `interval + 1`).
    pub interval: usize,
    /// Fraction into the interval.
    pub h: T,
    /// Which key this frame is, if it is one.
    pub key: Option<usize>,
}

/// In-between frames per interval for `frames` frames in total. Errors: fewer frames than
/// keys.
pub fn distribute<T: Real>(
    keys: &KeyFrames<T>,
    frames: usize,
    timing: Timing,
) -> Result<Vec<usize>> {
    let k = keys.len();
    if frames < k {
        return Err(Error::TooFewFrames { frames, keys: k });
    }
    let q = keys.quats();
    let weights: Vec<f64> = (0..k - 1)
        .map(|i| match (timing, keys.times()) {
            (Timing::Angle, _) => q[i].dot(q[i + 1]).abs().min(T::ONE).acos().to_f64(),
            (Timing::Uniform, Some(t)) => (t[i + 1] - t[i]).to_f64(),
            (Timing::Uniform, None) => 1.0,
        })
        .collect();
    Ok(largest_remainder(&weights, frames - k))
}

/// Splits `total` into integer parts proportional to `weights` (equal parts if all are 0).
pub fn largest_remainder(weights: &[f64], total: usize) -> Vec<usize> {
    let sum: f64 = weights.iter().sum();
    let w: Vec<f64> = if sum > 0.0 && sum.is_finite() {
        weights.iter().map(|v| v / sum).collect()
    } else {
        vec![1.0 / weights.len() as f64; weights.len()]
    };
    let exact: Vec<f64> = w.iter().map(|v| v * total as f64).collect();
    let mut counts: Vec<usize> = exact.iter().map(|v| v.floor() as usize).collect();
    // Rounding of huge counts in f64 can make the floors overshoot: never below 0.
    let mut left = total.saturating_sub(counts.iter().sum::<usize>());
    let mut order: Vec<usize> = (0..w.len()).collect();
    order.sort_by(|a, b| {
        (exact[*b] - exact[*b].floor()).total_cmp(&(exact[*a] - exact[*a].floor()))
    });
    for i in order.into_iter().cycle() {
        if left == 0 {
            break;
        }
        counts[i] += 1;
        left -= 1;
    }
    counts
}

/// The frame grid: key 0, the in-betweens of interval 0, key 1, …, the last key.
pub fn samples<T: Real>(counts: &[usize]) -> Vec<Sample<T>> {
    let mut out = Vec::with_capacity(counts.iter().sum::<usize>() + counts.len() + 1);
    for (i, n) in counts.iter().enumerate() {
        out.push(Sample {
            interval: i,
            h: T::ZERO,
            key: Some(i),
        });
        for k in 1..=*n {
            out.push(Sample {
                interval: i,
                h: T::from_f64(k as f64 / (*n + 1) as f64),
                key: None,
            });
        }
    }
    out.push(Sample {
        interval: counts.len() - 1,
        h: T::ONE,
        key: Some(counts.len()),
    });
    out
}
