//! Row-major 3×3 and 4×4 matrices acting on column vectors (`p' = M p`), as in
//! Dam et al. 1998, App. B.1 and B.3 and Kavan et al. 2006, §3.

use crate::{Real, Vec3};
use core::ops::Mul;

/// A 3×3 matrix, row-major: `m[row][col]`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Mat3<T> {
    /// Rows.
    pub m: [[T; 3]; 3],
}

/// A 4×4 homogeneous matrix, row-major: `m[row][col]`; a rigid transformation has the
/// rotation in the upper-left 3×3, the translation in the last column and `[0, 0, 0, 1]`
/// as the last row.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Mat4<T> {
    /// Rows.
    pub m: [[T; 4]; 4],
}

impl<T: Real> Mat3<T> {
    /// From rows.
    #[inline]
    pub const fn from_rows(m: [[T; 3]; 3]) -> Self {
        Self { m }
    }
    /// The identity.
    pub fn identity() -> Self {
        let mut m = [[T::ZERO; 3]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            row[i] = T::ONE;
        }
        Self { m }
    }
    /// The transpose.
    pub fn transpose(&self) -> Self {
        let mut m = [[T::ZERO; 3]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = self.m[j][i];
            }
        }
        Self { m }
    }
    /// The determinant.
    pub fn determinant(&self) -> T {
        let m = &self.m;
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    }
    /// `M v`.
    #[inline]
    pub fn mul_vec(&self, v: Vec3<T>) -> Vec3<T> {
        let m = &self.m;
        Vec3::new(
            m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z,
        )
    }
    /// All nine entries, row by row.
    pub fn to_row_major(&self) -> [T; 9] {
        let mut out = [T::ZERO; 9];
        for (k, v) in out.iter_mut().enumerate() {
            *v = self.m[k / 3][k % 3];
        }
        out
    }
    /// From nine entries, row by row.
    pub fn from_row_major(a: [T; 9]) -> Self {
        let mut m = [[T::ZERO; 3]; 3];
        for (k, v) in a.iter().enumerate() {
            m[k / 3][k % 3] = *v;
        }
        Self { m }
    }
    /// The largest absolute entry of `self − other`.
    pub fn max_abs_diff(&self, other: &Self) -> T {
        let (a, b) = (self.to_row_major(), other.to_row_major());
        a.iter()
            .zip(b.iter())
            .fold(T::ZERO, |acc, (x, y)| acc.max((*x - *y).abs()))
    }
    /// Whether every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.to_row_major().iter().all(|v| v.is_finite())
    }
    /// How far from a rotation: `max(‖MᵀM − I‖∞, |det M − 1|)`.
    pub fn rotation_deviation(&self) -> T {
        let mtm = self.transpose() * *self;
        mtm.max_abs_diff(&Self::identity())
            .max((self.determinant() - T::ONE).abs())
    }
}

impl<T: Real> Mul for Mat3<T> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let mut m = [[T::ZERO; 3]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = self.m[i][0] * o.m[0][j] + self.m[i][1] * o.m[1][j] + self.m[i][2] * o.m[2][j];
            }
        }
        Self { m }
    }
}

impl<T: Real> Mat4<T> {
    /// From rows.
    #[inline]
    pub const fn from_rows(m: [[T; 4]; 4]) -> Self {
        Self { m }
    }
    /// The identity.
    pub fn identity() -> Self {
        Self::from_rotation_translation(&Mat3::identity(), Vec3::zero())
    }
    /// The rigid transformation `[R t; 0 1]`.
    pub fn from_rotation_translation(r: &Mat3<T>, t: Vec3<T>) -> Self {
        let mut m = [[T::ZERO; 4]; 4];
        for (i, (row, r_row)) in m.iter_mut().zip(r.m.iter()).enumerate() {
            row[..3].copy_from_slice(r_row);
            row[3] = t.get(i);
        }
        m[3][3] = T::ONE;
        Self { m }
    }
    /// The upper-left 3×3 block.
    pub fn linear_part(&self) -> Mat3<T> {
        let mut r = [[T::ZERO; 3]; 3];
        for (i, row) in r.iter_mut().enumerate() {
            row.copy_from_slice(&self.m[i][..3]);
        }
        Mat3::from_rows(r)
    }
    /// The last column's first three entries.
    pub fn translation(&self) -> Vec3<T> {
        Vec3::new(self.m[0][3], self.m[1][3], self.m[2][3])
    }
    /// `M [p, 1]`, dropping the homogeneous coordinate (affine part only).
    pub fn transform_point(&self, p: Vec3<T>) -> Vec3<T> {
        self.linear_part().mul_vec(p) + self.translation()
    }
    /// All sixteen entries, row by row.
    pub fn to_row_major(&self) -> [T; 16] {
        let mut out = [T::ZERO; 16];
        for (k, v) in out.iter_mut().enumerate() {
            *v = self.m[k / 4][k % 4];
        }
        out
    }
    /// From sixteen entries, row by row.
    pub fn from_row_major(a: [T; 16]) -> Self {
        let mut m = [[T::ZERO; 4]; 4];
        for (k, v) in a.iter().enumerate() {
            m[k / 4][k % 4] = *v;
        }
        Self { m }
    }
    /// The largest absolute entry of `self − other`.
    pub fn max_abs_diff(&self, other: &Self) -> T {
        let (a, b) = (self.to_row_major(), other.to_row_major());
        a.iter()
            .zip(b.iter())
            .fold(T::ZERO, |acc, (x, y)| acc.max((*x - *y).abs()))
    }
    /// Whether every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.to_row_major().iter().all(|v| v.is_finite())
    }
}

impl<T: Real> Mul for Mat4<T> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let mut m = [[T::ZERO; 4]; 4];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                let mut acc = T::ZERO;
                for k in 0..4 {
                    acc += self.m[i][k] * o.m[k][j];
                }
                *v = acc;
            }
        }
        Self { m }
    }
}
