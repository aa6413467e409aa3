//! *LinMat*: linear interpolation of rotation matrices, element by element (Dam et al.
//! 1998, §6.1.2, eq. 6.2), `LinMat(M0, M1, h) = M0(1 − h) + M1 h`.
//!
//! The raw result is in general *not* a rotation (it scales and shears; at 180° apart it
//! collapses to rank 1 at h = ½). [`lin_mat`] returns that raw matrix; [`rotation_part`]
//! extracts the rotation closest to it in the Frobenius norm — the orthogonal factor of
//! the polar decomposition `M = R S` (Shoemake & Duff 1994, cited in §6.1.2) — which is
//! what Figure 6.2 shows projected on the sphere. [`non_rigidity`] measures how far the raw
//! matrix is from a rotation.

use crate::{Error, Mat3, Quat, Real, Result};

/// Eq. 6.2: the raw element-wise interpolation.
pub fn lin_mat<T: Real>(m0: &Mat3<T>, m1: &Mat3<T>, h: T) -> Mat3<T> {
    Mat3::from_rows(core::array::from_fn(|i| {
        core::array::from_fn(|j| m0.m[i][j] * (T::ONE - h) + m1.m[i][j] * h)
    }))
}

/// The rotation closest to `m` (orthogonal polar factor), as a unit quaternion. Computed by
/// Higham's iteration `R ← (R + R⁻ᵀ)/2`, which converges quadratically. Errors: `m`
/// singular, non-finite, or with negative determinant (its polar factor is a reflection).
pub fn rotation_part<T: Real>(m: &Mat3<T>) -> Result<Quat<T>> {
    if !m.is_finite() {
        return Err(Error::NonFinite { what: "matrix" });
    }
    let det = m.determinant();
    let scale = m.entries().fold(T::ZERO, |a, v| a.max(v.abs()));
    let threshold = T::EPSILON * scale * scale * scale;
    if det.partial_cmp(&threshold) != Some(core::cmp::Ordering::Greater) {
        return Err(Error::NotRotation {
            reason: "the interpolated matrix is singular or a reflection (keys 180° apart?)",
            deviation: det.to_f64(),
        });
    }
    let mut r = *m;
    for _ in 0..60 {
        let Some(inv) = r.inverse() else { break };
        let inv_t = inv.transpose();
        let next = Mat3::from_rows(core::array::from_fn(|i| {
            core::array::from_fn(|j| (r.m[i][j] + inv_t.m[i][j]) * T::HALF)
        }));
        let change = next.max_abs_diff(&r);
        r = next;
        if change <= T::EPSILON * T::from_i32(4) {
            break;
        }
    }
    Ok(Quat::from_rotation_matrix_unchecked(&r))
}

/// `‖MᵀM − I‖∞`: 0 for a rotation, growing as LinMat scales and shears.
pub fn non_rigidity<T: Real>(m: &Mat3<T>) -> T {
    (m.transpose() * *m).max_abs_diff(&Mat3::identity())
}
