//! Reduced-range trigonometric kernels for the interpolation formulas and the batched
//! conversions.
//!
//! ScLERP (Kavan et al. 2006, §4, `p̂ (p̂* q̂)^t`, evaluated as a dual Slerp, Dam et al.
//! 1998, eq. 6.4) needs the angle Ω between two unit quaternions on the shorter arc
//! (Ω ≤ π/2) and `sin`, `cos` of `tΩ/2`. The general library functions (`acos`, `atan2`,
//! `sin_cos`) reduce arbitrary arguments and handle every special value; here the arguments
//! are already small, and the angle comes from the chord, which is well conditioned at
//! every angle (unlike `acos` of the dot product near 0):
//!
//! * `Ω = d · acos(1 − y)/√(2y)` with `d = ‖p − q‖ = 2 sin(Ω/2)` and `y = d²/2 = 1 − cos Ω
//!   ∈ [0, 1]`: [`acos_over_chord`] is that smooth factor, a polynomial in `y` — no square
//!   root or division stands between the inputs and the angle;
//! * `sin x`, `cos x` for `|x| ≤ π/4 < 0.8`: [`sin_cos_reduced`];
//! * for f32 Slerp (Dam et al. 1998, eq. 6.13, up to a quarter turn), two shorter
//!   polynomials fitted to f32's precision: the squared angle `Ω² = 2y Z(y)`
//!   ([`angle2_over_2y_f32`], 9 terms) and the small part of `sinc √u = 1 + u T(u)`
//!   ([`sinc_minus_one_f32`], 5 terms), within 1.5 f32 ulp each;
//! * for the batched quaternion → Euler conversion (Bernardes & Viollet 2022, three
//!   `atan2` per item): [`atan2`], the four-quadrant arc tangent with no branch and no
//!   call — one division `t = min(|x|, |y|)/max(|x|, |y|) ∈ [0, 1]`, `atan t = t + t z P(z)`
//!   with `z = t²` (`P` in 20 terms), then the octant by selects and `π/2`, `π` as
//!   two-part constants — so that a loop of them vectorizes, where libm's `atan2` is a
//!   call with branches per value. It is hand-written rather than taken from `wide`
//!   (whose `f64x2::atan2` is Cephes' rational form, two divisions a value): the batch
//!   conversion is generic over [`Real`] like the rest of the crate, so its kernel must be
//!   too, and scalar code with selects is vectorized at the width of the function it is
//!   compiled into — four f64 lanes where a caller compiles the batch for AVX2, as the
//!   Python package does when the processor has it — where `wide`'s types fix their width
//!   and instructions when the crate is compiled.
//!
//! The polynomials were fitted in 50-digit arithmetic (unweighted least squares at Chebyshev
//! nodes of the first kind, near-minimax; every coefficient of `ACOS` free, the constant
//! rounding to exactly 1) on `y ≤ 1.0001`, `|x| ≤ 0.8` and `0 ≤ t ≤ 1` by
//! `scripts/fit_trig.py`, whose refit reproduces the tables bit for bit (its `--check`, run
//! in CI, reports that and fails if the tables' values drift past these bounds); in `f64`
//! they are within about 3 ulp (the angle) and 1.5 ulp (sin, cos, atan) of the true values
//! there — the tests check this against the library functions; the f32 tables likewise
//! within 1.5 f32 ulp, evaluated in f32. They are evaluated by Estrin's scheme (short
//! dependency chains), with fused multiply-adds where the build has them (`fma` target
//! feature), and are generic over [`Lanes`]: every [`Real`] (so the FLOP counter counts them
//! as they run) and `wide::f64x2`, two values at once (SSE2 on every x86-64, NEON on
//! AArch64).

use crate::Real;
use core::ops::{Add, Mul, Sub};
use wide::f64x2;

/// What the kernels need of a number type: ring operations, constants and multiply-add.
pub trait Lanes: Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> {
    /// The constant `c` (in every lane).
    fn splat(c: f64) -> Self;
    /// `self · b + c`, fused (one rounding, one instruction) where the build has FMA, else a
    /// product and a sum — never the slow software fused form.
    fn madd(self, b: Self, c: Self) -> Self;
}

impl<T: Real> Lanes for T {
    #[inline(always)]
    fn splat(c: f64) -> Self {
        T::from_f64(c)
    }
    #[inline(always)]
    fn madd(self, b: Self, c: Self) -> Self {
        if cfg!(target_feature = "fma") {
            self.fused_mul_add(b, c)
        } else {
            self * b + c
        }
    }
}

impl Lanes for f64x2 {
    #[inline(always)]
    fn splat(c: f64) -> Self {
        f64x2::splat(c)
    }
    #[inline(always)]
    fn madd(self, b: Self, c: Self) -> Self {
        // `wide` fuses exactly when the build has FMA.
        self.mul_add(b, c)
    }
}

/// Largest `y` for which [`acos_over_chord`] keeps its accuracy (a quarter turn, Ω = π/2,
/// is `y = 1`; the margin admits inputs a little off unit length).
pub const ACOS_OVER_CHORD_MAX: f64 = 1.0001;
/// Largest `|x|` for which [`sin_cos_reduced`] keeps its accuracy.
pub const SIN_COS_REDUCED_MAX: f64 = 0.8;

/// `acos(1 − y)/√(2y) = A(y)`: the coefficients of `A`, constant term first.
const ACOS: [f64; 19] = [
    1.0,
    0.08333333333332346,
    0.01875000000116525,
    0.005580357088380087,
    0.0018988728704829197,
    0.0006991098348534586,
    0.0002713369405374157,
    0.00010771133629716107,
    5.211967233891681e-05,
    -7.1111281090128315e-06,
    8.210460811134223e-05,
    -0.00015518110731632505,
    0.00026128879528178144,
    -0.0003209501529381417,
    0.0002972654653585578,
    -0.00019835317912646875,
    9.117110284807676e-05,
    -2.5823461343732896e-05,
    3.482519446779182e-06,
];
/// `sin(x) = x + x z S(z)`, `z = x²`.
const SIN: [f64; 6] = [
    -0.16666666666666663,
    0.008333333333330467,
    -0.00019841269836045036,
    2.7557315739226986e-06,
    -2.5051057508795905e-08,
    1.5912871368555095e-10,
];
/// `cos(x) = 1 − z/2 + z² C(z)`, `z = x²`.
const COS: [f64; 7] = [
    0.041666666666666664,
    -0.0013888888888888887,
    2.480158730158411e-05,
    -2.7557319220993776e-07,
    2.087675565161897e-09,
    -1.1470439189559761e-11,
    4.744616280885557e-14,
];

/// `atan(t) = t + t z P(z)`, `z = t²`, `0 ≤ t ≤ 1`: the coefficients of `P`.
const ATAN: [f64; 20] = [
    -0.3333333333333333,
    0.1999999999999784,
    -0.14285714285420378,
    0.11111111095189265,
    -0.09090908632998367,
    0.07692299608538965,
    -0.06666571116309021,
    0.05881552238667051,
    -0.05258206977515918,
    0.04738648786275643,
    -0.04262985730644524,
    0.037553839957608456,
    -0.031379046544951064,
    0.023831884941536995,
    -0.015671636995656543,
    0.008471897649490865,
    -0.003552058629716547,
    0.0010705283915803199,
    -0.0002047228449238937,
    1.8560948007510396e-05,
];

/// `acos(1 − y)²/(2y) = Z(y)` to f32's precision (coefficients rounded to f32 where used):
/// the squared angle between two unit quaternions is `Ω² = 2y Z(y)`, `y = 1 − cos Ω`.
const ANGLE2_F32: [f64; 9] = [
    1.000000005637174,
    0.1666657806792452,
    0.04446721433970504,
    0.01406248754671851,
    0.006160982669189821,
    -0.000959299380621566,
    0.005119355246258256,
    -0.0032711373969434936,
    0.0014551533271805839,
];
/// `(sin √u/√u − 1)/u = T(u)` to f32's precision for `0 ≤ u ≤` [`SINC_F32_MAX`]: `sinc √u
/// = 1 + u T(u)`.
const SINC_F32: [f64; 5] = [
    -0.1666666666388766,
    0.008333332769528681,
    -0.00019841086706879498,
    2.7536472237430724e-06,
    -2.408035098251646e-08,
];
/// Largest `u` for which [`sinc_minus_one_f32`] keeps its accuracy: `acos(−0.0001)²`, a
/// quarter turn with the margin of [`ACOS_OVER_CHORD_MAX`].
// Read by the tests and checked by scripts/fit_trig.py; Slerp's arguments stay below it.
#[allow(dead_code)]
pub const SINC_F32_MAX: f64 = 2.467715269538222;

/// `acos(1 − y)²/(2y)` to f32's precision for `0 ≤ y ≤` [`ACOS_OVER_CHORD_MAX`] (1 at
/// `y = 0`): `Ω² = 2y · angle2_over_2y_f32(y)`.
#[inline(always)]
pub fn angle2_over_2y_f32<L: Lanes>(y: L) -> L {
    poly(y, &ANGLE2_F32)
}

/// `sinc √u − 1 = u T(u)` to f32's precision for `0 ≤ u ≤` [`SINC_F32_MAX`]: the small part
/// of the sinc, kept apart so that ratios of sincs lose nothing to the 1.
#[inline(always)]
pub fn sinc_minus_one_f32<L: Lanes>(u: L) -> L {
    u * poly(u, &SINC_F32)
}

/// The polynomial with coefficients `c` (constant term first) at `z`, by Estrin's scheme
/// (pairs, then pairs of pairs, up to 32 coefficients): a dependency chain of about log₂ N
/// multiply-adds instead of Horner's N. Written out level by level: as a loop over levels
/// the compiler kept the coefficients in memory (ScLERP 48 ns instead of 26 ns).
#[inline(always)]
fn poly<L: Lanes, const N: usize>(z: L, c: &[f64; N]) -> L {
    let k = |i: usize| L::splat(c[i]);
    let z2 = z * z;
    let z4 = z2 * z2;
    let z8 = z4 * z4;
    let z16 = z8 * z8;
    let pair = |i: usize| {
        if i + 1 < N {
            Lanes::madd(k(i + 1), z, k(i))
        } else {
            k(i)
        }
    };
    let quad = |i: usize| {
        if i + 2 < N {
            Lanes::madd(pair(i + 2), z2, pair(i))
        } else {
            pair(i)
        }
    };
    let oct = |i: usize| {
        if i + 4 < N {
            Lanes::madd(quad(i + 4), z4, quad(i))
        } else {
            quad(i)
        }
    };
    let hex = |i: usize| {
        if i + 8 < N {
            Lanes::madd(oct(i + 8), z8, oct(i))
        } else {
            oct(i)
        }
    };
    if N > 16 {
        Lanes::madd(hex(16), z16, hex(0))
    } else {
        hex(0)
    }
}

/// `acos(1 − y)/√(2y)` for `0 ≤ y ≤` [`ACOS_OVER_CHORD_MAX`] (1 at `y = 0`): the angle
/// between two unit quaternions at chord `d` is `Ω = d · acos_over_chord(d²/2)`.
#[inline(always)]
pub fn acos_over_chord<L: Lanes>(y: L) -> L {
    poly(y, &ACOS)
}

/// `(sin x, cos x)` for `|x| ≤` [`SIN_COS_REDUCED_MAX`].
#[inline(always)]
pub fn sin_cos_reduced<L: Lanes>(x: L) -> (L, L) {
    let z = x * x;
    let s = Lanes::madd(x * z, poly(z, &SIN), x);
    let c = Lanes::madd(
        z * z,
        poly(z, &COS),
        Lanes::madd(z, L::splat(-0.5), L::splat(1.0)),
    );
    (s, c)
}

/// `(sin x / x, cos x)` from `z = x²`, for `|x| ≤` [`SIN_COS_REDUCED_MAX`]: the same
/// polynomials as [`sin_cos_reduced`], with no division by `x` (1 and 1 at `z = 0`).
#[inline(always)]
pub fn sinc_cos_reduced<L: Lanes>(z: L) -> (L, L) {
    let s = Lanes::madd(z, poly(z, &SIN), L::splat(1.0));
    let c = Lanes::madd(
        z * z,
        poly(z, &COS),
        Lanes::madd(z, L::splat(-0.5), L::splat(1.0)),
    );
    (s, c)
}

/// The four-quadrant arc tangent of `y/x` in [−π, π], as `Real::atan2` for finite `y`, `x`
/// that are not both zero, except that `y = −0` is taken as `+0` (the result's sign is the
/// sign of `y < 0`); within about 2 ulp of the true value in `f64` (the tests check it
/// against libm). No branch and no call: every choice is a select, so a loop of them
/// vectorizes.
#[inline(always)]
pub fn atan2<T: Real>(y: T, x: T) -> T {
    let (ax, ay) = (x.abs(), y.abs());
    let swap = ay > ax;
    let (big, small) = if swap { (ay, ax) } else { (ax, ay) };
    let t = small / big;
    let z = t * t;
    let r = Lanes::madd(t * z, poly(z, &ATAN), t);
    // π/2 and π as a rounded head and the rest (for f32 the rest of the f32 head).
    let half_pi = core::f64::consts::FRAC_PI_2;
    let (h_hi, h_lo) = (T::from_f64(half_pi), 6.123_233_995_736_766e-17);
    let h_lo = T::from_f64(half_pi - h_hi.to_f64() + h_lo);
    let (p_hi, p_lo) = (T::TWO * h_hi, T::TWO * h_lo);
    let r = if swap { h_hi - r + h_lo } else { r };
    let r = if x < T::ZERO { p_hi - r + p_lo } else { r };
    if y < T::ZERO {
        -r
    } else {
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative error in units of the last place of the exact value (f64 libm as reference,
    /// which is itself within 1 ulp).
    fn ulps(got: f64, want: f64) -> f64 {
        ((got - want) / want).abs() / f64::EPSILON
    }

    #[test]
    fn acos_over_chord_within_four_ulps_on_its_range() {
        let mut worst: f64 = 0.0;
        for i in 1..=100_000 {
            let y = ACOS_OVER_CHORD_MAX * f64::from(i) / 100_000.0;
            let d = (2.0 * y).sqrt();
            for omega in [
                d * acos_over_chord::<f64>(y),
                d * acos_over_chord(f64x2::splat(y)).to_array()[1],
            ] {
                // y = 2 sin²(Ω/2): the well-conditioned reference (not acos(1 − y)).
                worst = worst.max(ulps(omega, 2.0 * (0.5 * y).sqrt().asin()));
            }
        }
        assert!(worst < 4.0, "acos: {worst} ulp");
        assert_eq!(acos_over_chord::<f64>(0.0), 1.0);
        // Ω = 60°: y = 1/2.
        let f = acos_over_chord::<f32>(0.5);
        assert!((f - core::f32::consts::FRAC_PI_3).abs() <= 2.0 * f32::EPSILON);
    }

    #[test]
    fn sin_cos_within_two_ulps_on_their_range() {
        let (mut ws, mut wc): (f64, f64) = (0.0, 0.0);
        for i in 1..=100_000 {
            let x = SIN_COS_REDUCED_MAX * f64::from(i) / 100_000.0;
            for (s, c) in [sin_cos_reduced::<f64>(x), {
                let (s, c) = sin_cos_reduced(f64x2::new([0.0, x]));
                (s.to_array()[1], c.to_array()[1])
            }] {
                ws = ws.max(ulps(s, x.sin()));
                wc = wc.max(ulps(c, x.cos()));
            }
        }
        assert!(ws < 2.0 && wc < 2.5, "sin {ws} ulp, cos {wc} ulp");
        assert_eq!(sin_cos_reduced::<f64>(0.0), (0.0, 1.0));
        let (s, c) = sin_cos_reduced::<f32>(0.7);
        assert!((s - 0.7_f32.sin()).abs() < 2.0 * f32::EPSILON);
        assert!((c - 0.7_f32.cos()).abs() < 2.0 * f32::EPSILON);
    }
    #[test]
    fn the_f32_kernels_within_two_f32_ulps_on_their_range() {
        let ulps32 = |got: f32, want: f64| ((f64::from(got) - want) / want).abs() / 2f64.powi(-23);
        let mut worst = (0.0f64, 0.0f64);
        for i in 0..=4000 {
            let y = (i as f64 / 4000.0 * ACOS_OVER_CHORD_MAX) as f32;
            let want = if y == 0.0 {
                1.0
            } else {
                let y = f64::from(y);
                (1.0 - y).acos().powi(2) / (2.0 * y)
            };
            worst.0 = worst.0.max(ulps32(angle2_over_2y_f32(y), want));
            let u = (i as f64 / 4000.0 * SINC_F32_MAX) as f32;
            let r = f64::from(u).sqrt();
            let sinc = if u == 0.0 { 1.0 } else { r.sin() / r };
            worst.1 = worst.1.max(ulps32(1.0 + sinc_minus_one_f32(u), sinc));
        }
        assert!(worst.0 < 2.0 && worst.1 < 2.0, "{worst:?} f32 ulp");
        assert_eq!(angle2_over_2y_f32(0.0f32), 1.0);
        assert_eq!(sinc_minus_one_f32(0.0f32), 0.0);
    }

    /// `atan2` against libm (itself within 1 ulp) on every octant, in ulp of the true
    /// value, and its special values.
    #[test]
    fn atan2_within_two_ulps_of_libm() {
        let mut worst: f64 = 0.0;
        let mut worst32: f64 = 0.0;
        let n = 200_000;
        for i in 0..n {
            // Angles over the whole circle, radii over many octaves.
            let a = -core::f64::consts::PI
                + 2.0 * core::f64::consts::PI * (f64::from(i) + 0.5) / f64::from(n);
            let r = 2f64.powi(i % 40 - 20);
            let (y, x) = (r * a.sin(), r * a.cos());
            let want = y.atan2(x);
            worst = worst.max(ulps(atan2(y, x), want));
            let (y32, x32) = (y as f32, x as f32);
            let want32 = f64::from(y32).atan2(f64::from(x32));
            let got32 = f64::from(atan2(y32, x32));
            worst32 = worst32.max(((got32 - want32) / want32).abs() / f64::from(f32::EPSILON));
        }
        assert!(worst < 2.0, "atan2: {worst} ulp");
        assert!(worst32 < 2.0, "atan2 f32: {worst32} f32 ulp");
        // Exact where libm is: axes, diagonals' signs, zero y.
        let pi = core::f64::consts::PI;
        assert_eq!(atan2(0.0, 1.0), 0.0);
        assert_eq!(atan2(0.0, -1.0), pi);
        assert_eq!(atan2(-1.0, -0.0), -pi / 2.0);
        assert_eq!(atan2(1.0, 0.0), pi / 2.0);
        assert_eq!(atan2(3.0, 3.0), pi / 4.0);
        assert_eq!(atan2(-2.0f32, -2.0), -3.0 * core::f32::consts::FRAC_PI_4);
        assert_eq!(atan2(1e-300, 1.0), 1e-300);
    }
}
