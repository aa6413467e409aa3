//! Axis–angle and rotation-vector conversions (Dam et al. 1998, Proposition 21 and §3.3.6):
//! the unit quaternion `[cos(θ/2), sin(θ/2) n]` rotates by θ counter-clockwise about the
//! unit axis n (right-hand rule, App. A).

use crate::{Error, Quat, Real, Result, Vec3};

impl<T: Real> Quat<T> {
    /// The unit quaternion rotating by `angle` (radians, counter-clockwise) about `axis`:
    /// `[cos(angle/2), sin(angle/2) axis/‖axis‖]`. Errors: zero or non-finite axis/angle.
    pub fn from_axis_angle(axis: Vec3<T>, angle: T) -> Result<Self> {
        crate::error::check_finite("angle", &[angle])?;
        let a = axis.normalize().map_err(|e| match e {
            Error::ZeroNorm { .. } => Error::ZeroNorm {
                what: "rotation axis",
            },
            other => other,
        })?;
        let (s, c) = (angle * T::HALF).sin_cos();
        Ok(Self::from_scalar_vector(c, a * s))
    }

    /// The rotation about the x (0), y (1) or z (2) axis by `angle`.
    #[inline]
    pub fn from_axis_index(axis: usize, angle: T) -> Self {
        let (s, c) = (angle * T::HALF).sin_cos();
        Self::from_scalar_vector(c, Vec3::unit(axis) * s)
    }

    /// Unit axis and angle in [0, 2π] with `q/‖q‖ = [cos(angle/2), sin(angle/2) axis]`.
    /// The sign of q is kept: `−q` gives `(axis, 2π − angle)` with the opposite axis, the
    /// same rotation the long way round. The identity gives the x axis and angle 0.
    /// Errors: zero or non-finite input.
    pub fn to_axis_angle(self) -> Result<(Vec3<T>, T)> {
        let l = self.normalize()?.log()?;
        let v = l.vector();
        let half = v.norm();
        let axis = if half == T::ZERO {
            Vec3::unit(0)
        } else {
            v / half
        };
        Ok((axis, half * T::TWO))
    }

    /// The rotation vector `axis · angle` (angle in [0, π], the shorter way). Errors: zero
    /// or non-finite input.
    pub fn to_rotation_vector(self) -> Result<Vec3<T>> {
        Ok(self.normalize()?.to_positive_hemisphere().log()?.vector() * T::TWO)
    }

    /// The unit quaternion of the rotation vector `r` (angle `‖r‖` about `r/‖r‖`); exact
    /// for tiny `r`.
    pub fn from_rotation_vector(r: Vec3<T>) -> Result<Self> {
        crate::error::check_finite("rotation vector", &r.to_array())?;
        Ok(Self::pure(r * T::HALF).exp())
    }
}
