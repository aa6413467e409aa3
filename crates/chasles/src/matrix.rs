//! Row-major square matrices acting on column vectors (`p' = M p`), as in Dam et al. 1998,
//! App. B.1 and B.3 and Kavan et al. 2006, §3: [`Mat3`] for rotations, [`Mat4`] for
//! homogeneous (rigid) transformations — both the one type [`Mat`].

use crate::{Real, Vec3};
use core::ops::Mul;

/// An N×N matrix, row-major: `m[row][col]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mat<T, const N: usize> {
    /// Rows.
    pub m: [[T; N]; N],
}

/// A 3×3 matrix (rotations).
pub type Mat3<T> = Mat<T, 3>;

/// A 4×4 homogeneous matrix; a rigid transformation has the rotation in the upper-left
/// 3×3, the translation in the last column and `[0, 0, 0, 1]` as the last row.
pub type Mat4<T> = Mat<T, 4>;

impl<T: Real, const N: usize> Default for Mat<T, N> {
    fn default() -> Self {
        Self {
            m: [[T::ZERO; N]; N],
        }
    }
}

impl<T: Real, const N: usize> Mat<T, N> {
    /// From rows.
    #[inline]
    pub const fn from_rows(m: [[T; N]; N]) -> Self {
        Self { m }
    }
    /// The identity.
    pub fn identity() -> Self {
        Self::from_rows(core::array::from_fn(|i| {
            core::array::from_fn(|j| if i == j { T::ONE } else { T::ZERO })
        }))
    }
    /// The transpose.
    pub fn transpose(&self) -> Self {
        Self::from_rows(core::array::from_fn(|i| {
            core::array::from_fn(|j| self.m[j][i])
        }))
    }
    /// The entries, row by row.
    pub fn entries(&self) -> impl Iterator<Item = T> + '_ {
        self.m.iter().flat_map(|r| r.iter().copied())
    }
    /// The largest absolute entry of `self − other`.
    pub fn max_abs_diff(&self, other: &Self) -> T {
        self.entries()
            .zip(other.entries())
            .fold(T::ZERO, |acc, (x, y)| acc.max((x - y).abs()))
    }
    /// Whether every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.entries().all(|v| v.is_finite())
    }
}

impl<T: Real, const N: usize> Mul for Mat<T, N> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self::from_rows(core::array::from_fn(|i| {
            core::array::from_fn(|j| (0..N).fold(T::ZERO, |acc, k| acc + self.m[i][k] * o.m[k][j]))
        }))
    }
}

macro_rules! row_major {
    ($n:literal, $nn:literal) => {
        impl<T: Real> Mat<T, $n> {
            #[doc = concat!("All ", stringify!($nn), " entries, row by row.")]
            pub fn to_row_major(&self) -> [T; $nn] {
                core::array::from_fn(|k| self.m[k / $n][k % $n])
            }
            #[doc = concat!("From ", stringify!($nn), " entries, row by row.")]
            pub fn from_row_major(a: [T; $nn]) -> Self {
                Self::from_rows(core::array::from_fn(|i| {
                    core::array::from_fn(|j| a[i * $n + j])
                }))
            }
        }
    };
}
row_major!(3, 9);
row_major!(4, 16);

impl<T: Real> Mat3<T> {
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
    /// The inverse, or `None` when the determinant is zero or not finite.
    pub fn inverse(&self) -> Option<Self> {
        let det = self.determinant();
        if det == T::ZERO || !det.is_finite() {
            return None;
        }
        let m = &self.m;
        let c = |r0: usize, r1: usize, c0: usize, c1: usize| {
            m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
        };
        // Adjugate (transposed cofactors) over the determinant.
        let adj = [
            [c(1, 2, 1, 2), -c(0, 2, 1, 2), c(0, 1, 1, 2)],
            [-c(1, 2, 0, 2), c(0, 2, 0, 2), -c(0, 1, 0, 2)],
            [c(1, 2, 0, 1), -c(0, 2, 0, 1), c(0, 1, 0, 1)],
        ];
        Some(Self::from_rows(adj.map(|r| r.map(|v| v / det))))
    }
    /// How far from a rotation: `max(‖MᵀM − I‖∞, |det M − 1|)`.
    pub fn rotation_deviation(&self) -> T {
        let mtm = self.transpose() * *self;
        mtm.max_abs_diff(&Self::identity())
            .max((self.determinant() - T::ONE).abs())
    }
}

impl<T: Real> Mat4<T> {
    /// The rigid transformation `[R t; 0 1]`.
    pub fn from_rotation_translation(r: &Mat3<T>, t: Vec3<T>) -> Self {
        Self::from_rows(core::array::from_fn(|i| {
            core::array::from_fn(|j| match (i, j) {
                (3, 3) => T::ONE,
                (3, _) => T::ZERO,
                (_, 3) => t.get(i),
                _ => r.m[i][j],
            })
        }))
    }
    /// The upper-left 3×3 block.
    pub fn linear_part(&self) -> Mat3<T> {
        Mat3::from_rows(core::array::from_fn(|i| {
            core::array::from_fn(|j| self.m[i][j])
        }))
    }
    /// The last column's first three entries.
    pub fn translation(&self) -> Vec3<T> {
        Vec3::new(self.m[0][3], self.m[1][3], self.m[2][3])
    }
    /// `M [p, 1]`, dropping the homogeneous coordinate (affine part only).
    pub fn transform_point(&self, p: Vec3<T>) -> Vec3<T> {
        self.linear_part().mul_vec(p) + self.translation()
    }
}
