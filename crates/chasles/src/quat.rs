//! Quaternions `[s, v] = [w, (x, y, z)]` (Dam et al. 1998, §3.3).
//!
//! * Product: Definition 7 / App. B.3, `[s, v][s', v'] = [ss' − v·v', s v' + s' v + v × v']`.
//! * Conjugate, norm, inverse: Definitions 8–10, `q⁻¹ = q* / ‖q‖²`.
//! * Exponential and logarithm: Definitions 14–15, extended here to every quaternion:
//!   `exp[w, v] = e^w [cos‖v‖, sin‖v‖ · v/‖v‖]`, `log q = [ln‖q‖, atan2(‖v‖, w) · v/‖v‖]`.
//!   For a unit quaternion `q = [cos θ, sin θ · n]` this is the report's `log q = [0, θ n]`:
//!   θ is the *half* angle of the rotation q performs.
//! * Power: Definition 16, `q^t = exp(t log q)` (Propositions 15–17 hold).
//! * Rotation: Proposition 21, `v' = q v q*` for unit q rotates v by `2θ` about `n`.
//!
//! Numerical care (the traps of log/exp/pow near the identity and near 2π): `sin‖v‖/‖v‖` and `atan2(‖v‖, w)/‖v‖`
//! are evaluated by series near ‖v‖ = 0, so exp, log and pow have no 0/0 at the identity;
//! near the rotation angle 2π (q ≈ −1) the logarithm keeps the direction of `v`, and at
//! exactly `q = −‖q‖` (no direction left) it picks the x axis, so `exp(log q) = q` still holds.

use crate::real::{atan2_over, sinc};
use crate::{Error, Real, Result, Vec3};
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub};

/// A quaternion `w + xi + yj + zk`. Arrays and files use the order `[w, x, y, z]`
/// (scalar first, as both papers write `[s, v]`); glam and nalgebra store `x, y, z, w`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Quat<T> {
    /// Scalar part s.
    pub w: T,
    /// i component.
    pub x: T,
    /// j component.
    pub y: T,
    /// k component.
    pub z: T,
}

impl<T: Real> Quat<T> {
    /// Builds `w + xi + yj + zk`.
    #[inline]
    pub const fn new(w: T, x: T, y: T, z: T) -> Self {
        Self { w, x, y, z }
    }
    /// The identity rotation `[1, 0]`.
    #[inline]
    pub fn identity() -> Self {
        Self::new(T::ONE, T::ZERO, T::ZERO, T::ZERO)
    }
    /// The zero quaternion.
    #[inline]
    pub fn zero() -> Self {
        Self::new(T::ZERO, T::ZERO, T::ZERO, T::ZERO)
    }
    /// From scalar part `s` and vector part `v`: `[s, v]`.
    #[inline]
    pub fn from_scalar_vector(s: T, v: Vec3<T>) -> Self {
        Self::new(s, v.x, v.y, v.z)
    }
    /// The pure quaternion `[0, v]`.
    #[inline]
    pub fn pure(v: Vec3<T>) -> Self {
        Self::from_scalar_vector(T::ZERO, v)
    }
    /// From `[w, x, y, z]`.
    #[inline]
    pub fn from_array(a: [T; 4]) -> Self {
        Self::new(a[0], a[1], a[2], a[3])
    }
    /// To `[w, x, y, z]`.
    #[inline]
    pub fn to_array(self) -> [T; 4] {
        [self.w, self.x, self.y, self.z]
    }
    /// The vector part `(x, y, z)`.
    #[inline]
    pub fn vector(self) -> Vec3<T> {
        Vec3::new(self.x, self.y, self.z)
    }
    /// The conjugate `[s, −v]` (Definition 8).
    #[inline]
    pub fn conjugate(self) -> Self {
        Self::new(self.w, -self.x, -self.y, -self.z)
    }
    /// The 4D dot product `⟨p, q⟩`.
    #[inline]
    pub fn dot(self, o: Self) -> T {
        self.w * o.w + self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// `‖q‖²`.
    #[inline]
    pub fn norm_squared(self) -> T {
        self.dot(self)
    }
    /// `‖q‖` (Definition 9), without overflow or underflow for components near the ends
    /// of T's range.
    #[inline]
    pub fn norm(self) -> T {
        crate::real::robust_norm(&[self.w, self.x, self.y, self.z])
    }
    /// Whether all four components are finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.w.is_finite() && self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }
    /// Whether `| ‖q‖ − 1 | ≤ tol`.
    #[inline]
    pub fn is_unit(self, tol: T) -> bool {
        (self.norm() - T::ONE).abs() <= tol
    }
    fn check(self, what: &'static str) -> Result<()> {
        crate::error::check_finite(what, &self.to_array())
    }
    /// `q / ‖q‖`; a typed error for a zero or non-finite quaternion.
    pub fn normalize(self) -> Result<Self> {
        self.check("quaternion")?;
        let n = self.norm();
        if n == T::ZERO {
            return Err(Error::ZeroNorm { what: "quaternion" });
        }
        if !n.is_finite() {
            // Components finite but the squared norm overflowed: rescale first.
            let m = self.max_abs();
            return (self / m).normalize();
        }
        Ok(self / n)
    }
    fn max_abs(self) -> T {
        self.w
            .abs()
            .max(self.x.abs())
            .max(self.y.abs())
            .max(self.z.abs())
    }
    /// `q⁻¹ = q* / ‖q‖²` (Definition 10); a typed error for zero or non-finite q.
    pub fn inverse(self) -> Result<Self> {
        self.check("quaternion")?;
        let n2 = self.norm_squared();
        if n2 == T::ZERO {
            return Err(Error::ZeroNorm { what: "quaternion" });
        }
        Ok(self.conjugate() / n2)
    }
    /// The same rotation with a non-negative scalar part (`q` or `−q`): the representative
    /// whose powers `q^t` take the shorter way (Kavan et al. 2006, Figure 3).
    #[inline]
    pub fn to_positive_hemisphere(self) -> Self {
        if self.w < T::ZERO {
            -self
        } else {
            self
        }
    }

    /// The exponential of any quaternion, `exp[w, v] = e^w [cos‖v‖, sin‖v‖ v/‖v‖]`
    /// (Definition 15, extended to a non-zero scalar part). Exact at `v = 0`.
    pub fn exp(self) -> Self {
        let v = self.vector();
        let n = v.norm();
        let e = self.w.exp();
        Self::from_scalar_vector(e * n.cos(), v * (e * sinc(n)))
    }

    /// The logarithm of any non-zero quaternion, `log q = [ln‖q‖, atan2(‖v‖, w) v/‖v‖]`
    /// (Definition 14 for unit q). The vector part has length in [0, π]: the principal value.
    ///
    /// Exact near the identity (series, no 0/0). For `q = −‖q‖` exactly (a rotation by 2π,
    /// no axis left) the x axis is chosen; `exp(log q) = q` holds in every case.
    /// Errors: zero or non-finite input.
    pub fn log(self) -> Result<Self> {
        self.check("quaternion")?;
        let n2 = self.norm_squared();
        if n2 == T::ZERO {
            return Err(Error::ZeroNorm { what: "quaternion" });
        }
        if !n2.is_finite() {
            // Finite components whose squares overflow: log(m q') = [ln m, 0] + log q'.
            let m = self.max_abs();
            return Ok((self / m).log()? + Self::new(m.ln(), T::ZERO, T::ZERO, T::ZERO));
        }
        let ln_norm = T::HALF * n2.ln();
        let v = self.vector();
        let n = v.norm();
        if self.w > T::ZERO {
            return Ok(Self::from_scalar_vector(ln_norm, v * atan2_over(n, self.w)));
        }
        // w ≤ 0: the half-angle is in [π/2, π]; work with the unit direction.
        let dir = match Self::pure(v).normalize() {
            Ok(d) => d.vector(),
            Err(_) => Vec3::unit(0),
        };
        let half_angle = n.atan2(self.w);
        Ok(Self::from_scalar_vector(ln_norm, dir * half_angle))
    }

    /// `q^t = exp(t log q)` (Definition 16). For unit q, `q^t` turns `t` times as far about
    /// the same axis; `q` and `−q` give the two arcs (Kavan et al. 2006, Figure 3).
    pub fn powf(self, t: T) -> Result<Self> {
        Ok((self.log()? * t).exp())
    }

    /// Rotates `v` by the unit quaternion q: `q [0, v] q*` (Proposition 21), evaluated as
    /// `v + 2w (u × v) + 2 u × (u × v)`. For a non-unit q use [`Quat::sandwich`].
    #[inline]
    pub fn rotate(self, v: Vec3<T>) -> Vec3<T> {
        let u = self.vector();
        let t = u.cross(v) * T::TWO;
        v + t * self.w + u.cross(t)
    }

    /// `q [0, v] q⁻¹` for any non-zero q (Proposition 18: the scale of q does not matter).
    pub fn sandwich(self, v: Vec3<T>) -> Result<Vec3<T>> {
        let unit = self.normalize()?;
        Ok(unit.rotate(v))
    }

    /// The angle in [0, π] of the rotation that takes `self` to `other` (both non-zero; q
    /// and −q are the same rotation): `2 atan2(‖v‖, |w|)` of `self* · other`, accurate
    /// also for nearly equal rotations (unlike `2 acos(|⟨p, q⟩|)`).
    pub fn angle_to(self, other: Self) -> Result<T> {
        let d = self.normalize()?.conjugate() * other.normalize()?;
        Ok(T::TWO * d.vector().norm().atan2(d.w.abs()))
    }

    /// Slerp from `self` to `end` at `t` along the shorter rotation (`end` flipped to `−end`
    /// when `⟨self, end⟩ < 0`, Dam et al. footnote 7), as glam's `Quat::slerp` and
    /// nalgebra's `UnitQuaternion::slerp` go: [`crate::interp::slerp::slerp_shortest`] for
    /// unit quaternions (at t = 1 it gives `end` or `−end`, the same rotation), extrapolating
    /// outside [0, 1]. The report's own Slerp, eq. 6.13 along the arc between
    /// the two 4D points as given, is [`crate::interp::slerp::slerp`].
    #[inline(always)]
    pub fn slerp(self, end: Self, t: T) -> Self {
        crate::interp::slerp::slerp_shortest(self, end, t)
    }

    /// Converts the scalar type (e.g. f32 → f64).
    pub fn cast<U: Real>(self) -> Quat<U> {
        Quat::new(
            U::from_f64(self.w.to_f64()),
            U::from_f64(self.x.to_f64()),
            U::from_f64(self.y.to_f64()),
            U::from_f64(self.z.to_f64()),
        )
    }
}

impl<T: Real> Mul for Quat<T> {
    type Output = Self;
    /// Hamilton product (Dam et al. App. B.3).
    #[inline]
    fn mul(self, o: Self) -> Self {
        Self::new(
            self.w * o.w - self.x * o.x - self.y * o.y - self.z * o.z,
            self.w * o.x + self.x * o.w + self.y * o.z - self.z * o.y,
            self.w * o.y - self.x * o.z + self.y * o.w + self.z * o.x,
            self.w * o.z + self.x * o.y - self.y * o.x + self.z * o.w,
        )
    }
}
impl<T: Real> MulAssign for Quat<T> {
    #[inline]
    fn mul_assign(&mut self, o: Self) {
        *self = *self * o;
    }
}
impl<T: Real> Mul<T> for Quat<T> {
    type Output = Self;
    #[inline]
    fn mul(self, s: T) -> Self {
        Self::new(self.w * s, self.x * s, self.y * s, self.z * s)
    }
}
impl<T: Real> Div<T> for Quat<T> {
    type Output = Self;
    #[inline]
    fn div(self, s: T) -> Self {
        Self::new(self.w / s, self.x / s, self.y / s, self.z / s)
    }
}
impl<T: Real> Add for Quat<T> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::new(self.w + o.w, self.x + o.x, self.y + o.y, self.z + o.z)
    }
}
impl<T: Real> AddAssign for Quat<T> {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl<T: Real> Sub for Quat<T> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self::new(self.w - o.w, self.x - o.x, self.y - o.y, self.z - o.z)
    }
}
impl<T: Real> Neg for Quat<T> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self::new(-self.w, -self.x, -self.y, -self.z)
    }
}
