//! Dual numbers `â = a0 + ε aε` with `ε² = 0` (Kavan et al. 2006, §3).
//!
//! Any smooth function extends to dual numbers as `f(a0 + ε aε) = f(a0) + ε f'(a0) aε`;
//! that is how [`Dual::sin`], [`Dual::cos`], [`Dual::sqrt`] and friends are defined, and
//! why dual quaternion exp/log (eq. 2) look like the quaternion ones with dual angles.

use crate::{Error, Real, Result};
use core::ops::{Add, Div, Mul, Neg, Sub};

/// A dual number `re + ε du`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Dual<T> {
    /// Non-dual (real) part `a0`.
    pub re: T,
    /// Dual part `aε`.
    pub du: T,
}

impl<T: Real> Dual<T> {
    /// Builds `re + ε du`.
    #[inline]
    pub const fn new(re: T, du: T) -> Self {
        Self { re, du }
    }
    /// The dual number `re + ε0`.
    #[inline]
    pub fn real(re: T) -> Self {
        Self::new(re, T::ZERO)
    }
    /// The dual conjugate `a0 − ε aε`.
    #[inline]
    pub fn conjugate(self) -> Self {
        Self::new(self.re, -self.du)
    }
    /// Whether both parts are finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.re.is_finite() && self.du.is_finite()
    }
    /// `1/â = 1/a0 − ε aε/a0²`; a typed error for a purely dual number (a0 = 0) or
    /// non-finite input.
    pub fn inverse(self) -> Result<Self> {
        crate::error::check_finite("dual number", &[self.re, self.du])?;
        if self.re == T::ZERO {
            return Err(Error::PurelyDual {
                re: self.re.to_f64(),
                du: self.du.to_f64(),
            });
        }
        let inv = T::ONE / self.re;
        Ok(Self::new(inv, -self.du * inv * inv))
    }
    /// `â / b̂`; a typed error when `b̂` is purely dual.
    pub fn checked_div(self, o: Self) -> Result<Self> {
        Ok(self * o.inverse()?)
    }
    /// `√â = √a0 + ε aε / (2√a0)`; a typed error unless `a0 > 0` (Kavan et al. §3).
    pub fn sqrt(self) -> Result<Self> {
        crate::error::check_finite("dual number", &[self.re, self.du])?;
        // `!(re > 0)` also rejects NaN.
        if self.re <= T::ZERO {
            return Err(Error::NonPositiveSqrt {
                re: self.re.to_f64(),
                du: self.du.to_f64(),
            });
        }
        let r = self.re.sqrt();
        Ok(Self::new(r, self.du / (T::TWO * r)))
    }
    /// `sin â = sin a0 + ε aε cos a0`.
    #[inline]
    pub fn sin(self) -> Self {
        let (s, c) = self.re.sin_cos();
        Self::new(s, self.du * c)
    }
    /// `cos â = cos a0 − ε aε sin a0`.
    #[inline]
    pub fn cos(self) -> Self {
        let (s, c) = self.re.sin_cos();
        Self::new(c, -self.du * s)
    }
    /// `(sin â, cos â)` at once.
    #[inline]
    pub fn sin_cos(self) -> (Self, Self) {
        let (s, c) = self.re.sin_cos();
        (Self::new(s, self.du * c), Self::new(c, -self.du * s))
    }
    /// `exp â = e^a0 (1 + ε aε)`.
    #[inline]
    pub fn exp(self) -> Self {
        let e = self.re.exp();
        Self::new(e, e * self.du)
    }
    /// `ln â = ln a0 + ε aε / a0`; a typed error unless `a0 > 0`.
    pub fn ln(self) -> Result<Self> {
        crate::error::check_finite("dual number", &[self.re, self.du])?;
        if self.re <= T::ZERO {
            return Err(Error::NonPositiveLog {
                re: self.re.to_f64(),
                du: self.du.to_f64(),
            });
        }
        Ok(Self::new(self.re.ln(), self.du / self.re))
    }
    /// `atan2(ŷ, x̂)` with derivative `(x yε − y xε) / (x² + y²)`; at `(0, 0)` the dual part
    /// is 0.
    #[inline]
    pub fn atan2(self, x: Self) -> Self {
        let r2 = self.re * self.re + x.re * x.re;
        let du = if r2 == T::ZERO {
            T::ZERO
        } else {
            (x.re * self.du - self.re * x.du) / r2
        };
        Self::new(self.re.atan2(x.re), du)
    }
}

impl<T: Real> Add for Dual<T> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::new(self.re + o.re, self.du + o.du)
    }
}
impl<T: Real> Sub for Dual<T> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self::new(self.re - o.re, self.du - o.du)
    }
}
impl<T: Real> Neg for Dual<T> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self::new(-self.re, -self.du)
    }
}
impl<T: Real> Mul for Dual<T> {
    type Output = Self;
    /// `(a0 + εaε)(b0 + εbε) = a0b0 + ε(a0bε + aεb0)`.
    #[inline]
    fn mul(self, o: Self) -> Self {
        Self::new(self.re * o.re, self.re * o.du + self.du * o.re)
    }
}
impl<T: Real> Mul<T> for Dual<T> {
    type Output = Self;
    #[inline]
    fn mul(self, s: T) -> Self {
        Self::new(self.re * s, self.du * s)
    }
}
impl<T: Real> Div<T> for Dual<T> {
    type Output = Self;
    #[inline]
    fn div(self, s: T) -> Self {
        Self::new(self.re / s, self.du / s)
    }
}
