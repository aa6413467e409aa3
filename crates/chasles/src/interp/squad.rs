//! *Squad*: spherical spline quaternion interpolation (Dam et al. 1998, §6.2.1,
//! Definition 17, eq. 6.14–6.16; Shoemake 1987).
//!
//! `Squad(q_i, q_{i+1}, s_i, s_{i+1}, h) = Slerp(Slerp(q_i, q_{i+1}, h), Slerp(s_i, s_{i+1}, h), 2h(1 − h))`
//! with the inner control points
//! `s_i = q_i exp(−(log(q_i⁻¹ q_{i−1}) + log(q_i⁻¹ q_{i+1})) / 4)` (eq. 6.15/6.16), which make
//! the curve C¹ at every key (Proposition 30). End conditions: `s_0 = q_0`, `s_N = q_N` (the
//! report's "simplest solution"). The keys must be in one hemisphere; [`super::KeyFrames`]
//! with [`super::Hemisphere::Chain`] (the default) sees to that.
//!
//! A key with an angular velocity ω ([`super::KeyFrames::with_velocities`], §8.2) gets its
//! own inner control points on each side, chosen so that the curve leaves and reaches it
//! at that velocity. Differentiating eq. 6.14, Squad leaves `q_i` with `dq/dh = q_i (L₊ +
//! 2 log(q_i⁻¹ a_i))` and reaches it with `q_i (−L₋ − 2 log(q_i⁻¹ b_i))` (`L± =
//! log(q_i⁻¹ q_{i±1})`, a_i the point used in interval i, b_i in interval i − 1); asking for
//! `dq/dh = q_i v`, `v = ½ Δt q_i⁻¹ (0, ω) q_i` (Δt the interval's parameter length) gives
//! `a_i = q_i exp((v − L₊)/2)` and `b_i = q_i exp(−(v + L₋)/2)`. (Without a velocity, a_i =
//! b_i = s_i, and both tangents are `(L₊ − L₋)/2`: eq. 6.15 is the choice that makes them
//! equal.)

use super::slerp::slerp;
use super::KeyFrames;
use crate::{Quat, Real, Result};

/// Squad over a sequence of keys: the keys and their inner control points.
#[derive(Debug, Clone, PartialEq)]
pub struct Squad<T> {
    q: Vec<Quat<T>>,
    /// The inner control point interval i starts from (`a_i`).
    s: Vec<Quat<T>>,
    /// The inner control point interval i − 1 ends at (`b_i`): `s` but at keys with a
    /// velocity.
    b: Vec<Quat<T>>,
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
        let mut b = s.clone();
        for i in 0..n {
            let Some(w) = keys.velocity(i) else { continue };
            let inv = q[i].conjugate();
            // v = ½ Δt q⁻¹ (0, ω) q for the interval on each side.
            let body = inv * Quat::pure(w) * q[i];
            if i + 1 < n {
                let v = body * (T::HALF * keys.duration(i));
                let l = (inv * q[i + 1]).log()?;
                s[i] = q[i] * ((v - l) * T::HALF).exp();
            }
            if i > 0 {
                let v = body * (T::HALF * keys.duration(i - 1));
                let l = (inv * q[i - 1]).log()?;
                b[i] = q[i] * ((v + l) * -T::HALF).exp();
            }
        }
        Ok(Self { q, s, b })
    }
    /// The keys.
    pub fn keys(&self) -> &[Quat<T>] {
        &self.q
    }
    /// The inner control points `s_i` (eq. 6.15) each interval starts from; at a key with an
    /// angular velocity, the one its outgoing interval uses.
    pub fn controls(&self) -> &[Quat<T>] {
        &self.s
    }
    /// The inner control points each interval ends at: [`Squad::controls`] but at keys with
    /// an angular velocity.
    pub fn incoming_controls(&self) -> &[Quat<T>] {
        &self.b
    }
    /// Eq. 6.14 at `h ∈ [0, 1]` in interval `i` (clamped to the last interval).
    pub fn eval(&self, interval: usize, h: T) -> Quat<T> {
        let i = interval.min(self.q.len() - 2);
        let outer = slerp(self.q[i], self.q[i + 1], h);
        let inner = slerp(self.s[i], self.b[i + 1], h);
        slerp(outer, inner, T::TWO * h * (T::ONE - h))
    }
}
