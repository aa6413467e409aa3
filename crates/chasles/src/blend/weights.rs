//! Convex blending weights (Kavan et al. 2006, §4: "convex weights w = (w1, …, wn)").
//!
//! Every blend takes the weights through [`convex_weights`]: a weight that is negative or
//! not finite, a sum that is not positive, or a count that does not match the transforms
//! is a typed error. Otherwise the weights are **scaled to sum to 1** (so `[1, 3]` means
//! `[0.25, 0.75]`) — the documented normalization; a sum of exactly zero is an error, never
//! a silent NaN.

use crate::{Error, Real, Result};

/// Validates and scales weights to sum to 1. `n` is the number of transforms.
pub fn convex_weights<T: Real>(w: &[T], n: usize) -> Result<Vec<T>> {
    check_lengths(n, w.len())?;
    let mut sum = T::ZERO;
    for (index, v) in w.iter().enumerate() {
        if !v.is_finite() || *v < T::ZERO {
            return Err(Error::BadWeight {
                index,
                value: v.to_f64(),
            });
        }
        sum += *v;
    }
    if sum <= T::ZERO || !sum.is_finite() {
        return Err(Error::WeightSum { sum: sum.to_f64() });
    }
    Ok(w.iter().map(|v| *v / sum).collect())
}

/// The index of the largest weight (the first one on ties): the pivot for hemisphere
/// choices.
pub fn pivot<T: Real>(w: &[T]) -> usize {
    let mut best = 0;
    for (i, v) in w.iter().enumerate() {
        if *v > w[best] {
            best = i;
        }
    }
    best
}

/// The length check of the `*_convex` blends (weights already convex, no allocation): at
/// least one transform, one weight each.
pub(crate) fn check_lengths(n: usize, w: usize) -> Result<()> {
    if n == 0 {
        return Err(Error::BlendInput {
            what: "nothing to blend: no transforms".into(),
        });
    }
    if w != n {
        return Err(Error::BlendInput {
            what: format!("{n} transforms but {w} weights"),
        });
    }
    Ok(())
}
