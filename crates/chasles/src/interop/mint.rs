//! Conversions with mint (feature `mint`), the interchange types many math crates accept:
//! `Quaternion` (`v` then `s`), `Vector3`, `RowMatrix3/4` and `ColumnMatrix3/4`.

use crate::{Mat3, Mat4, Quat, Real, Vec3};

impl<T: Real> From<mint::Quaternion<T>> for Quat<T> {
    #[inline]
    fn from(q: mint::Quaternion<T>) -> Self {
        Quat::new(q.s, q.v.x, q.v.y, q.v.z)
    }
}
impl<T: Real> From<Quat<T>> for mint::Quaternion<T> {
    #[inline]
    fn from(q: Quat<T>) -> Self {
        mint::Quaternion {
            v: mint::Vector3 {
                x: q.x,
                y: q.y,
                z: q.z,
            },
            s: q.w,
        }
    }
}
impl<T: Real> From<mint::Vector3<T>> for Vec3<T> {
    #[inline]
    fn from(v: mint::Vector3<T>) -> Self {
        Vec3::new(v.x, v.y, v.z)
    }
}
impl<T: Real> From<Vec3<T>> for mint::Vector3<T> {
    #[inline]
    fn from(v: Vec3<T>) -> Self {
        mint::Vector3 {
            x: v.x,
            y: v.y,
            z: v.z,
        }
    }
}
impl<T: Real> From<mint::RowMatrix3<T>> for Mat3<T> {
    fn from(m: mint::RowMatrix3<T>) -> Self {
        let rows: [[T; 3]; 3] = m.into();
        Mat3::from_rows(rows)
    }
}
impl<T: Real> From<Mat3<T>> for mint::RowMatrix3<T> {
    fn from(m: Mat3<T>) -> Self {
        m.m.into()
    }
}
impl<T: Real> From<mint::ColumnMatrix3<T>> for Mat3<T> {
    fn from(m: mint::ColumnMatrix3<T>) -> Self {
        let cols: [[T; 3]; 3] = m.into();
        Mat3::from_rows(cols).transpose()
    }
}
impl<T: Real> From<Mat3<T>> for mint::ColumnMatrix3<T> {
    fn from(m: Mat3<T>) -> Self {
        m.transpose().m.into()
    }
}
impl<T: Real> From<mint::RowMatrix4<T>> for Mat4<T> {
    fn from(m: mint::RowMatrix4<T>) -> Self {
        let rows: [[T; 4]; 4] = m.into();
        Mat4::from_rows(rows)
    }
}
impl<T: Real> From<Mat4<T>> for mint::RowMatrix4<T> {
    fn from(m: Mat4<T>) -> Self {
        m.m.into()
    }
}
impl<T: Real> From<mint::ColumnMatrix4<T>> for Mat4<T> {
    fn from(m: mint::ColumnMatrix4<T>) -> Self {
        let cols: [[T; 4]; 4] = m.into();
        Mat4::from_rows(cols).transpose()
    }
}
impl<T: Real> From<Mat4<T>> for mint::ColumnMatrix4<T> {
    fn from(m: Mat4<T>) -> Self {
        m.transpose().m.into()
    }
}
