//! Key frames: the rotations a curve must pass through, with optional times.

use crate::{Error, Quat, Real, Result};

/// Validated key frames: unit quaternions (at least two), optionally with strictly
/// increasing times.
#[derive(Debug, Clone, PartialEq)]
pub struct KeyFrames<T> {
    q: Vec<Quat<T>>,
    times: Option<Vec<T>>,
}

/// Which signs the keys keep. q and −q are the same rotation but not the same point of the
/// sphere, and every quaternion curve depends on the choice (Dam et al. §6.1.5, footnote
/// 7; Squad needs same-hemisphere keys, §6.2.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Hemisphere {
    /// Flip each key to the hemisphere of the one before it (`q_i · q_{i−1} ≥ 0`): every
    /// interval then takes the shorter rotation. The default.
    #[default]
    Chain,
    /// Keep the signs as given: an interval whose keys have `q_i · q_{i+1} < 0` takes the
    /// longer way round.
    AsGiven,
}

impl<T: Real> KeyFrames<T> {
    /// Keys from quaternions (normalized here) and optional times. Errors: fewer than two
    /// keys, a zero or non-finite key (naming its index), times of the wrong count, not
    /// finite or not strictly increasing.
    pub fn new(keys: &[Quat<T>], times: Option<&[T]>, hemisphere: Hemisphere) -> Result<Self> {
        if keys.len() < 2 {
            return Err(Error::TooFewKeys {
                what: "interpolation",
                needed: 2,
                got: keys.len(),
            });
        }
        let mut q = Vec::with_capacity(keys.len());
        for (index, k) in keys.iter().enumerate() {
            let u = k.normalize().map_err(|e| Error::BadKey {
                index,
                source: Box::new(e),
            })?;
            let u = match (hemisphere, q.last()) {
                (Hemisphere::Chain, Some(prev)) if u.dot(*prev) < T::ZERO => -u,
                _ => u,
            };
            q.push(u);
        }
        if let Some(t) = times {
            if t.len() != keys.len() {
                return Err(Error::WrongLength {
                    what: "key times",
                    expected: "one per key",
                    got: t.len(),
                });
            }
            for (index, v) in t.iter().enumerate() {
                if !v.is_finite() || (index > 0 && *v <= t[index - 1]) {
                    return Err(Error::BadKeyTime {
                        index,
                        value: v.to_f64(),
                    });
                }
            }
        }
        Ok(Self {
            q,
            times: times.map(|t| t.to_vec()),
        })
    }
    /// The unit key quaternions (signs as chosen by [`Hemisphere`]).
    pub fn quats(&self) -> &[Quat<T>] {
        &self.q
    }
    /// The key times, if given.
    pub fn times(&self) -> Option<&[T]> {
        self.times.as_deref()
    }
    /// Number of keys (≥ 2).
    pub fn len(&self) -> usize {
        self.q.len()
    }
    /// Always false: there are at least two keys.
    pub fn is_empty(&self) -> bool {
        false
    }
    /// The parameter value of a point `h` into interval `i`: the key time interpolated
    /// linearly, or `i + h` without times.
    pub fn parameter(&self, interval: usize, h: T) -> T {
        match &self.times {
            Some(t) => t[interval] + (t[interval + 1] - t[interval]) * h,
            None => T::from_f64(interval as f64) + h,
        }
    }
}
