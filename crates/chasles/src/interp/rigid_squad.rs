//! The dual-quaternion *Squad*: Dam et al. 1998, Definition 17 (eq. 6.14–6.16) on unit dual
//! quaternions (Kavan et al. 2006, §3–4).
//!
//! `Squad(q̂_i, q̂_{i+1}, ŝ_i, ŝ_{i+1}, h) = ScLERP(ScLERP(q̂_i, q̂_{i+1}, h), ScLERP(ŝ_i, ŝ_{i+1}, h), 2h(1 − h))`
//! with `ScLERP(p̂, q̂, h) = p̂ exp(h log(p̂* q̂))` and the inner control points
//! `ŝ_i = q̂_i exp(−(log(q̂_i* q̂_{i−1}) + log(q̂_i* q̂_{i+1})) / 4)` (eq. 6.15 with the
//! dual-quaternion log and exp), `ŝ_0 = q̂_0`, `ŝ_N = q̂_N` (the report's end condition).
//!
//! Proposition 30's argument uses only the group operations, log and exp, so it holds on the
//! unit dual quaternions as on the unit quaternions: differentiating eq. 6.14 at h = 0,
//! the curve leaves q̂_i with `q̂_i (L₊ + 2 log(q̂_i* ŝ_i)) = q̂_i (L₊ − L₋)/2` and reaches it
//! from the interval before with the same derivative (`L± = log(q̂_i* q̂_{i±1})`): C¹ at the
//! keys (`tests/rigid.rs` measures it by one-sided differences). C¹ in the interval
//! parameter h: with key times whose intervals differ in length the velocity in time scales
//! by each interval's length on either side of a key, as the quaternion Squad's does. Every term is a product,
//! log or exp of relative motions, so the curve is bi-invariant. With no translations it is
//! Squad; with no rotations, the uniform Catmull–Rom spline of the translations (module
//! [`super::rigid`]).

use super::rigid::{screw, RigidKeys};
use crate::{DualQuat, Real, Result};

/// The dual-quaternion Squad over a sequence of keys: the keys and their control points.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidSquad<T> {
    q: Vec<DualQuat<T>>,
    s: Vec<DualQuat<T>>,
}

impl<T: Real> RigidSquad<T> {
    /// Computes the control points ŝ_i (eq. 6.15 on dual quaternions). Errors: a relative
    /// motion whose log fails (not finite).
    pub fn new(keys: &RigidKeys<T>) -> Result<Self> {
        let q = keys.dual_quats().to_vec();
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
    /// The inner control points ŝ_i.
    pub fn controls(&self) -> &[DualQuat<T>] {
        &self.s
    }
    /// Eq. 6.14 at `h ∈ [0, 1]` in interval `i` (clamped to the last interval); the keys
    /// exactly at h = 0 and h = 1.
    pub fn eval(&self, interval: usize, h: T) -> Result<DualQuat<T>> {
        let i = interval.min(self.q.len() - 2);
        if h == T::ZERO {
            return Ok(self.q[i]);
        }
        if h == T::ONE {
            return Ok(self.q[i + 1]);
        }
        let outer = screw(self.q[i], self.q[i + 1], h)?;
        let inner = screw(self.s[i], self.s[i + 1], h)?;
        screw(outer, inner, T::TWO * h * (T::ONE - h))
    }
}
