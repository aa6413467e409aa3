//! Conversions with glam (feature `glam`): `Quat`/`DQuat`, `Vec3`/`DVec3`, `Mat3`/`DMat3`,
//! `Mat4`/`DMat4`. glam quaternions are `x, y, z, w` in memory; the mapping is by name, so
//! round trips are exact.

use crate::{Mat3, Mat4, Quat, Vec3};

macro_rules! glam_conversions {
    ($t:ty, $gq:ty, $gv:ty, $gm3:ty, $gm4:ty) => {
        impl From<$gq> for Quat<$t> {
            #[inline]
            fn from(q: $gq) -> Self {
                Quat::new(q.w, q.x, q.y, q.z)
            }
        }
        impl From<Quat<$t>> for $gq {
            #[inline]
            fn from(q: Quat<$t>) -> Self {
                <$gq>::from_xyzw(q.x, q.y, q.z, q.w)
            }
        }
        impl From<$gv> for Vec3<$t> {
            #[inline]
            fn from(v: $gv) -> Self {
                Vec3::new(v.x, v.y, v.z)
            }
        }
        impl From<Vec3<$t>> for $gv {
            #[inline]
            fn from(v: Vec3<$t>) -> Self {
                <$gv>::new(v.x, v.y, v.z)
            }
        }
        impl From<$gm3> for Mat3<$t> {
            fn from(m: $gm3) -> Self {
                Mat3::from_rows(m.to_cols_array_2d()).transpose()
            }
        }
        impl From<Mat3<$t>> for $gm3 {
            fn from(m: Mat3<$t>) -> Self {
                <$gm3>::from_cols_array_2d(&m.transpose().m)
            }
        }
        impl From<$gm4> for Mat4<$t> {
            fn from(m: $gm4) -> Self {
                Mat4::from_rows(m.to_cols_array_2d()).transpose()
            }
        }
        impl From<Mat4<$t>> for $gm4 {
            fn from(m: Mat4<$t>) -> Self {
                <$gm4>::from_cols_array_2d(&m.transpose().m)
            }
        }
    };
}

glam_conversions!(f32, glam::Quat, glam::Vec3, glam::Mat3, glam::Mat4);
glam_conversions!(f64, glam::DQuat, glam::DVec3, glam::DMat3, glam::DMat4);
