//! Euler angles in all 12 axis sequences, extrinsic and intrinsic (Dam et al. 1998, §3.1,
//! App. A, B.1, B.2 and B.5).
//!
//! * **Extrinsic** (fixed axes), written in lower case, e.g. `xyz`: rotate about the fixed x
//!   axis by the first angle, then about the fixed y axis by the second, then about the
//!   fixed z axis by the third: `R = Rz(γ) Ry(β) Rx(α)`. This is the report's own convention
//!   (App. A and B.1), available as [`EulerOrder::DAM`].
//! * **Intrinsic** (moving axes), written in upper case, e.g. `XYZ`: `R = Rx(α) Ry(β) Rz(γ)`
//!   — the same rotation as extrinsic `zyx` with the angles reversed.
//!
//! The twelve sequences are the six Tait–Bryan ones (`xyz`, `xzy`, `yxz`, `yzx`, `zxy`,
//! `zyx`) and the six proper Euler ones (`xyx`, `xzx`, `yxy`, `yzy`, `zxz`, `zyz`). This
//! naming is the one of SciPy's `Rotation.from_euler`.
//!
//! Extraction (matrix or quaternion → angles) follows B.5: "go via the rotation", with the
//! direct quaternion method of Bernardes & Viollet (2022, PLoS ONE 17(11)), which works
//! for every sequence and stays accurate near gimbal lock: the first and third angles come
//! from the half-sum and half-difference `atan2`s, so the rotation rebuilt from the angles
//! matches to rounding even where the angles themselves are ill-conditioned.
//! Ranges: first and third angle in [−π, π]; the middle one in [−π/2, π/2] (Tait–Bryan,
//! as B.2's "assuming cos β > 0") or [0, π] (proper Euler).
//!
//! **Gimbal lock** (middle angle at ±π/2 for Tait–Bryan, 0 or π for proper Euler, within
//! 16 ε): as in B.2 the third angle is defined to be 0 ("we arbitrarily define γ ≡ 0") and
//! the whole remaining rotation goes into the first angle. For intrinsic orders the third
//! angle (in the order written) is the one set to 0, too. [`EulerAngles::gimbal_lock`]
//! says when that happened.
//!
//! **Batches**: [`quats_to_euler`] extracts the angles of a slice of quaternions with the
//! same formulas in a loop the compiler vectorizes: the normalization as
//! [`Quat::normalize`] does it, the three `atan2`s by the crate's branch-free kernel (within
//! about 1.3 ulp of libm's, where libm's `atan2` is a call with branches per value and
//! cannot be vectorized). Items the kernel should not decide — near gimbal lock, a zero
//! `atan2` argument whose sign matters, a norm outside the plain range, a zero or
//! non-finite quaternion — go through [`Quat::to_euler`] itself, so the results agree with
//! it to a few ulp everywhere and exactly at gimbal lock.

use super::BatchError;
use crate::{trig, Error, Mat3, Quat, Real, Result};
use core::fmt;
use core::str::FromStr;

/// An Euler-angle convention: three axes (0 = x, 1 = y, 2 = z) and whether they are fixed
/// (extrinsic) or moving (intrinsic).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct EulerOrder {
    /// The axes in the order written, e.g. `[0, 1, 2]` for `xyz`.
    pub axes: [u8; 3],
    /// Moving axes (upper-case name) rather than fixed ones (lower-case name).
    pub intrinsic: bool,
}

/// Angles with the information whether the extraction met gimbal lock.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerAngles<T> {
    /// The three angles in radians, in the order of the [`EulerOrder`]'s axes.
    pub angles: [T; 3],
    /// True when the middle angle was at its singular value and the third angle was set to
    /// 0 by convention (Dam et al. App. B.2).
    pub gimbal_lock: bool,
}

impl EulerOrder {
    /// The report's convention (Dam et al. App. A, B.1): fixed axes x, then y, then z,
    /// `R = Rz(γ) Ry(β) Rx(α)`.
    pub const DAM: EulerOrder = EulerOrder {
        axes: [0, 1, 2],
        intrinsic: false,
    };

    /// Builds an order; a typed error unless no two neighbouring axes are equal and every
    /// axis is 0, 1 or 2.
    pub fn new(axes: [u8; 3], intrinsic: bool) -> Result<Self> {
        let ok = axes.iter().all(|a| *a < 3) && axes[0] != axes[1] && axes[1] != axes[2];
        let o = EulerOrder { axes, intrinsic };
        if ok {
            Ok(o)
        } else {
            Err(Error::UnknownEulerOrder(format!("{axes:?}")))
        }
    }

    /// All 24 conventions: 12 sequences, each extrinsic and intrinsic.
    pub fn all() -> Vec<EulerOrder> {
        let mut v = Vec::with_capacity(24);
        for intrinsic in [false, true] {
            for a in 0..3u8 {
                for b in 0..3u8 {
                    for c in 0..3u8 {
                        if let Ok(o) = Self::new([a, b, c], intrinsic) {
                            v.push(o);
                        }
                    }
                }
            }
        }
        v
    }

    /// Whether first and last axis are equal (proper Euler) rather than all different
    /// (Tait–Bryan).
    pub fn is_proper_euler(&self) -> bool {
        self.axes[0] == self.axes[2]
    }
}

impl FromStr for EulerOrder {
    type Err = Error;
    /// Parses `xyz` (extrinsic) or `XYZ` (intrinsic); mixed case is an error.
    fn from_str(s: &str) -> Result<Self> {
        let bad = || Error::UnknownEulerOrder(s.to_string());
        let chars: Vec<char> = s.chars().collect();
        if chars.len() != 3 {
            return Err(bad());
        }
        let upper = chars.iter().all(|c| c.is_ascii_uppercase());
        let lower = chars.iter().all(|c| c.is_ascii_lowercase());
        if !(upper || lower) {
            return Err(bad());
        }
        let mut axes = [0u8; 3];
        for (a, c) in axes.iter_mut().zip(chars.iter()) {
            *a = match c.to_ascii_lowercase() {
                'x' => 0,
                'y' => 1,
                'z' => 2,
                _ => return Err(bad()),
            };
        }
        Self::new(axes, upper).map_err(|_| bad())
    }
}

impl fmt::Display for EulerOrder {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for a in self.axes {
            let c = [b'x', b'y', b'z'][a as usize] as char;
            let c = if self.intrinsic {
                c.to_ascii_uppercase()
            } else {
                c
            };
            write!(f, "{c}")?;
        }
        Ok(())
    }
}

impl<T: Real> Quat<T> {
    /// The unit quaternion of Euler angles (radians) in the given convention:
    /// extrinsic `q = q_c(γ) q_b(β) q_a(α)`, intrinsic `q = q_a(α) q_b(β) q_c(γ)`.
    pub fn from_euler(order: EulerOrder, angles: [T; 3]) -> Self {
        let [a, b, c] = order.axes.map(usize::from);
        let qa = Quat::from_axis_index(a, angles[0]);
        let qb = Quat::from_axis_index(b, angles[1]);
        let qc = Quat::from_axis_index(c, angles[2]);
        if order.intrinsic {
            qa * qb * qc
        } else {
            qc * qb * qa
        }
    }

    /// Euler angles of the rotation of q (any non-zero q; its scale and sign do not
    /// matter). See the module docs for ranges and gimbal lock. Errors: zero or
    /// non-finite q.
    pub fn to_euler(self, order: EulerOrder) -> Result<EulerAngles<T>> {
        let q = self.normalize()?;
        let [a, b, c] = order.axes;
        if order.intrinsic {
            // Intrinsic abc = extrinsic cba with the angles reversed; the intrinsic third
            // angle is then the extrinsic first one.
            let e = extrinsic_angles(q, [c, b, a], true);
            Ok(EulerAngles {
                angles: [e.angles[2], e.angles[1], e.angles[0]],
                gimbal_lock: e.gimbal_lock,
            })
        } else {
            Ok(extrinsic_angles(q, [a, b, c], false))
        }
    }
}

impl<T: Real> Mat3<T> {
    /// The rotation matrix of Euler angles (App. B.1 for [`EulerOrder::DAM`]).
    pub fn from_euler(order: EulerOrder, angles: [T; 3]) -> Self {
        Quat::from_euler(order, angles).to_rotation_matrix()
    }

    /// Euler angles of a rotation matrix (App. B.2, B.5). Errors: not a rotation, or not
    /// finite.
    pub fn to_euler(&self, order: EulerOrder) -> Result<EulerAngles<T>> {
        Quat::from_rotation_matrix(self)?.to_euler(order)
    }
}

/// Bernardes & Viollet's direct method for the extrinsic sequence `axes` (first applied
/// first). At gimbal lock one of the outer angles is set to 0: the third, or the first
/// when `zero_first`.
fn extrinsic_angles<T: Real>(q: Quat<T>, axes: [u8; 3], zero_first: bool) -> EulerAngles<T> {
    let (i, j, mut k) = (axes[0] as i32, axes[1] as i32, axes[2] as i32);
    let proper = i == k;
    if proper {
        k = 3 - i - j;
    }
    let sign = T::from_i32((i - j) * (j - k) * (k - i) / 2);
    let v = q.vector();
    let (qi, qj, qk) = (
        v.get(i as usize),
        v.get(j as usize),
        v.get(k as usize) * sign,
    );
    let (a, b, c, d) = if proper {
        (q.w, qi, qj, qk)
    } else {
        (q.w - qj, qi + qk, qj + q.w, qk - qi)
    };
    let hyp = |x: T, y: T| (x * x + y * y).sqrt();
    let middle = T::TWO * hyp(c, d).atan2(hyp(a, b));
    let lock_tol = T::EPSILON * T::from_i32(16);
    let half_sum = b.atan2(a);
    let half_diff = d.atan2(c);
    let (mut first, mut third, lock) = if middle.abs() <= lock_tol {
        (T::TWO * half_sum, T::ZERO, true)
    } else if (middle - T::PI).abs() <= lock_tol {
        (-T::TWO * half_diff, T::ZERO, true)
    } else {
        (half_sum - half_diff, half_sum + half_diff, false)
    };
    if lock && zero_first {
        // The same total rotation, moved into the third angle: at β = 0 the invariant is
        // α + γ, at β = π it is α − γ.
        third = if middle.abs() <= lock_tol {
            first
        } else {
            -first
        };
        first = T::ZERO;
    }
    let mut middle = middle;
    if !proper {
        third *= sign;
        middle -= T::PI * T::HALF;
    }
    EulerAngles {
        angles: [wrap(first), middle, wrap(third)],
        gimbal_lock: lock,
    }
}

/// Euler angles of every quaternion of `q` in `order`: `out[i]` is
/// `q[i].to_euler(order)?.angles` to a few ulp — each angle is a sum or difference of
/// `atan2`s computed by the crate's kernel (within about 1.3 ulp of libm's), so the two
/// differ by at most about 8 ε (4 ulp at π) over the tests' random inputs in f64 and f32,
/// up to the wrap at ±π — and exactly that where it matters which of two nearby
/// representations is chosen: near gimbal lock (the middle angle within 64 ε of its singular
/// values), for a zero `atan2` argument (whose sign picks ±π) and for quaternions whose
/// squared norm is not a normal finite number. Those items, and only those, are converted
/// by [`Quat::to_euler`] itself; the others go through a loop without branches or calls,
/// which the compiler vectorizes (`#[inline(always)]`, so that a caller can compile it for
/// wider vectors inside a `#[target_feature]` function). Errors: the first item that is
/// zero or not finite (its index and [`Quat::to_euler`]'s error; the items before it are
/// written), or `q` and `out` of different lengths.
#[inline(always)]
pub fn quats_to_euler<T: Real>(
    q: &[Quat<T>],
    order: EulerOrder,
    out: &mut [[T; 3]],
) -> core::result::Result<(), BatchError> {
    super::same_lengths(&[q.len(), out.len()], &["quats_to_euler: q and out"])?;
    let plan = Plan::new(order);
    const BLOCK: usize = 128;
    for (b, (qs, os)) in q.chunks(BLOCK).zip(out.chunks_mut(BLOCK)).enumerate() {
        let mut slow = [false; BLOCK];
        for ((q, o), s) in qs.iter().zip(os.iter_mut()).zip(slow.iter_mut()) {
            let (angles, ok) = plan.angles(*q);
            *o = angles;
            *s = !ok;
        }
        if slow.iter().any(|s| *s) {
            for (k, ((q, o), _)) in qs
                .iter()
                .zip(os.iter_mut())
                .zip(slow)
                .enumerate()
                .filter(|(_, (_, s))| *s)
            {
                *o = q
                    .to_euler(order)
                    .map_err(|error| BatchError {
                        index: b * BLOCK + k,
                        error,
                    })?
                    .angles;
            }
        }
    }
    Ok(())
}

/// An order's extraction worked out once for a batch: the extrinsic sequence of
/// [`extrinsic_angles`] (for an intrinsic order, the reversed one, with the output
/// reversed) as selections of the quaternion's components.
struct Plan<T> {
    /// `(i, j, k)` of [`extrinsic_angles`], each as a one-hot choice of x, y, z.
    pick: [[bool; 3]; 3],
    proper: bool,
    sign: T,
    reverse: bool,
}

impl<T: Real> Plan<T> {
    fn new(order: EulerOrder) -> Self {
        let [a, b, c] = order.axes;
        let axes = if order.intrinsic {
            [c, b, a]
        } else {
            [a, b, c]
        };
        let (i, j, mut k) = (axes[0] as i32, axes[1] as i32, axes[2] as i32);
        let proper = i == k;
        if proper {
            k = 3 - i - j;
        }
        let one_hot = |a: i32| [a == 0, a == 1, a == 2];
        Plan {
            pick: [one_hot(i), one_hot(j), one_hot(k)],
            proper,
            sign: T::from_i32((i - j) * (j - k) * (k - i) / 2),
            reverse: order.intrinsic,
        }
    }

    /// [`extrinsic_angles`] of `q / ‖q‖` away from gimbal lock, and whether this item may
    /// use them (else [`Quat::to_euler`] must decide). Every choice is a select: no
    /// branch, no call.
    #[inline(always)]
    fn angles(&self, q: Quat<T>) -> ([T; 3], bool) {
        // Quat::normalize on its common path (robust_norm's plain sum of squares).
        let n2 = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
        let plain = n2.is_finite() & (n2 >= T::MIN_POSITIVE);
        let n = n2.sqrt();
        let (w, v) = (q.w / n, [q.x / n, q.y / n, q.z / n]);
        let pick = |p: [bool; 3]| {
            if p[0] {
                v[0]
            } else if p[1] {
                v[1]
            } else {
                v[2]
            }
        };
        let (qi, qj, qk) = (pick(self.pick[0]), pick(self.pick[1]), pick(self.pick[2]));
        let qk = qk * self.sign;
        let (a, b, c, d) = if self.proper {
            (w, qi, qj, qk)
        } else {
            (w - qj, qi + qk, qj + w, qk - qi)
        };
        let hyp = |x: T, y: T| (x * x + y * y).sqrt();
        let middle = T::TWO * trig::atan2(hyp(c, d), hyp(a, b));
        let half_sum = trig::atan2(b, a);
        let half_diff = trig::atan2(d, c);
        let band = T::EPSILON * T::from_i32(64);
        let ok = plain
            & (middle.abs() > band)
            & ((middle - T::PI).abs() > band)
            & (b != T::ZERO)
            & (d != T::ZERO);
        let first = half_sum - half_diff;
        let (mut third, mut middle) = (half_sum + half_diff, middle);
        if !self.proper {
            third *= self.sign;
            middle -= T::PI * T::HALF;
        }
        let (first, third) = (wrap(first), wrap(third));
        let angles = if self.reverse {
            [third, middle, first]
        } else {
            [first, middle, third]
        };
        (angles, ok)
    }
}

/// Wraps an angle into [−π, π].
#[inline(always)]
fn wrap<T: Real>(a: T) -> T {
    let two_pi = T::TWO * T::PI;
    if a > T::PI {
        a - two_pi
    } else if a < -T::PI {
        a + two_pi
    } else {
        a
    }
}
