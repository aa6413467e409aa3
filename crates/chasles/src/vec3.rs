//! 3-vectors: points, translations, rotation axes and screw moments.

use crate::{Error, Real, Result};
use core::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// A 3-vector `[x, y, z]` in a right-handed frame (Dam et al. 1998, App. A).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Vec3<T> {
    /// x.
    pub x: T,
    /// y.
    pub y: T,
    /// z.
    pub z: T,
}

impl<T: Real> Vec3<T> {
    /// Builds a vector.
    #[inline]
    pub const fn new(x: T, y: T, z: T) -> Self {
        Self { x, y, z }
    }
    /// The zero vector.
    #[inline]
    pub fn zero() -> Self {
        Self::new(T::ZERO, T::ZERO, T::ZERO)
    }
    /// The x, y or z unit vector (`axis` 0, 1, 2; anything else gives z).
    #[inline]
    pub fn unit(axis: usize) -> Self {
        match axis {
            0 => Self::new(T::ONE, T::ZERO, T::ZERO),
            1 => Self::new(T::ZERO, T::ONE, T::ZERO),
            _ => Self::new(T::ZERO, T::ZERO, T::ONE),
        }
    }
    /// From `[x, y, z]`.
    #[inline]
    pub fn from_array(a: [T; 3]) -> Self {
        Self::new(a[0], a[1], a[2])
    }
    /// To `[x, y, z]`.
    #[inline]
    pub fn to_array(self) -> [T; 3] {
        [self.x, self.y, self.z]
    }
    /// Component by index (0, 1, 2; anything else gives z).
    #[inline]
    pub fn get(self, i: usize) -> T {
        match i {
            0 => self.x,
            1 => self.y,
            _ => self.z,
        }
    }
    /// Dot product.
    #[inline]
    pub fn dot(self, o: Self) -> T {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// Cross product (right-handed).
    #[inline]
    pub fn cross(self, o: Self) -> Self {
        Self::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }
    /// Squared length.
    #[inline]
    pub fn norm_squared(self) -> T {
        self.dot(self)
    }
    /// Length, without overflow or underflow for components near the ends of T's range.
    #[inline]
    pub fn norm(self) -> T {
        crate::real::robust_norm(&[self.x, self.y, self.z])
    }
    /// The unit vector in the same direction; a typed error for zero or non-finite input.
    pub fn normalize(self) -> Result<Self> {
        crate::error::check_finite("vector", &self.to_array())?;
        let n = self.norm();
        if n == T::ZERO || !n.is_finite() {
            return Err(Error::ZeroNorm { what: "vector" });
        }
        Ok(self / n)
    }
    /// Whether all components are finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }
    /// Some unit vector perpendicular to `self` (which need not be unit; zero gives x).
    pub fn any_perpendicular(self) -> Self {
        let a = Self::new(self.x.abs(), self.y.abs(), self.z.abs());
        // Cross with the axis of the smallest component: best conditioned.
        let other = if a.x <= a.y && a.x <= a.z {
            Self::unit(0)
        } else if a.y <= a.z {
            Self::unit(1)
        } else {
            Self::unit(2)
        };
        self.cross(other).normalize().unwrap_or(Self::unit(0))
    }
    /// Converts the scalar type (e.g. f32 → f64).
    pub fn cast<U: Real>(self) -> Vec3<U> {
        Vec3::new(
            U::from_f64(self.x.to_f64()),
            U::from_f64(self.y.to_f64()),
            U::from_f64(self.z.to_f64()),
        )
    }
}

impl<T: Real> Add for Vec3<T> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}
impl<T: Real> AddAssign for Vec3<T> {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl<T: Real> Sub for Vec3<T> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}
impl<T: Real> SubAssign for Vec3<T> {
    #[inline]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}
impl<T: Real> Neg for Vec3<T> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}
impl<T: Real> Mul<T> for Vec3<T> {
    type Output = Self;
    #[inline]
    fn mul(self, s: T) -> Self {
        Self::new(self.x * s, self.y * s, self.z * s)
    }
}
impl<T: Real> Div<T> for Vec3<T> {
    type Output = Self;
    #[inline]
    fn div(self, s: T) -> Self {
        Self::new(self.x / s, self.y / s, self.z / s)
    }
}
