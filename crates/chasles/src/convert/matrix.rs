//! Quaternion ↔ rotation matrix (Dam et al. 1998, App. B.3 and B.4).
//!
//! Quaternion → matrix is B.3's `M = V_q H_{q⁻¹}`. Matrix → quaternion does **not** use
//! B.4's trace-only formula `s = ½√(1 + tr R)`, `v = (R₃₂ − R₂₃, …)/(4s)`: near 180° the
//! trace is −1, `s → 0` and the division loses every digit. We use Shepperd's
//! largest-diagonal method instead (Shepperd 1978): of the four candidates
//! `4w² = 1 + tr`, `4x² = 1 + 2R₀₀ − tr`, … the largest is taken as the pivot, so the
//! divisor is never below ½. The sign is chosen so that `w ≥ 0` (B.4 also takes the
//! positive root), which is the shorter-arc representative.
//!
//! [`quats_from_rotation_matrices`] runs [`Quat::from_rotation_matrix`] over a slice with
//! the same operations in the same order — the rotation check, the pivot, the divisions,
//! the normalization — but the pivot's four cases as selects instead of branches (a random
//! rotation's pivot is a coin toss for the branch predictor), so its results are the
//! per-item function's bit for bit. [`quats_to_rotation_matrices`] runs
//! [`Quat::to_rotation_matrix`] over a slice, eight quaternions side by side in lanes (the
//! nine entries of a row-major matrix are too many for the compiler to vectorize a loop
//! that stores them item by item), bit for bit too.

use super::{BatchError, LANES};
use crate::{Error, Mat3, Mat4, Quat, Real, Result};

/// The rotation matrices of `q` into `out` (row-major, as [`Mat3::to_row_major`] gives
/// them): [`Quat::to_rotation_matrix`] bit for bit for every quaternion whose squared norm
/// is a normal finite number (any such scale: `q/‖q‖`'s rotation), eight at a time side by
/// side in lanes, in loops without branches or calls that the compiler vectorizes
/// (`#[inline(always)]`, so that a caller can compile it for wider vectors inside a
/// `#[target_feature]` function). The others go through `q.normalize()?` first: rescaled
/// where `‖q‖²` overflows or is subnormal (where `2/‖q‖²` would not be finite), an error
/// for a zero or non-finite quaternion. Errors: the first such item (its index and
/// [`Quat::normalize`]'s error; the items before it are written), or `q` and `out` of
/// different lengths.
#[inline(always)]
pub fn quats_to_rotation_matrices<T: Real>(
    q: &[Quat<T>],
    out: &mut [[T; 9]],
) -> core::result::Result<(), BatchError> {
    super::same_lengths(
        &[q.len(), out.len()],
        &["quats_to_rotation_matrices: q and out"],
    )?;
    let (qg, qr) = q.as_chunks::<LANES>();
    let (og, or) = out.as_chunks_mut::<LANES>();
    for (g, (qs, os)) in qg.iter().zip(og.iter_mut()).enumerate() {
        rotations_in_lanes(g * LANES, qs, os)?;
    }
    if let Some(last) = qr.last() {
        // The rest, padded with copies of its last quaternion.
        let qs = core::array::from_fn(|l| *qr.get(l).unwrap_or(last));
        rotations_in_lanes(qg.len() * LANES, &qs, or)?;
    }
    Ok(())
}

/// [`quats_to_rotation_matrices`] of [`LANES`] quaternions (the first `out.len()` of them
/// written), the first being item `start`: `to_rotation_matrix`'s operations in one loop
/// over the lanes, which the compiler vectorizes, then the entries stored item by item.
#[inline(always)]
#[allow(clippy::needless_range_loop)] // the lane loop is the point: it vectorizes
fn rotations_in_lanes<T: Real>(
    start: usize,
    q: &[Quat<T>; LANES],
    out: &mut [[T; 9]],
) -> core::result::Result<(), BatchError> {
    let mut m = [[T::ZERO; LANES]; 9];
    let mut plain = [false; LANES];
    for l in 0..LANES {
        let (w, x, y, z) = (q[l].w, q[l].x, q[l].y, q[l].z);
        let n2 = w * w + x * x + y * y + z * z;
        plain[l] = n2.is_finite() & (n2 >= T::MIN_POSITIVE);
        let s = if n2 > T::ZERO { T::TWO / n2 } else { T::ZERO };
        let (xx, yy, zz) = (x * x * s, y * y * s, z * z * s);
        let (xy, xz, yz) = (x * y * s, x * z * s, y * z * s);
        let (wx, wy, wz) = (w * x * s, w * y * s, w * z * s);
        m[0][l] = T::ONE - (yy + zz);
        m[1][l] = xy - wz;
        m[2][l] = xz + wy;
        m[3][l] = xy + wz;
        m[4][l] = T::ONE - (xx + zz);
        m[5][l] = yz - wx;
        m[6][l] = xz - wy;
        m[7][l] = yz + wx;
        m[8][l] = T::ONE - (xx + yy);
    }
    for (l, o) in out.iter_mut().enumerate() {
        *o = if plain[l] {
            core::array::from_fn(|k| m[k][l])
        } else {
            q[l].normalize()
                .map_err(|error| BatchError {
                    index: start + l,
                    error,
                })?
                .to_rotation_matrix()
                .to_row_major()
        };
    }
    Ok(())
}

/// [`Quat::from_rotation_matrix`] of every matrix of `m` into `out`, bit for bit, in a loop
/// without branches or calls: Shepperd's four cases are all computed and selected. Matrices
/// with an entry beyond ±2, or that fail the checks, are converted by
/// [`Quat::from_rotation_matrix`] itself, which reports them. `#[inline(always)]`, so that a
/// caller can compile it for wider vectors inside a `#[target_feature]` function. Errors:
/// the first item that is not a rotation or not finite (its index and the per-item error;
/// the items before it are written), or `m` and `out` of different lengths.
#[inline(always)]
pub fn quats_from_rotation_matrices<T: Real>(
    m: &[Mat3<T>],
    out: &mut [Quat<T>],
) -> core::result::Result<(), BatchError> {
    super::same_lengths(
        &[m.len(), out.len()],
        &["quats_from_rotation_matrices: m and out"],
    )?;
    const BLOCK: usize = 128;
    for (b, (ms, os)) in m.chunks(BLOCK).zip(out.chunks_mut(BLOCK)).enumerate() {
        let mut slow = [false; BLOCK];
        for ((m, o), s) in ms.iter().zip(os.iter_mut()).zip(slow.iter_mut()) {
            let (q, ok) = shepperd_selected(m);
            *o = q;
            *s = !ok;
        }
        if slow.iter().any(|s| *s) {
            for (k, ((m, o), _)) in ms
                .iter()
                .zip(os.iter_mut())
                .zip(slow)
                .enumerate()
                .filter(|(_, (_, s))| *s)
            {
                *o = Quat::from_rotation_matrix(m).map_err(|error| BatchError {
                    index: b * BLOCK + k,
                    error,
                })?;
            }
        }
    }
    Ok(())
}

/// [`Quat::from_rotation_matrix`] for a matrix whose entries are within ±2, with selects
/// for branches, and whether its result stands (the checks passed and the normalization
/// took its plain path). Every operation is the per-item function's, in its order.
#[inline(always)]
fn shepperd_selected<T: Real>(r: &Mat3<T>) -> (Quat<T>, bool) {
    let m = &r.m;
    let two = T::TWO;
    let small = m.iter().flatten().fold(true, |a, v| a & (v.abs() <= two));
    // rotation_deviation: ‖MᵀM − I‖ (entry (i, j) summed over k from 0, as Mat's product
    // does) and |det M − 1|; with entries within ±2 nothing overflows or is NaN, so the
    // largest deviation exceeds the tolerance exactly when one of them does.
    let tol = crate::default_tolerance::<T>() * T::from_i32(4);
    let mut rotation = (r.determinant() - T::ONE).abs() <= tol;
    for i in 0..3 {
        for j in i..3 {
            let e = T::ZERO + m[0][i] * m[0][j] + m[1][i] * m[1][j] + m[2][i] * m[2][j];
            let id = if i == j { T::ONE } else { T::ZERO };
            rotation &= (e - id).abs() <= tol;
        }
    }
    // from_rotation_matrix_unchecked.
    let tr = m[0][0] + m[1][1] + m[2][2];
    let one = T::ONE;
    let quarter = T::HALF * T::HALF;
    let cw = one + tr;
    let cx = one + m[0][0] - m[1][1] - m[2][2];
    let cy = one - m[0][0] + m[1][1] - m[2][2];
    let cz = one - m[0][0] - m[1][1] + m[2][2];
    let pw = (cw >= cx) & (cw >= cy) & (cw >= cz);
    let px = !pw & (cx >= cy) & (cx >= cz);
    let py = !pw & !px & (cy >= cz);
    let pick = |w: T, x: T, y: T, z: T| {
        if pw {
            w
        } else if px {
            x
        } else if py {
            y
        } else {
            z
        }
    };
    let s = pick(cw, cx, cy, cz).sqrt() * two;
    let (d0, d1, d2) = (m[2][1] - m[1][2], m[0][2] - m[2][0], m[1][0] - m[0][1]);
    let (s0, s1, s2) = (m[0][1] + m[1][0], m[0][2] + m[2][0], m[1][2] + m[2][1]);
    let pivot = quarter * s;
    // Each component: the pivot's quarter·s, or its case's numerator over s.
    let part = |own: bool, num: T| if own { pivot } else { num / s };
    let q = Quat::new(
        part(pw, pick(pivot, d0, d1, d2)),
        part(px, pick(d0, pivot, s0, s1)),
        part(py, pick(d1, s0, pivot, s2)),
        part(!pw & !px & !py, pick(d2, s1, s2, pivot)),
    );
    let q = q.to_positive_hemisphere();
    // Quat::normalize on its plain path.
    let n2 = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
    let plain = n2.is_finite() & (n2 >= T::MIN_POSITIVE);
    (q / n2.sqrt(), small & rotation & plain)
}

impl<T: Real> Quat<T> {
    /// The rotation matrix of q (App. B.3). A non-unit q is treated as `q/‖q‖` (the matrix
    /// of `q p q⁻¹`, Proposition 18); the zero quaternion, which is no rotation, gives the
    /// identity — use [`Quat::normalize`] first to catch it as an error.
    pub fn to_rotation_matrix(self) -> Mat3<T> {
        let n2 = self.norm_squared();
        let s = if n2 > T::ZERO { T::TWO / n2 } else { T::ZERO };
        let (w, x, y, z) = (self.w, self.x, self.y, self.z);
        let (xx, yy, zz) = (x * x * s, y * y * s, z * z * s);
        let (xy, xz, yz) = (x * y * s, x * z * s, y * z * s);
        let (wx, wy, wz) = (w * x * s, w * y * s, w * z * s);
        Mat3::from_rows([
            [T::ONE - (yy + zz), xy - wz, xz + wy],
            [xy + wz, T::ONE - (xx + zz), yz - wx],
            [xz - wy, yz + wx, T::ONE - (xx + yy)],
        ])
    }

    /// The 4×4 homogeneous rotation matrix (App. B.3).
    pub fn to_matrix4(self) -> Mat4<T> {
        Mat4::from_rotation_translation(&self.to_rotation_matrix(), crate::Vec3::zero())
    }

    /// The unit quaternion of a 4×4 homogeneous *rotation* matrix (App. B.3's 4×4 form).
    /// Errors: non-finite entries, a translation or a last row other than `[0, 0, 0, 1]`
    /// (use [`crate::DualQuat::from_matrix4`] for rigid motions), or a non-rotation block.
    pub fn from_matrix4(m: &Mat4<T>) -> Result<Self> {
        if !m.is_finite() {
            return Err(Error::NonFinite { what: "4x4 matrix" });
        }
        let mut dev = T::ZERO;
        for i in 0..3 {
            dev = dev.max(m.m[i][3].abs()).max(m.m[3][i].abs());
        }
        dev = dev.max((m.m[3][3] - T::ONE).abs());
        if dev > crate::default_tolerance::<T>() * T::from_i32(4) {
            return Err(Error::NotRotation {
                reason: "the 4x4 matrix has a translation or a projective part",
                deviation: dev.to_f64(),
            });
        }
        Self::from_rotation_matrix(&m.linear_part())
    }

    /// The unit quaternion (with `w ≥ 0`) of a rotation matrix, exact at every angle
    /// including 180° (Shepperd's method). Errors: non-finite entries, or a matrix further
    /// than [`crate::default_tolerance`] from a rotation (`‖RᵀR − I‖`, `det R`).
    pub fn from_rotation_matrix(r: &Mat3<T>) -> Result<Self> {
        if !r.is_finite() {
            return Err(Error::NonFinite {
                what: "rotation matrix",
            });
        }
        let dev = r.rotation_deviation();
        if dev > crate::default_tolerance::<T>() * T::from_i32(4) {
            let reason = if r.determinant() < T::ZERO {
                "determinant is negative (a reflection)"
            } else {
                "columns are not orthonormal"
            };
            return Err(Error::NotRotation {
                reason,
                deviation: dev.to_f64(),
            });
        }
        Ok(Self::from_rotation_matrix_unchecked(r))
    }

    /// Shepperd's method without the rotation check; the result is normalized, so a matrix
    /// that is nearly a rotation gives a nearby unit quaternion.
    pub fn from_rotation_matrix_unchecked(r: &Mat3<T>) -> Self {
        let m = &r.m;
        let tr = m[0][0] + m[1][1] + m[2][2];
        let one = T::ONE;
        let quarter = T::HALF * T::HALF;
        // Candidates for 4w², 4x², 4y², 4z².
        let cw = one + tr;
        let cx = one + m[0][0] - m[1][1] - m[2][2];
        let cy = one - m[0][0] + m[1][1] - m[2][2];
        let cz = one - m[0][0] - m[1][1] + m[2][2];
        let q = if cw >= cx && cw >= cy && cw >= cz {
            let s = cw.sqrt() * T::TWO; // 4w
            Self::new(
                quarter * s,
                (m[2][1] - m[1][2]) / s,
                (m[0][2] - m[2][0]) / s,
                (m[1][0] - m[0][1]) / s,
            )
        } else if cx >= cy && cx >= cz {
            let s = cx.sqrt() * T::TWO; // 4x
            Self::new(
                (m[2][1] - m[1][2]) / s,
                quarter * s,
                (m[0][1] + m[1][0]) / s,
                (m[0][2] + m[2][0]) / s,
            )
        } else if cy >= cz {
            let s = cy.sqrt() * T::TWO; // 4y
            Self::new(
                (m[0][2] - m[2][0]) / s,
                (m[0][1] + m[1][0]) / s,
                quarter * s,
                (m[1][2] + m[2][1]) / s,
            )
        } else {
            let s = cz.sqrt() * T::TWO; // 4z
            Self::new(
                (m[1][0] - m[0][1]) / s,
                (m[0][2] + m[2][0]) / s,
                (m[1][2] + m[2][1]) / s,
                quarter * s,
            )
        };
        let q = q.to_positive_hemisphere();
        q.normalize().unwrap_or_else(|_| Self::identity())
    }

    /// Dam et al.'s App. B.4 trace-only formula, kept to show why it is not used: it loses
    /// all precision as the angle approaches 180° (`s → 0`). Not for production use.
    pub fn from_rotation_matrix_trace_only(r: &Mat3<T>) -> Self {
        let m = &r.m;
        let s = T::HALF * (T::ONE + m[0][0] + m[1][1] + m[2][2]).max(T::ZERO).sqrt();
        let d = T::from_i32(4) * s;
        Self::new(
            s,
            (m[2][1] - m[1][2]) / d,
            (m[0][2] - m[2][0]) / d,
            (m[1][0] - m[0][1]) / d,
        )
    }
}
