//! Spherical Catmull–Rom splines by Schlag's geometric construction (J. Schlag, "Using
//! geometric constructions to interpolate orientation with quaternions", Graphics Gems II,
//! 1991, pp. 377–380), after Barry & Goldman's recursive evaluation of Catmull–Rom splines
//! (SIGGRAPH 1988): the three levels of linear interpolation that make a Catmull–Rom
//! segment in flat space, each replaced by Slerp.
//!
//! With knots `t_{i−1} < t_i < t_{i+1} < t_{i+2}` (the key times, or `0, 1, 2, …` without
//! them) and `t ∈ [t_i, t_{i+1}]`, the segment from `q_i` to `q_{i+1}` is
//!
//! ```text
//! A₁ = Slerp(q_{i−1}, q_i,     (t − t_{i−1})/(t_i − t_{i−1}))      (extrapolates: ≥ 1)
//! A₂ = Slerp(q_i,     q_{i+1}, (t − t_i)/(t_{i+1} − t_i))
//! A₃ = Slerp(q_{i+1}, q_{i+2}, (t − t_{i+1})/(t_{i+2} − t_{i+1})) (extrapolates: ≤ 0)
//! B₁ = Slerp(A₁, A₂, (t − t_{i−1})/(t_{i+1} − t_{i−1}))
//! B₂ = Slerp(A₂, A₃, (t − t_i)/(t_{i+2} − t_i))
//! q(t) = Slerp(B₁, B₂, (t − t_i)/(t_{i+1} − t_i)).
//! ```
//!
//! A₁ and A₃ are Slerp in eq. 6.4's form, `Slerp(p, q, h) = p (p*q)^h`, evaluated from
//! their nearer end (`A₁ = q_i exp((t − t_i) v)` with `v = log(q_{i−1}* q_i)/(t_i − t_{i−1})`,
//! the same great circle), so that the extrapolation never takes a logarithm of a point
//! past the keys.
//!
//! **Properties.** The curve passes through every key (at `t = t_i`, A₁ = A₂ = B₁ = q_i).
//! It is C¹: at a key B₁ = B₂, so the last Slerp adds nothing to the derivative and
//! `q'(t_i) = q_i v_i` with the log-space velocity
//! `v_i = α_i log(q_{i−1}* q_i)/Δ_{i−1} + β_i log(q_i* q_{i+1})/Δ_i`,
//! `α_i = Δ_i/(Δ_{i−1} + Δ_i)`, `β_i = Δ_{i−1}/(Δ_{i−1} + Δ_i)`, `Δ_i = t_{i+1} − t_i` — the
//! same from both sides (the angular velocity in the body frame is `2 v_i`). With equal
//! spans this is the Catmull–Rom tangent `(log(q_{i−1}* q_i) + log(q_i* q_{i+1}))/2`.
//! On keys about one axis the curve is the scalar Catmull–Rom spline of the angles.
//!
//! **Ends.** A phantom key beyond each end, the reflection of the second key through the
//! end key (`q_{−1} = q_0 q_1* q_0`, one span before): the end tangent is then the chord's,
//! as Squad's `s_0 = q_0` makes it (Dam et al. §6.2.1), and two keys give Slerp.
//!
//! **Limits.** Every Slerp of the construction takes the shorter arc between its two
//! points. A₁ runs ahead of q_i along the incoming chord for a whole span Δ_i, so when a
//! span is much longer than the one before it (or the outgoing velocities are large, as
//! extreme [`super::tcb`] parameters make them) A₁ can get more than a half turn in 4D from
//! A₂; near there the construction is ill-conditioned and the curve swings fast, and on a
//! great circle, where the points meet exactly antipodal, it jumps. With equal spans A₁
//! and A₂ stay within `φ_{i−1} + φ_i ≤ π` (the keys' half-angles), so Catmull–Rom itself
//! is safe there; roughly, keep `(Δ_i/Δ_{i−1}) φ_{i−1} + φ_i` (and the mirror image)
//! below π.
//!
//! The construction takes any velocities for the outer geodesics A₁ and A₃:
//! [`super::tcb`] uses it for Kochanek–Bartels splines, which equal this curve when tension,
//! continuity and bias are 0.

use super::slerp::slerp;
use super::KeyFrames;
use crate::{Quat, Real, Result, Vec3};

/// A spherical Catmull–Rom spline (or, with other outer velocities, a Kochanek–Bartels
/// spline) through key frames: the keys, the spans and the velocities of the outer
/// geodesics of Schlag's construction.
#[derive(Debug, Clone, PartialEq)]
pub struct CatmullRom<T> {
    q: Vec<Quat<T>>,
    /// Δ_i, one per interval.
    span: Vec<T>,
    /// Per key: the log-space velocity of A₁, the geodesic through q_i used when q_i
    /// starts an interval.
    before: Vec<Vec3<T>>,
    /// Per key: the log-space velocity of A₃, the geodesic through q_i used when q_i ends
    /// an interval.
    after: Vec<Vec3<T>>,
}

/// `log(p* q)`'s vector part: the log-space step from `p` to `q` (half the rotation
/// vector), `q` as given.
pub(crate) fn step<T: Real>(p: Quat<T>, q: Quat<T>) -> Result<Vec3<T>> {
    Ok((p.conjugate() * q).log()?.vector())
}

/// The chord velocities `u_i = log(q_i* q_{i+1})/Δ_i`, one per interval, and the spans.
pub(crate) fn chords<T: Real>(keys: &KeyFrames<T>) -> Result<(Vec<Vec3<T>>, Vec<T>)> {
    let q = keys.quats();
    let span: Vec<T> = (0..q.len() - 1).map(|i| keys.span(i)).collect();
    let u = (0..q.len() - 1)
        .map(|i| Ok(step(q[i], q[i + 1])? / span[i]))
        .collect::<Result<Vec<_>>>()?;
    Ok((u, span))
}

/// The weights `(α_i, β_i)` of the incoming and outgoing chord velocities in the tangent at
/// key `i` (see the module docs), with the phantom spans at the ends.
pub(crate) fn weights<T: Real>(span: &[T], i: usize) -> (T, T) {
    let prev = span[i.saturating_sub(1).min(span.len() - 1)];
    let next = span[i.min(span.len() - 1)];
    let sum = prev + next;
    (next / sum, prev / sum)
}

impl<T: Real> CatmullRom<T> {
    /// The Catmull–Rom spline through the keys (knots at the key times, else 0, 1, 2, …).
    /// Errors: none for valid keys (the logarithms of unit quaternions exist).
    pub fn new(keys: &KeyFrames<T>) -> Result<Self> {
        let (u, span) = chords(keys)?;
        let n = keys.len();
        // A₁ at key i runs along the incoming chord (the outgoing one at key 0, the
        // phantom's reflection); A₃ along the outgoing chord (the incoming at the end).
        let before = (0..n).map(|i| u[i.saturating_sub(1)]).collect();
        let after = (0..n).map(|i| u[i.min(n - 2)]).collect();
        Ok(Self::from_parts(keys.quats().to_vec(), span, before, after))
    }
    /// The construction with given outer velocities (see the fields).
    pub(crate) fn from_parts(
        q: Vec<Quat<T>>,
        span: Vec<T>,
        before: Vec<Vec3<T>>,
        after: Vec<Vec3<T>>,
    ) -> Self {
        Self {
            q,
            span,
            before,
            after,
        }
    }
    /// The keys.
    pub fn keys(&self) -> &[Quat<T>] {
        &self.q
    }
    /// The curve at `h ∈ [0, 1]` into interval `i` (clamped to the last interval), i.e. at
    /// `t = t_i + h Δ_i`: Schlag's three levels of Slerp (module docs).
    pub fn eval(&self, interval: usize, h: T) -> Quat<T> {
        let i = interval.min(self.q.len() - 2);
        let last = self.span.len() - 1;
        let d = self.span[i];
        let dp = self.span[i.saturating_sub(1)];
        let dn = self.span[(i + 1).min(last)];
        let (a, b) = (self.q[i], self.q[i + 1]);
        let a1 = a * Quat::pure(self.before[i] * (h * d)).exp();
        let a2 = slerp(a, b, h);
        let a3 = b * Quat::pure(self.after[i + 1] * (-(T::ONE - h) * d)).exp();
        let b1 = slerp(a1, a2, (dp + h * d) / (dp + d));
        let b2 = slerp(a2, a3, h * d / (d + dn));
        slerp(b1, b2, h)
    }
    /// The angular velocity (body frame, radians per unit of the parameter) with which the
    /// curve leaves each key (the last key: arrives), from the closed form of the module
    /// docs: twice the log-space velocity.
    pub fn leaving(&self) -> Vec<Vec3<T>> {
        let n = self.q.len();
        (0..n)
            .map(|i| {
                let (alpha, beta) = weights(&self.span, i);
                if i + 1 == n {
                    return self.arriving_at(i, alpha, beta);
                }
                let u = self.chord(i);
                (self.before[i] * alpha + u * beta) * T::TWO
            })
            .collect()
    }
    /// The angular velocity (body frame, radians per unit of the parameter) with which the
    /// curve arrives at each key (the first key: leaves).
    pub fn arriving(&self) -> Vec<Vec3<T>> {
        let n = self.q.len();
        (0..n)
            .map(|i| {
                let (alpha, beta) = weights(&self.span, i);
                if i == 0 {
                    return (self.before[0] * alpha + self.chord(0) * beta) * T::TWO;
                }
                self.arriving_at(i, alpha, beta)
            })
            .collect()
    }
    fn arriving_at(&self, i: usize, alpha: T, beta: T) -> Vec3<T> {
        (self.chord(i - 1) * alpha + self.after[i] * beta) * T::TWO
    }
    /// `log(q_i* q_{i+1})/Δ_i` (zero if the logarithm fails, which unit keys never do).
    fn chord(&self, i: usize) -> Vec3<T> {
        step(self.q[i], self.q[i + 1]).unwrap_or(Vec3::zero()) / self.span[i]
    }
}
