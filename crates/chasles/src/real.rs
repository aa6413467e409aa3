//! The scalar type every algebraic type is generic over.
//!
//! [`Real`] is implemented for `f32` and `f64`. It is deliberately small — the arithmetic
//! operators plus the handful of elementary functions the papers use — so that other number
//! types (for instance a FLOP-counting wrapper, see Kavan et al. 2006, Table 1, row "FLOPS")
//! can implement it too.

use core::fmt::{Debug, Display};
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// A real number: `f32`, `f64`, or any type that behaves like them.
pub trait Real:
    Copy
    + PartialEq
    + PartialOrd
    + Debug
    + Display
    + Default
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 2.
    const TWO: Self;
    /// 1/2.
    const HALF: Self;
    /// π.
    const PI: Self;
    /// Machine epsilon: the gap between 1 and the next larger number.
    const EPSILON: Self;
    /// The smallest positive normal number.
    const MIN_POSITIVE: Self;

    /// Converts from `f64` (rounding to the nearest representable value).
    fn from_f64(v: f64) -> Self;
    /// Converts to `f64`.
    fn to_f64(self) -> f64;
    /// Square root.
    fn sqrt(self) -> Self;
    /// Sine.
    fn sin(self) -> Self;
    /// Cosine.
    fn cos(self) -> Self;
    /// Arc sine.
    fn asin(self) -> Self;
    /// Arc cosine.
    fn acos(self) -> Self;
    /// Four-quadrant arc tangent of `self / x`, in ]−π, π].
    fn atan2(self, x: Self) -> Self;
    /// e^self.
    fn exp(self) -> Self;
    /// Natural logarithm.
    fn ln(self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// Whether the value is neither infinite nor NaN.
    fn is_finite(self) -> bool;

    /// The larger of two values (NaN-ignoring like `f64::max`).
    #[inline]
    #[allow(clippy::eq_op)] // `x != x` is the NaN test for a generic type
    fn max(self, other: Self) -> Self {
        if self >= other || other != other {
            self
        } else {
            other
        }
    }
    /// The smaller of two values (NaN-ignoring like `f64::min`).
    #[inline]
    #[allow(clippy::eq_op)] // `x != x` is the NaN test for a generic type
    fn min(self, other: Self) -> Self {
        if self <= other || other != other {
            self
        } else {
            other
        }
    }
    /// Sine and cosine at once.
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
    /// `self · a + b`. For `f32` and `f64` with one rounding (`mul_add`): one instruction
    /// where the code is compiled with the `fma` target feature, a slow software routine
    /// elsewhere — so generic code calls it only on such paths (see `trig::Lanes`). The
    /// default is a product and a sum.
    #[inline]
    fn fused_mul_add(self, a: Self, b: Self) -> Self {
        self * a + b
    }
    /// Converts a small integer constant.
    #[inline]
    fn from_i32(v: i32) -> Self {
        Self::from_f64(f64::from(v))
    }
}

macro_rules! impl_real {
    ($t:ident) => {
        impl Real for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const TWO: Self = 2.0;
            const HALF: Self = 0.5;
            const PI: Self = core::$t::consts::PI;
            const EPSILON: Self = $t::EPSILON;
            const MIN_POSITIVE: Self = $t::MIN_POSITIVE;

            #[inline]
            fn from_f64(v: f64) -> Self {
                v as $t
            }
            #[inline]
            fn to_f64(self) -> f64 {
                f64::from(self)
            }
            #[inline]
            fn sqrt(self) -> Self {
                $t::sqrt(self)
            }
            #[inline]
            fn sin(self) -> Self {
                $t::sin(self)
            }
            #[inline]
            fn cos(self) -> Self {
                $t::cos(self)
            }
            #[inline]
            fn asin(self) -> Self {
                $t::asin(self)
            }
            #[inline]
            fn acos(self) -> Self {
                $t::acos(self)
            }
            #[inline]
            fn atan2(self, x: Self) -> Self {
                $t::atan2(self, x)
            }
            #[inline]
            fn exp(self) -> Self {
                $t::exp(self)
            }
            #[inline]
            fn ln(self) -> Self {
                $t::ln(self)
            }
            #[inline]
            fn abs(self) -> Self {
                $t::abs(self)
            }
            #[inline]
            fn is_finite(self) -> bool {
                $t::is_finite(self)
            }
            #[inline]
            fn max(self, other: Self) -> Self {
                $t::max(self, other)
            }
            #[inline]
            fn min(self, other: Self) -> Self {
                $t::min(self, other)
            }
            #[inline]
            fn sin_cos(self) -> (Self, Self) {
                $t::sin_cos(self)
            }
            #[inline]
            fn fused_mul_add(self, a: Self, b: Self) -> Self {
                $t::mul_add(self, a, b)
            }
        }
    };
}

impl_real!(f32);
impl_real!(f64);

/// The shorter arc's numbers from `x0 = p·q`, `dm = ‖p − q‖²` and `dp = ‖p + q‖²` (for
/// Slerp of quaternions and ScLERP of the real parts): where `x0 < 0` those of −q,
/// `[−x0, dp, dm, −1]`, else `[x0, dm, dp, 1]` — `[x, d2, e2, s]`, with the sign `s` for
/// q's weights (exact, so a blend that takes it there gives the bits of the blend with s q).
///
/// By a mask in two lanes, with no branch and off the chain of dependent operations. In
/// ScLERP the compiler made `if x0 < 0 { … }` a branch, which on random pairs is guessed
/// wrong half the time; in Slerp it made it a select, with ‖p − s q‖² after it, on that
/// chain. ScLERP over 10⁶ stored random pairs, best of 20 loops: 36.3–36.6 ns a blend
/// with the branch, 37.2–37.7 with the sign first (the comparison's bit as the sign bit
/// of 1) and ‖p0 ∓ s q0‖² after it, 33.5 with the mask.
#[inline(always)]
pub(crate) fn shorter_arc(x0: f64, dm: f64, dp: f64) -> [f64; 4] {
    use wide::f64x2;
    let neg = f64x2::splat(x0).simd_lt(f64x2::ZERO);
    let [d2, e2] = neg
        .bitselect(f64x2::new([dp, dm]), f64x2::new([dm, dp]))
        .to_array();
    let [x, s] = neg
        .bitselect(f64x2::new([-x0, -1.0]), f64x2::new([x0, 1.0]))
        .to_array();
    [x, d2, e2, s]
}

/// `sin(x)/x`, exact at and near 0 (Taylor series below a threshold instead of 0/0).
#[inline]
pub fn sinc<T: Real>(x: T) -> T {
    let x2 = x * x;
    // Below x² < sqrt(eps) the series 1 − x²/6 + x⁴/120 is exact to rounding.
    if x2 < T::EPSILON.sqrt() {
        T::ONE - x2 / T::from_i32(6) * (T::ONE - x2 / T::from_i32(20))
    } else {
        x.sin() / x
    }
}

/// `atan2(n, w) / n` for `n ≥ 0`: the factor that turns the vector part of a quaternion
/// into its logarithm. Finite for `n → 0` when `w > 0` (limit `1/w`).
///
/// For `n = 0` and `w ≤ 0` the true value is infinite (the half-angle is π but the axis is
/// undefined); callers handle that case before calling.
#[inline]
pub fn atan2_over<T: Real>(n: T, w: T) -> T {
    if n == T::ZERO {
        T::ONE / w
    } else {
        n.atan2(w) / n
    }
}

/// The relative tolerance used by the library's "is this unit / rigid / a rotation" checks:
/// `sqrt(ε)`-scaled, about 1.5e-8 for f64 and 3.5e-4 for f32.
#[inline]
pub fn default_tolerance<T: Real>() -> T {
    T::EPSILON.sqrt()
}

/// `√(Σ xᵢ²)` without overflow or underflow: the plain sum of squares where it is a
/// normal, finite number (almost always: one test), else the components scaled by the
/// largest first (`m √(Σ (xᵢ/m)²)`), so that a vector of 1e200s or of 1e-200s keeps its
/// length. NaN in, NaN out; an infinite component gives infinity.
#[inline]
pub(crate) fn robust_norm<T: Real>(x: &[T]) -> T {
    let n2 = x.iter().fold(T::ZERO, |a, v| a + *v * *v);
    if n2.is_finite() && n2 >= T::MIN_POSITIVE {
        return n2.sqrt();
    }
    #[allow(clippy::eq_op)] // `x != x` is the NaN test for a generic type
    if n2 != n2 {
        return n2;
    }
    let m = x.iter().fold(T::ZERO, |a, v| a.max(v.abs()));
    if m == T::ZERO || !m.is_finite() {
        return m;
    }
    m * x
        .iter()
        .fold(T::ZERO, |a, v| a + (*v / m) * (*v / m))
        .sqrt()
}

#[cfg(test)]
mod tests {
    use super::{robust_norm, shorter_arc};

    #[test]
    fn the_shorter_arc_flips_below_zero_only() {
        let (dm, dp) = (0.25, 3.75);
        for x0 in [
            f64::NEG_INFINITY,
            -0.5,
            -1e-300,
            -f64::MIN_POSITIVE / 4.0,
            -0.0,
            0.0,
            1e-300,
            0.5,
            f64::NAN,
        ] {
            let want = if x0 < 0.0 {
                [-x0, dp, dm, -1.0]
            } else {
                [x0, dm, dp, 1.0]
            };
            let got = shorter_arc(x0, dm, dp);
            assert_eq!(got.map(f64::to_bits), want.map(f64::to_bits), "{x0}");
        }
    }

    #[test]
    fn the_norm_neither_overflows_nor_underflows() {
        assert_eq!(robust_norm(&[3.0f64, 4.0]), 5.0);
        assert!((robust_norm(&[3e200f64, 4e200]) / 5e200 - 1.0).abs() < 1e-15);
        assert!((robust_norm(&[3e-200f64, 4e-200]) / 5e-200 - 1.0).abs() < 1e-15);
        assert!((robust_norm(&[3e30f32, 4e30]) / 5e30 - 1.0).abs() < 1e-6);
        assert_eq!(robust_norm(&[0.0f64, 0.0]), 0.0);
        assert_eq!(robust_norm(&[f64::INFINITY, 1.0]), f64::INFINITY);
        assert!(robust_norm(&[f64::NAN, 1e300]).is_nan());
    }
}
