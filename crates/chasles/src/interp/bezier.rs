//! Spherical Bézier curves evaluated by de Casteljau's construction with Slerp (K.
//! Shoemake, "Animating rotation with quaternion curves", SIGGRAPH 1985, §§ 4–5).
//!
//! Each interval `q_n → q_{n+1}` is a cubic Bézier curve on the sphere with control points
//! `q_n, a_n, b_{n+1}, q_{n+1}`, evaluated by repeated Slerp (de Casteljau):
//!
//! ```text
//! p₀₁ = Slerp(q_n, a_n, h),  p₁₂ = Slerp(a_n, b_{n+1}, h),  p₂₃ = Slerp(b_{n+1}, q_{n+1}, h)
//! p₀₁₂ = Slerp(p₀₁, p₁₂, h), p₁₂₃ = Slerp(p₁₂, p₂₃, h),    q(h) = Slerp(p₀₁₂, p₁₂₃, h).
//! ```
//!
//! The inner control points come from the neighbouring keys with Shoemake's two spherical
//! operations, `Double(p, q) = 2 (p·q) q − p` (p reflected through q: `q p* q` for unit
//! quaternions) and `Bisect(p, q) = (p + q)/‖p + q‖` (the midpoint of the arc):
//! `â_n = Bisect(Double(q_{n−1}, q_n), q_{n+1})` is the point on the tangent great circle
//! that the Catmull–Rom tangent reaches (in flat space `q_n + (q_{n+1} − q_{n−1})/2`); the
//! control point is a third of the way there, `a_n = Slerp(q_n, â_n, 1/3)`, as in the
//! Bézier form of a cubic with that tangent, and `b_n = Double(a_n, q_n)` is its reflection
//! through the key.
//!
//! **Properties** (tested by number): the curve passes through the keys (de Casteljau at
//! `h = 0, 1`); it is C¹ at every key in the parameter `n + h`, because `b_n` is `a_n`
//! reflected through `q_n` on a great circle, so both legs have the same log-space length
//! `log(q_n* a_n)` and the curve leaves and reaches `q_n` with the angular velocity
//! `6 log(q_n* a_n)` (three legs' worth, doubled to a rotation). With key times of unequal
//! spans it is only G¹ (the direction is continuous; the speed per unit of time jumps by
//! the ratio of the spans), as Shoemake's construction knows no times. On keys about one
//! axis it equals the Catmull–Rom spline ([`super::catmull_rom`]). Ends: the phantom
//! `q_{−1} = Double(q_1, q_0)` (and likewise after the last key) puts `a_0` on the first
//! chord, so two keys give Slerp. `Bisect` has no answer when its two points are antipodal
//! (both neighbours a half turn from the key); the control point is then the key itself.

use super::slerp::slerp;
use super::KeyFrames;
use crate::{Quat, Real, Result};

/// Shoemake's `Double(p, q) = 2 (p·q) q − p`: p reflected through q.
pub fn double<T: Real>(p: Quat<T>, q: Quat<T>) -> Quat<T> {
    q * (T::TWO * p.dot(q)) - p
}

/// Shoemake's `Bisect(p, q) = (p + q)/‖p + q‖`; `None` when `p + q` is zero.
pub fn bisect<T: Real>(p: Quat<T>, q: Quat<T>) -> Option<Quat<T>> {
    (p + q).normalize().ok()
}

/// A spherical Bézier spline through key frames with Shoemake's control points.
#[derive(Debug, Clone, PartialEq)]
pub struct Bezier<T> {
    q: Vec<Quat<T>>,
    /// `a_n`: the control point after key n.
    a: Vec<Quat<T>>,
    /// `b_n`: the control point before key n.
    b: Vec<Quat<T>>,
}

impl<T: Real> Bezier<T> {
    /// Shoemake's control points for the keys (module docs).
    pub fn new(keys: &KeyFrames<T>) -> Result<Self> {
        let q = keys.quats().to_vec();
        let n = q.len();
        let third = T::ONE / T::from_i32(3);
        let mut a = Vec::with_capacity(n);
        let mut b = Vec::with_capacity(n);
        for k in 0..n {
            let prev = if k == 0 { double(q[1], q[0]) } else { q[k - 1] };
            let next = if k + 1 == n {
                double(q[n - 2], q[n - 1])
            } else {
                q[k + 1]
            };
            let far = bisect(double(prev, q[k]), next).unwrap_or(q[k]);
            let ak = slerp(q[k], far, third);
            a.push(ak);
            b.push(double(ak, q[k]));
        }
        Ok(Self { q, a, b })
    }
    /// The keys.
    pub fn keys(&self) -> &[Quat<T>] {
        &self.q
    }
    /// The control points after each key, `a_n`.
    pub fn after(&self) -> &[Quat<T>] {
        &self.a
    }
    /// The control points before each key, `b_n`.
    pub fn before(&self) -> &[Quat<T>] {
        &self.b
    }
    /// The curve at `h ∈ [0, 1]` into interval `i` (clamped to the last interval): de
    /// Casteljau with Slerp.
    pub fn eval(&self, interval: usize, h: T) -> Quat<T> {
        let i = interval.min(self.q.len() - 2);
        let (p0, p1, p2, p3) = (self.q[i], self.a[i], self.b[i + 1], self.q[i + 1]);
        let p01 = slerp(p0, p1, h);
        let p12 = slerp(p1, p2, h);
        let p23 = slerp(p2, p3, h);
        slerp(slerp(p01, p12, h), slerp(p12, p23, h), h)
    }
}
