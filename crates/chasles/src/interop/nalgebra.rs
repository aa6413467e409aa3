//! Conversions with nalgebra (feature `nalgebra`): `Quaternion`, `UnitQuaternion`,
//! `UnitDualQuaternion`, `Isometry3`, `Vector3`, `Matrix3`, `Matrix4`, for f32 and f64.
//!
//! nalgebra stores quaternions as `i, j, k, w`; the mapping is by name, so the round trips
//! Quaternion, UnitQuaternion, UnitDualQuaternion, Vector3 and the matrices are exact.
//! Into the `Unit` types the conversion is `TryFrom`: a quaternion further than
//! [`crate::default_tolerance`] from unit is refused rather than silently renormalized.
//! An `Isometry3` becomes a dual quaternion by eq. (1) of Kavan et al., which rounds.

use crate::{DualQuat, Error, Mat3, Mat4, Quat, Real, Vec3};
use nalgebra as na;

macro_rules! nalgebra_conversions {
    ($t:ty) => {
        impl From<na::Quaternion<$t>> for Quat<$t> {
            #[inline]
            fn from(q: na::Quaternion<$t>) -> Self {
                Quat::new(q.w, q.i, q.j, q.k)
            }
        }
        impl From<Quat<$t>> for na::Quaternion<$t> {
            #[inline]
            fn from(q: Quat<$t>) -> Self {
                na::Quaternion::new(q.w, q.x, q.y, q.z)
            }
        }
        impl From<na::UnitQuaternion<$t>> for Quat<$t> {
            #[inline]
            fn from(q: na::UnitQuaternion<$t>) -> Self {
                q.into_inner().into()
            }
        }
        impl TryFrom<Quat<$t>> for na::UnitQuaternion<$t> {
            type Error = Error;
            fn try_from(q: Quat<$t>) -> Result<Self, Error> {
                crate::error::check_finite("quaternion", &q.to_array())?;
                if !q.is_unit(crate::default_tolerance()) {
                    return Err(Error::NotUnitQuat {
                        norm: q.norm().to_f64(),
                    });
                }
                Ok(na::UnitQuaternion::new_unchecked(q.into()))
            }
        }
        impl From<na::UnitDualQuaternion<$t>> for DualQuat<$t> {
            #[inline]
            fn from(q: na::UnitDualQuaternion<$t>) -> Self {
                let d = q.into_inner();
                DualQuat::new(d.real.into(), d.dual.into())
            }
        }
        impl TryFrom<DualQuat<$t>> for na::UnitDualQuaternion<$t> {
            type Error = Error;
            fn try_from(q: DualQuat<$t>) -> Result<Self, Error> {
                let q = q.check_unit()?;
                Ok(na::UnitDualQuaternion::new_unchecked(
                    na::DualQuaternion::from_real_and_dual(q.real.into(), q.dual.into()),
                ))
            }
        }
        impl From<na::Isometry3<$t>> for DualQuat<$t> {
            fn from(iso: na::Isometry3<$t>) -> Self {
                DualQuat::from_rotation_translation(
                    iso.rotation.into(),
                    iso.translation.vector.into(),
                )
            }
        }
        impl TryFrom<DualQuat<$t>> for na::Isometry3<$t> {
            type Error = Error;
            fn try_from(q: DualQuat<$t>) -> Result<Self, Error> {
                let q = q.check_unit()?;
                let rot = na::UnitQuaternion::new_unchecked(q.real.into());
                let t: na::Vector3<$t> = q.translation().into();
                Ok(na::Isometry3::from_parts(t.into(), rot))
            }
        }
        impl From<na::Vector3<$t>> for Vec3<$t> {
            #[inline]
            fn from(v: na::Vector3<$t>) -> Self {
                Vec3::new(v.x, v.y, v.z)
            }
        }
        impl From<Vec3<$t>> for na::Vector3<$t> {
            #[inline]
            fn from(v: Vec3<$t>) -> Self {
                na::Vector3::new(v.x, v.y, v.z)
            }
        }
        impl From<na::Matrix3<$t>> for Mat3<$t> {
            fn from(m: na::Matrix3<$t>) -> Self {
                Mat3::from_rows(core::array::from_fn(|i| {
                    core::array::from_fn(|j| m[(i, j)])
                }))
            }
        }
        impl From<Mat3<$t>> for na::Matrix3<$t> {
            fn from(m: Mat3<$t>) -> Self {
                na::Matrix3::from_fn(|i, j| m.m[i][j])
            }
        }
        impl From<na::Matrix4<$t>> for Mat4<$t> {
            fn from(m: na::Matrix4<$t>) -> Self {
                Mat4::from_rows(core::array::from_fn(|i| {
                    core::array::from_fn(|j| m[(i, j)])
                }))
            }
        }
        impl From<Mat4<$t>> for na::Matrix4<$t> {
            fn from(m: Mat4<$t>) -> Self {
                na::Matrix4::from_fn(|i, j| m.m[i][j])
            }
        }
    };
}

nalgebra_conversions!(f32);
nalgebra_conversions!(f64);
