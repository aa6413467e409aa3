//! *Slerp*: spherical linear interpolation (Dam et al. 1998, §6.1.5).
//!
//! * [`slerp_pow`]: eq. 6.4, `Slerp(p, q, h) = p (p* q)^h`, through the quaternion power.
//! * [`slerp`]: eq. 6.13, `(p sin((1 − h)Ω) + q sin(hΩ)) / sin Ω` with `cos Ω = p·q`,
//!   the form without exponentiation. In the trigonometric form ([`slerp_trig`]) Ω is
//!   computed as `2 atan2(‖p − q‖, ‖p + q‖)`, which is accurate at every angle (unlike
//!   `acos(p·q)` near 0), and for small Ω `sin(hΩ)/sin Ω` is evaluated as
//!   `h · sinc(hΩ)/sinc(Ω)`, so Ω → 0 has no 0/0 (the report's patch `Slerp(q, q, h) ≡ q`
//!   is the limit, not a special case). Up to a quarter turn (`p·q ≥ 0`) the weights come
//!   in f32 from two short polynomials of `trig.rs` fitted to f32 ([`slerp_weights_f32`]:
//!   the squared angle from `1 − p·q = ‖p − q‖²/2` (taken from the difference, which keeps
//!   small angles), and the small parts of the sincs; within four f32 ulp
//!   of the true weights, fewer operations than Eberly's series [`slerp_weights_series`],
//!   which it replaced) and in f64 from the reduced polynomial kernels of `trig.rs` (the ones
//!   ScLERP uses; [`slerp_weights_reduced`]): no `acos`, `sin`, square root or 0/0, within a
//!   few ulp of f64.
//!
//! Both follow the great arc between p and q *as given* (Proposition 29: the shorter arc
//! between the two 4D points). Footnote 7: q and −q are the same rotation, so the shorter
//! *rotation* may be the arc to −q; [`slerp_shortest`] flips q when `p·q < 0`. Antipodal
//! keys (q = −p) have no unique arc: [`slerp`] then turns about an axis perpendicular to p
//! in 4D (any great circle through p and −p is as short), still with unit speed.

use crate::real::sinc;
use crate::{Quat, Real, Result};

/// Eq. 6.4: `p (p* q)^h`. Errors: zero or non-finite inputs.
pub fn slerp_pow<T: Real>(p: Quat<T>, q: Quat<T>, h: T) -> Result<Quat<T>> {
    Ok(p * (p.conjugate() * q).powf(h)?)
}

/// Eq. 6.13 for unit p and q, exact for Ω → 0 and defined for q = −p (see module docs).
///
/// For `p·q ≥ 0` (Ω ≤ π/2, every shorter-arc Slerp) the weights `sin(hΩ)/sin Ω` come, in
/// f32 (any `Real` with ε > 1e-10), from [`slerp_weights_f32`]'s two short polynomials
/// (within four f32 ulp; `1 − cos Ω` taken from the chord, `‖p − q‖²/2`), and in f64 from the
/// reduced polynomial kernels ([`slerp_weights_reduced`]: no `acos`, `sin` or square root,
/// within a few ulp); beyond a quarter turn the trigonometric form, [`slerp_trig`], kept
/// out of line so that the common path inlines small.
#[inline(always)]
pub fn slerp<T: Real>(p: Quat<T>, q: Quat<T>, h: T) -> Quat<T> {
    let x = p.dot(q);
    if x >= T::ZERO && (T::ZERO..=T::ONE).contains(&h) {
        return within_quarter_turn(p, q, h);
    }
    slerp_trig(p, q, h)
}

/// Slerp for `x = p·q ≥ 0` and `0 ≤ h ≤ 1` (the ranges the polynomials are fitted on) with
/// no branch and no call: [`slerp_weights_f32`]'s polynomials from the chord in f32, the
/// reduced kernels in f64.
#[inline(always)]
fn within_quarter_turn<T: Real>(p: Quat<T>, q: Quat<T>, h: T) -> Quat<T> {
    if T::EPSILON > T::from_f64(1e-10) {
        let (a, b) = slerp_weights_f32_chord(half_chord2(p, q), h);
        p * a + q * b
    } else {
        let (a, b) = slerp_weights_reduced(p.cast(), q.cast(), h.to_f64());
        p * T::from_f64(a) + q * T::from_f64(b)
    }
}

/// Eq. 6.13 by trigonometry: `Ω = acos(p·q)` where that is well conditioned
/// (`|p·q| < ½`, with `sin Ω = √(1 − (p·q)²)`), else `Ω = 2 atan2(‖p − q‖, ‖p + q‖)` and
/// `sin Ω = ‖p − q‖ ‖p + q‖ / 2`, with the sinc form below Ω = 1e-3 so that Ω → 0 has no
/// 0/0. h = 0 and h = 1 give p and q exactly.
#[inline(never)]
pub fn slerp_trig<T: Real>(p: Quat<T>, q: Quat<T>, h: T) -> Quat<T> {
    if h == T::ZERO {
        return p;
    } else if h == T::ONE {
        return q;
    }
    let x = p.dot(q);
    if x.abs() < T::HALF {
        // 60° < Ω < 120°: acos and √(1 − x²) are well conditioned here, and cheaper.
        let omega = x.acos();
        let sin_omega = (T::ONE - x * x).sqrt();
        return p * (((T::ONE - h) * omega).sin() / sin_omega)
            + q * ((h * omega).sin() / sin_omega);
    }
    let d = (p - q).norm();
    let s = (p + q).norm();
    let omega = T::TWO * d.atan2(s);
    if s == T::ZERO {
        // q = −p: every great circle through p and −p has the same length π; turn in the
        // plane of p and a 4D vector perpendicular to it.
        let perp = Quat::new(-p.x, p.w, -p.z, p.y);
        let (sn, cs) = (h * T::PI).sin_cos();
        return p * cs + perp * sn;
    }
    let g = T::ONE - h;
    if omega < T::from_f64(1e-3) {
        // Divided (not multiplied by a reciprocal) so that h = 0 and h = 1 give p and q
        // exactly.
        let s_omega = sinc(omega);
        let a = g * sinc(g * omega) / s_omega;
        let b = h * sinc(h * omega) / s_omega;
        return p * a + q * b;
    }
    let sin_omega = d * s * T::HALF;
    p * ((g * omega).sin() / sin_omega) + q * ((h * omega).sin() / sin_omega)
}

/// The Slerp weights `(sin((1 − h)Ω)/sin Ω, sin(hΩ)/sin Ω)` for unit `p`, `q` with
/// `p·q ≥ 0` (Ω ≤ π/2), from the reduced kernels of `trig.rs` — no `acos`, `sin` or
/// square root: with `y = ‖p − q‖²/2 = 1 − cos Ω` the half angle is `(Ω/2)² = y A(y)²/2`
/// (`acos_over_chord`), and by `sin 2u = 2 sin u cos u`
/// `sin(hΩ)/sin Ω = h · sinc(hΩ/2) cos(hΩ/2) / (sinc(Ω/2) cos(Ω/2))`, every argument
/// within π/4 (`sinc_cos_reduced`). Smooth at Ω = 0 (no 0/0), exact at
/// h = 0 and h = 1.
#[inline(always)]
pub fn slerp_weights_reduced(p: Quat<f64>, q: Quat<f64>, h: f64) -> (f64, f64) {
    weights_reduced((p - q).norm_squared() * 0.5, h)
}

/// [`slerp_weights_reduced`] from `y = ‖p − q‖²/2`.
#[inline(always)]
fn weights_reduced(y: f64, h: f64) -> (f64, f64) {
    use crate::trig::{acos_over_chord, sinc_cos_reduced};
    let a = acos_over_chord(y);
    let z0 = y * a * a * 0.5;
    let g = 1.0 - h;
    // Scalar: two lanes of f64x2 for (1 − h, h) measured slower (the shuffles and the
    // vector division cost more than the second scalar polynomial saves).
    let (s0, c0) = sinc_cos_reduced(z0);
    let (sg, cg) = sinc_cos_reduced(g * g * z0);
    let (sh, ch) = sinc_cos_reduced(h * h * z0);
    let den = s0 * c0;
    ((g * sg * cg) / den, (h * sh * ch) / den)
}

/// The Slerp weights `(sin((1 − h)Ω)/sin Ω, sin(hΩ)/sin Ω)` for `x = cos Ω ∈ [0, 1]` and
/// `h ∈ [0, 1]`, to f32's precision, from two short polynomials of `trig.rs`: the squared
/// angle `z = Ω² = 2y Z(y)` from `y = 1 − x`, and `sinc √u = 1 + δ(u)`; then
/// `sin(hΩ)/sin Ω = h sinc(hΩ)/sinc Ω = h (1 + (δ(h²z) − δ(z))/(1 + δ(z)))`, the ratio's
/// small part apart from its 1 so that rounding stays below an ulp of the weight. No
/// `acos`, `sin`, square root or 0/0; one division; exact at h = 0 and h = 1.
#[inline(always)]
pub fn slerp_weights_f32<T: Real>(x: T, h: T) -> (T, T) {
    slerp_weights_f32_chord(T::ONE - x, h)
}

/// `y = ‖p − q‖²/2 = 1 − p·q` from the difference, the form that keeps its precision as Ω
/// → 0: `1 − p·q` loses the small angle to rounding (one f32 ulp of the cosine is 12 % of
/// y at Ω = 1e-3), which extrapolation (h far outside [0, 1]) multiplies by h².
#[inline(always)]
fn half_chord2<T: Real>(p: Quat<T>, q: Quat<T>) -> T {
    (p - q).norm_squared() * T::HALF
}

/// [`slerp_weights_f32`] from `y = 1 − cos Ω` (see [`half_chord2`]).
#[inline(always)]
fn slerp_weights_f32_chord<T: Real>(y: T, h: T) -> (T, T) {
    use crate::trig::{angle2_over_2y_f32, sinc_minus_one_f32};
    let z = (y + y) * angle2_over_2y_f32(y);
    let g = T::ONE - h;
    let d0 = sinc_minus_one_f32(z);
    let dh = sinc_minus_one_f32(h * h * z);
    let dg = sinc_minus_one_f32(g * g * z);
    let r = T::ONE / (T::ONE + d0);
    (g + g * ((dg - d0) * r), h + h * ((dh - d0) * r))
}

/// The Slerp weights `(sin((1 − h)Ω)/sin Ω, sin(hΩ)/sin Ω)` for `x = cos Ω ∈ [0, 1]`
/// without trigonometry, after D. Eberly ("A Fast and Accurate Algorithm for Computing
/// SLERP", J. Graphics, GPU, and Game Tools 15(3), 2011): `sin(tΩ)/sin Ω = Σ c_i(t)
/// (x − 1)^i` with `c_0 = t`, `c_i = c_{i−1} (t² − i²)/(i(2i + 1))`, summed in nested
/// (Horner) form. We keep sixteen terms and scale the last by `1 + μ`, μ = 0.91667, to
/// stand for the tail; μ was fitted here by minimax over x ∈ [0, 1], t ∈ [0, 1], where
/// the maximum error is 3.1e-8 (eight terms, as in Eberly's float version, reach only
/// 1.9e-5 with the best μ — too coarse for f32). Exact at h = 0 and h = 1. f32 Slerp used
/// it until [`slerp_weights_f32`], which needs about a third fewer operations than the 96
/// of the two sixteen-step chains here, in shorter dependency chains (`examples/stored_pairs`
/// times both).
#[inline(always)]
pub fn slerp_weights_series<T: Real>(x: T, h: T) -> (T, T) {
    let xm1 = x - T::ONE;
    let g = T::ONE - h;
    let (h2, g2) = (h * h, g * g);
    let mut fh = T::ONE;
    let mut fg = T::ONE;
    for i in (0..SERIES_TERMS).rev() {
        let (u, v) = (T::from_f64(SERIES_U[i]), T::from_f64(SERIES_V[i]));
        fh = T::ONE + (u * h2 - v) * xm1 * fh;
        fg = T::ONE + (u * g2 - v) * xm1 * fg;
    }
    (g * fg, h * fh)
}

const SERIES_TERMS: usize = 16;
const SERIES_ONE_PLUS_MU: f64 = 1.91667;
/// `u_i = 1/(i(2i+1))`, `v_i = i/(2i+1)` for i = 1…16, the last times `1 + μ`.
const SERIES_U: [f64; SERIES_TERMS] = series_coefficients().0;
const SERIES_V: [f64; SERIES_TERMS] = series_coefficients().1;

const fn series_coefficients() -> ([f64; SERIES_TERMS], [f64; SERIES_TERMS]) {
    let mut u = [0.0; SERIES_TERMS];
    let mut v = [0.0; SERIES_TERMS];
    let mut k = 0;
    while k < SERIES_TERMS {
        let i = (k + 1) as f64;
        let scale = if k + 1 == SERIES_TERMS {
            SERIES_ONE_PLUS_MU
        } else {
            1.0
        };
        u[k] = scale / (i * (2.0 * i + 1.0));
        v[k] = scale * i / (2.0 * i + 1.0);
        k += 1;
    }
    (u, v)
}

/// Slerp along the shorter rotation (footnote 7): uses −q when `p·q < 0`.
///
/// In f32 it has no branch and no call for any h, extrapolation included (see
/// `shortest_f32`), so a loop of it is vectorized: over 10⁶ stored pairs about 1.3× glam's
/// `slerp` per call (`examples/stored_pairs`). In f64 the chord `‖p ∓ q‖²` is computed
/// before the flip's sign is known and chosen by it (`real::shorter_arc`; the sign goes on
/// q's weight: the same bits as [`slerp`] to the flipped q). Before, the sign (a select,
/// not a branch) came first and the chord after it, on the chain of dependent operations:
/// 1.5× nalgebra's `slerp` per call now, 1.35× so. h outside [0, 1] goes to
/// [`slerp_trig`].
#[inline(always)]
pub fn slerp_shortest<T: Real>(p: Quat<T>, q: Quat<T>, h: T) -> Quat<T> {
    if T::EPSILON > T::from_f64(1e-10) {
        // f32: every h without a branch or a call (the casts are exact and compile away).
        return shortest_f32(p.cast(), q.cast(), h.to_f64() as f32).cast();
    }
    // After the flip p·q ≥ 0: the trigonometric form only to extrapolate (h outside
    // [0, 1]).
    if !(T::ZERO..=T::ONE).contains(&h) {
        // Extrapolation: past the kernels' fitted range (h Ω/2 ≤ π/4).
        let s = if p.dot(q) < T::ZERO { -T::ONE } else { T::ONE };
        return slerp_trig(p, q * s, h);
    }
    // The reduced kernels in f64, the chord chosen by the flip's sign (`shorter_arc`) and
    // the sign on q's weight: the bits of `within_quarter_turn(p, s q, h)`.
    let (pd, qd) = (p.cast::<f64>(), q.cast::<f64>());
    let (dm, dp) = ((pd - qd).norm_squared(), (pd + qd).norm_squared());
    let [_, d2, _, s] = crate::real::shorter_arc(pd.dot(qd), dm, dp);
    let (a, b) = weights_reduced(d2 * 0.5, h.to_f64());
    p * T::from_f64(a) + q * T::from_f64(b * s)
}

/// Slerp along the shorter arc in f32 for every `h`, with no branch and no call, so that a
/// user's loop of [`slerp_shortest`] is vectorized as [`slerp_shortest_batch`] is.
///
/// For `0 ≤ h ≤ 1` it is the batch form's arithmetic (the polynomials of
/// [`slerp_weights_f32`] with `y` from the chord, [`half_chord2`]: equal bits). To
/// extrapolate, `hΩ` is reduced by the nearest multiple kπ (Cody and Waite's three-part π,
/// as Cephes' `sinf`), `hΩ = kπ + r` with `|r| ≤ π/2`, and by `sin(hΩ) = (−1)ᵏ sin r`,
/// `sin((1 − h)Ω) = (−1)ᵏ sin(Ω − r)` (folded into `[−π/2, π/2]` by `sin(π − t) = sin t`)
/// the weights are `(−1)ᵏ (t/Ω) (1 + δ(t²))/(1 + δ(Ω²))`, `δ = sinc − 1` the same polynomial
/// on the same domain. Where k = 0 (no turn past π/2) `t/Ω` is h or 1 − h itself, so Ω → 0
/// has no 0/0 there either. Both weights come from the one reduced r, so the result stays
/// on the great circle through p and q; like the trigonometric form, its error grows as
/// ε·max(|h|, 1/sin Ω) (the final `a p + b q` cancels large weights), and hΩ itself carries
/// a rounding of |hΩ|·2⁻²⁴. NaN or infinite h, or an hΩ past f32's range, gives NaN.
#[inline(always)]
fn shortest_f32(p: Quat<f32>, q: Quat<f32>, h: f32) -> Quat<f32> {
    use crate::trig::{angle2_over_2y_f32, sinc_minus_one_f32};
    use std::f32::consts::{FRAC_1_PI, FRAC_PI_2, PI};
    // Adding and subtracting 1.5·2²³ rounds to the nearest integer (|v| < 2²²) with no
    // `round` call (SSE2 has no rounding instruction).
    const ROUND: f32 = 12_582_912.0;
    // π = PI_A + PI_B + PI_C, PI_A (8 bits) and PI_B (11 bits) short enough that k·PI_A and
    // k·PI_B are exact for |k| < 2¹³ (|hΩ| < 2.5·10⁴); beyond, r picks up their rounding.
    const PI_A: f32 = 3.140625;
    const PI_B: f32 = 9.675_026e-4;
    const PI_C: f32 = 1.509_958e-7;
    let x = p.dot(q);
    let q = if x < 0.0 { -q } else { q };
    let y = half_chord2(p, q);
    let z = (y + y) * angle2_over_2y_f32(y);
    let g = 1.0 - h;
    let inside = (0.0..=1.0).contains(&h);
    // The extrapolation's reduction (computed in every lane, used only outside [0, 1]).
    let omega = if z > 0.0 { z.sqrt() } else { 0.0 };
    let xb = h * omega;
    let k = (xb * FRAC_1_PI + ROUND) - ROUND;
    let r = ((xb - k * PI_A) - k * PI_B) - k * PI_C;
    // Within [−π/2, π/2] even where |hΩ| is past 2²² π and the reduction is only rounding
    // (comparisons, so NaN stays NaN).
    let r = if r > FRAC_PI_2 { FRAC_PI_2 } else { r };
    let r = if r < -FRAC_PI_2 { -FRAC_PI_2 } else { r };
    let t = omega - r;
    let folded = t > FRAC_PI_2;
    let t = if folded { PI - t } else { t };
    let half = k * 0.5;
    let odd = half != (half + ROUND) - ROUND;
    let turn = (if odd { -1.0 } else { 1.0 }) / omega;
    let simple_b = inside || k == 0.0;
    let simple_a = inside || (k == 0.0 && !folded);
    let (cb, ub) = if simple_b {
        (h, h * h * z)
    } else {
        (r * turn, r * r)
    };
    let (ca, ua) = if simple_a {
        (g, g * g * z)
    } else {
        (t * turn, t * t)
    };
    let d0 = sinc_minus_one_f32(z);
    let db = sinc_minus_one_f32(ub);
    let da = sinc_minus_one_f32(ua);
    let inv = 1.0 / (1.0 + d0);
    let a = ca + ca * ((da - d0) * inv);
    let b = cb + cb * ((db - d0) * inv);
    p * a + q * b
}

/// [`slerp_shortest`] of every `(p[i], q[i], h[i])` into `out[i]`. When every `h` is in
/// [0, 1] (checked first, in one pass) the loop has no branch and no call, so the compiler
/// can vectorize it: over 10⁶ stored pairs about twice glam's per-call Slerp in f32
/// (`examples/stored_pairs`); otherwise each pair goes through [`slerp_shortest`].
/// Errors: inputs of different lengths.
pub fn slerp_shortest_batch<T: Real>(
    p: &[Quat<T>],
    q: &[Quat<T>],
    h: &[T],
    out: &mut [Quat<T>],
) -> Result<()> {
    for (len, what) in [
        (q.len(), "slerp_shortest_batch: p and q"),
        (h.len(), "slerp_shortest_batch: p and h"),
        (out.len(), "slerp_shortest_batch: p and out"),
    ] {
        if len != p.len() {
            return Err(crate::Error::BatchLengths {
                what,
                a: p.len(),
                b: len,
            });
        }
    }
    if h.iter().all(|h| (T::ZERO..=T::ONE).contains(h)) {
        for (((o, p), q), h) in out.iter_mut().zip(p).zip(q).zip(h) {
            let x = p.dot(*q);
            let s = if x < T::ZERO { -T::ONE } else { T::ONE };
            *o = within_quarter_turn(*p, *q * s, *h);
        }
    } else {
        for (((o, p), q), h) in out.iter_mut().zip(p).zip(q).zip(h) {
            *o = slerp_shortest(*p, *q, *h);
        }
    }
    Ok(())
}
