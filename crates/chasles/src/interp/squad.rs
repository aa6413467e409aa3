//! *Squad*: spherical spline quaternion interpolation (Dam et al. 1998, §6.2.1,
//! Definition 17, eq. 6.14–6.16; Shoemake 1987).
//!
//! `Squad(q_i, q_{i+1}, s_i, s_{i+1}, h) = Slerp(Slerp(q_i, q_{i+1}, h), Slerp(s_i, s_{i+1}, h), 2h(1 − h))`
//! with the inner control points
//! `s_i = q_i exp(−(log(q_i⁻¹ q_{i−1}) + log(q_i⁻¹ q_{i+1})) / 4)` (eq. 6.15/6.16), which make
//! the curve C¹ at every key (Proposition 30). End conditions: `s_0 = q_0`, `s_N = q_N` (the
//! report's "simplest solution"). The keys must be in one hemisphere; [`super::KeyFrames`]
//! with [`super::Hemisphere::Chain`] (the default) sees to that.

use super::slerp::slerp;
use super::KeyFrames;
use crate::{Quat, Real, Result};

/// Squad over a sequence of keys: the keys and their inner control points.
#[derive(Debug, Clone, PartialEq)]
pub struct Squad<T> {
    q: Vec<Quat<T>>,
    s: Vec<Quat<T>>,
}

impl<T: Real> Squad<T> {
    /// Computes the control points `s_i` (eq. 6.15) for the keys.
    pub fn new(keys: &KeyFrames<T>) -> Result<Self> {
        let q = keys.quats().to_vec();
        let n = q.len();
        let mut s = Vec::with_capacity(n);
        s.push(q[0]);
        for i in 1..n - 1 {
            let inv = q[i].conjugate();
            let sum = (inv * q[i - 1]).log()? + (inv * q[i + 1]).log()?;
            s.push(q[i] * (sum * T::from_f64(-0.25)).exp());
        }
        s.push(q[n - 1]);
        Ok(Self { q, s })
    }
    /// The keys.
    pub fn keys(&self) -> &[Quat<T>] {
        &self.q
    }
    /// The inner control points `s_i`.
    pub fn controls(&self) -> &[Quat<T>] {
        &self.s
    }
    /// Eq. 6.14 at `h ∈ [0, 1]` in interval `i` (clamped to the last interval).
    pub fn eval(&self, interval: usize, h: T) -> Quat<T> {
        let i = interval.min(self.q.len() - 2);
        let outer = slerp(self.q[i], self.q[i + 1], h);
        let inner = slerp(self.s[i], self.s[i + 1], h);
        slerp(outer, inner, T::TWO * h * (T::ONE - h))
    }
}
