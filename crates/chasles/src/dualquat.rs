//! Dual quaternions `q̂ = q0 + ε qε` (Kavan et al. 2006, §3).
//!
//! * Product `(a0 + εaε)(b0 + εbε) = a0b0 + ε(a0bε + aεb0)`; composition of rigid
//!   transformations is multiplication (`(p̂ q̂)` applies q̂ first).
//! * Three conjugations: quaternion `q̂* = q0* + ε qε*`, dual `q0 − ε qε`, and both
//!   `q0* − ε qε*` (used for transforming points, `q̂ v̂ q̂*` in §3).
//! * Norm `‖q̂‖ = ‖q0‖ + ε ⟨q0, qε⟩/‖q0‖` (a dual number), inverse `q̂* / ‖q̂‖²`; unit iff
//!   `‖q0‖ = 1` and `⟨q0, qε⟩ = 0`.
//! * Rigid transformation, eq. (1): rotation q0 then translation t is `q0 + ε ½ t q0`; back,
//!   `t = 2 qε q0*`.
//! * Normalization (a numerical trap: dividing by ‖q0‖ alone is not enough): divide by ‖q0‖
//!   and remove from qε its part along q0, so the result is exactly unit.
//!
//! As 8 numbers: `[w, x, y, z, wε, xε, yε, zε]`. Exp, log, powers and screw parameters are
//! in [`crate::screw`].

use crate::{Dual, Error, Mat4, Quat, Real, Result, Vec3};
use core::ops::{Add, Mul, Neg, Sub};

/// A dual quaternion `real + ε dual`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DualQuat<T> {
    /// Non-dual part q0 (the rotation, for a unit dual quaternion).
    pub real: Quat<T>,
    /// Dual part qε (`½ t q0` for a unit dual quaternion).
    pub dual: Quat<T>,
}

impl<T: Real> DualQuat<T> {
    /// Builds `real + ε dual`.
    #[inline]
    pub const fn new(real: Quat<T>, dual: Quat<T>) -> Self {
        Self { real, dual }
    }
    /// The identity transformation `1 + ε0`.
    #[inline]
    pub fn identity() -> Self {
        Self::new(Quat::identity(), Quat::zero())
    }
    /// From `[w, x, y, z, wε, xε, yε, zε]`.
    pub fn from_array(a: [T; 8]) -> Self {
        Self::new(
            Quat::new(a[0], a[1], a[2], a[3]),
            Quat::new(a[4], a[5], a[6], a[7]),
        )
    }
    /// To `[w, x, y, z, wε, xε, yε, zε]`.
    pub fn to_array(self) -> [T; 8] {
        let (r, d) = (self.real, self.dual);
        [r.w, r.x, r.y, r.z, d.w, d.x, d.y, d.z]
    }
    /// Whether all eight numbers are finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.real.is_finite() && self.dual.is_finite()
    }
    /// Eq. (1): rotation by the unit quaternion `rotation`, then translation by `t`:
    /// `q0 + ε ½ [0, t] q0`. `rotation` must be unit (see [`Quat::normalize`]).
    #[inline]
    pub fn from_rotation_translation(rotation: Quat<T>, t: Vec3<T>) -> Self {
        Self::new(rotation, Quat::pure(t * T::HALF) * rotation)
    }
    /// Pure rotation `q0 + ε0`.
    #[inline]
    pub fn from_rotation(rotation: Quat<T>) -> Self {
        Self::new(rotation, Quat::zero())
    }
    /// Pure translation `1 + ε ½ t`.
    #[inline]
    pub fn from_translation(t: Vec3<T>) -> Self {
        Self::new(Quat::identity(), Quat::pure(t * T::HALF))
    }
    /// The rotation part q0.
    #[inline]
    pub fn rotation(self) -> Quat<T> {
        self.real
    }
    /// The translation `2 qε q0* / ‖q0‖²` (for a unit dual quaternion `2 qε q0*`, §3).
    #[inline]
    pub fn translation(self) -> Vec3<T> {
        let n2 = self.real.norm_squared();
        (self.dual * self.real.conjugate()).vector() * (T::TWO / n2)
    }
    /// Quaternion conjugation `q0* + ε qε*`.
    #[inline]
    pub fn conjugate(self) -> Self {
        Self::new(self.real.conjugate(), self.dual.conjugate())
    }
    /// Dual conjugation `q0 − ε qε`.
    #[inline]
    pub fn dual_conjugate(self) -> Self {
        Self::new(self.real, -self.dual)
    }
    /// Both conjugations `q0* − ε qε*`.
    #[inline]
    pub fn full_conjugate(self) -> Self {
        Self::new(self.real.conjugate(), -self.dual.conjugate())
    }
    /// `‖q̂‖² = q̂* q̂ = ‖q0‖² + ε 2⟨q0, qε⟩`, always defined.
    #[inline]
    pub fn norm_squared(self) -> Dual<T> {
        Dual::new(self.real.norm_squared(), T::TWO * self.real.dot(self.dual))
    }
    /// `‖q̂‖ = ‖q0‖ + ε ⟨q0, qε⟩/‖q0‖` (§3). Errors: `q0 = 0` (no norm in the dual sense).
    pub fn norm(self) -> Result<Dual<T>> {
        self.norm_squared().sqrt().map_err(|_| Error::ZeroNorm {
            what: "dual quaternion (real part)",
        })
    }
    /// `q̂⁻¹ = q̂* / ‖q̂‖²` (§3). Errors: zero or non-finite real part.
    pub fn inverse(self) -> Result<Self> {
        crate::error::check_finite("dual quaternion", &self.to_array())?;
        let inv = self.norm_squared().inverse().map_err(|_| Error::ZeroNorm {
            what: "dual quaternion (real part)",
        })?;
        Ok(self.conjugate() * inv)
    }
    /// Whether `| ‖q0‖ − 1 | ≤ tol` and `|⟨q0, qε⟩| ≤ tol · max(1, ‖qε‖)`.
    pub fn is_unit(self, tol: T) -> bool {
        let dot = self.real.dot(self.dual).abs();
        (self.real.norm() - T::ONE).abs() <= tol && dot <= tol * T::ONE.max(self.dual.norm())
    }
    /// Checks [`DualQuat::is_unit`] with [`crate::default_tolerance`], returning a typed error.
    pub fn check_unit(self) -> Result<Self> {
        crate::error::check_finite("dual quaternion", &self.to_array())?;
        if self.is_unit(crate::default_tolerance()) {
            Ok(self)
        } else {
            Err(Error::NotUnit {
                norm_deviation: (self.real.norm() - T::ONE).to_f64(),
                dot: self.real.dot(self.dual).to_f64(),
            })
        }
    }
    /// The nearest unit dual quaternion: `q0/‖q0‖ + ε (qε/‖q0‖ − ⟨q0, qε⟩ q0/‖q0‖³)`.
    /// Errors: zero or non-finite real part.
    pub fn normalize(self) -> Result<Self> {
        crate::error::check_finite("dual quaternion", &self.to_array())?;
        let n = self.real.norm();
        if n == T::ZERO {
            return Err(Error::ZeroNorm {
                what: "dual quaternion (real part)",
            });
        }
        let real = self.real / n;
        let dual = self.dual / n;
        Ok(Self::new(real, dual - real * real.dot(dual)))
    }
    /// ScLERP from `self` to `end` (unit dual quaternions) at `t`: the screw motion along
    /// the shorter rotation (Kavan et al. 2006, §4; [`crate::blend::sclerp::sclerp`]), as
    /// nalgebra's `UnitDualQuaternion::sclerp` goes, and defined at a half turn, where
    /// nalgebra's `try_sclerp` gives up. Errors: non-finite input.
    #[inline]
    pub fn sclerp(self, end: Self, t: T) -> Result<Self> {
        crate::blend::sclerp::sclerp(self, end, t)
    }
    /// The same transformation with `w0 ≥ 0` (`q̂` or `−q̂`): its powers take the shorter way.
    #[inline]
    pub fn to_positive_hemisphere(self) -> Self {
        if self.real.w < T::ZERO {
            -self
        } else {
            self
        }
    }
    /// Transforms a point by the unit dual quaternion: rotation, then translation; the
    /// closed form of `q̂ (1 + ε p) q̂*` used by DQS (Kavan et al. 2006, §6):
    /// `p + 2 v0 × (v0 × p + w0 p) + 2 (w0 vε − wε v0 + v0 × vε)`.
    #[inline]
    pub fn transform_point(self, p: Vec3<T>) -> Vec3<T> {
        let (w0, v0) = (self.real.w, self.real.vector());
        let (we, ve) = (self.dual.w, self.dual.vector());
        let r = p + v0.cross(v0.cross(p) + p * w0) * T::TWO;
        r + (ve * w0 - v0 * we + v0.cross(ve)) * T::TWO
    }
    /// Transforms a direction (rotation only) by the unit dual quaternion.
    #[inline]
    pub fn transform_vector(self, v: Vec3<T>) -> Vec3<T> {
        self.real.rotate(v)
    }
    /// The 4×4 homogeneous matrix of the (unit) dual quaternion (§3).
    pub fn to_matrix4(self) -> Mat4<T> {
        Mat4::from_rotation_translation(&self.real.to_rotation_matrix(), self.translation())
    }
    /// The unit dual quaternion of a rigid 4×4 matrix (eq. 1, with the rotation by
    /// Shepperd's method). Errors: non-finite entries, a last row other than `[0, 0, 0, 1]`,
    /// or an upper-left block that is not a rotation.
    pub fn from_matrix4(m: &Mat4<T>) -> Result<Self> {
        if !m.is_finite() {
            return Err(Error::NonFinite { what: "4x4 matrix" });
        }
        let tol = crate::default_tolerance::<T>() * T::from_i32(4);
        let row = m.m[3];
        let dev = row[0]
            .abs()
            .max(row[1].abs())
            .max(row[2].abs())
            .max((row[3] - T::ONE).abs());
        if dev > tol {
            return Err(Error::NotRigid {
                reason: "last row is not [0, 0, 0, 1]",
                deviation: dev.to_f64(),
            });
        }
        let q = Quat::from_rotation_matrix(&m.linear_part()).map_err(|e| match e {
            Error::NotRotation { reason, deviation } => Error::NotRigid { reason, deviation },
            other => other,
        })?;
        Ok(Self::from_rotation_translation(q, m.translation()))
    }
    /// [`DualQuat::from_matrix4`] without the checks, for matrices known to be rigid.
    pub fn from_matrix4_unchecked(m: &Mat4<T>) -> Self {
        Self::from_rotation_translation(
            Quat::from_rotation_matrix_unchecked(&m.linear_part()),
            m.translation(),
        )
    }
    /// Converts the scalar type (e.g. f32 → f64).
    pub fn cast<U: Real>(self) -> DualQuat<U> {
        DualQuat::new(self.real.cast(), self.dual.cast())
    }
}

impl<T: Real> Mul for DualQuat<T> {
    type Output = Self;
    /// `(a0 + εaε)(b0 + εbε) = a0b0 + ε(a0bε + aεb0)`.
    #[inline]
    fn mul(self, o: Self) -> Self {
        Self::new(self.real * o.real, self.real * o.dual + self.dual * o.real)
    }
}
impl<T: Real> Mul<Dual<T>> for DualQuat<T> {
    type Output = Self;
    /// Multiplication by a dual scalar (which commutes with dual quaternions).
    #[inline]
    fn mul(self, s: Dual<T>) -> Self {
        Self::new(self.real * s.re, self.dual * s.re + self.real * s.du)
    }
}
impl<T: Real> Mul<T> for DualQuat<T> {
    type Output = Self;
    #[inline]
    fn mul(self, s: T) -> Self {
        Self::new(self.real * s, self.dual * s)
    }
}
impl<T: Real> Add for DualQuat<T> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::new(self.real + o.real, self.dual + o.dual)
    }
}
impl<T: Real> Sub for DualQuat<T> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self::new(self.real - o.real, self.dual - o.dual)
    }
}
impl<T: Real> Neg for DualQuat<T> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self::new(-self.real, -self.dual)
    }
}
