//! DIB (Kavan et al. 2006, §4, the box "DIB") in the lane algebra, branch-free, so that one
//! vertex runs in each lane: the start is DLB against the pivot (the first of the heaviest
//! influences); then `b̂ ← b̂ exp(δ̂)`, normalized, with `δ̂` the second-order step below
//! for the update `x̂ = Σ wᵢ log(b̂* q̂ᵢ)`, until every lane has stopped by the library's rule
//! (the update's norm ‖x̂‖ below [`DIB_PRECISION`], or no longer shrinking within
//! [`STALL_FACTOR`] × of it, or not finite: a lane that stops keeps its blend), at most
//! [`DIB_UPDATES`] times. The AVX2 kernel (`avx2::dib`) runs it on `__m256`, eight
//! vertices at once, the AVX-512F kernel (`avx512`) on `__m512`, sixteen; on `f32` it is the same algorithm one vertex at a time, which the tests
//! hold against the library's `dib` (the scalar fast path itself runs the library's
//! `dib_convex`, the reference's very calls, so that it equals the reference bit for bit).
//!
//! **Second-order step** (past the paper): where the paper steps by the update itself,
//! `δ̂ = x̂`, the lanes step by `δ̂ = x̂ (1 + tr M / 3) − M x̂ / 3`, `M = Σ wᵢ x̂ᵢ x̂ᵢᵀ`, to
//! the same fixed point under the same stopping rule: one update where the paper's step
//! needs two (derivation and measurements in [`second_order`]). The influences' logarithms
//! are taken two at a time, interleaved, an odd count's last alone ([`Wide`], `update`;
//! measured again after the logarithm
//! below lost its reduction, one at a time was 2 % slower on the synthetic mesh and 1–4 %
//! faster on the characters: `wide`'s module docs).
//!
//! **One and two influences** (the paper's own identities): DIB of one transform is that
//! transform, so a lane of one influence keeps DLB's start; DIB of two is ScLERP (Lemma 3),
//! which a lane of two influences takes in closed form, `q̂ₐ exp(t log(q̂ₐ* q̂_b))` written
//! as a weighted sum of the two ([`mod@sclerp`], whose module docs derive it: no moments,
//! no DLB sum to step from and no pass to show convergence); only lanes of three or more
//! iterate, and a block with none makes no update at all. The rules look at a lane's own
//! weights only, so a vertex's numbers do not depend on its block-mates (the kernel's tests
//! shift every block and compare bits), and the GPU shader takes ScLERP in closed form for
//! such a vertex too. Against DIB in f64 on the characters' clips the closed form is within
//! 4.6e-7 (relatively; 4.4e-7 by the logarithm and exponential), where the reference
//! path's iteration, which stops within its rule's reach, was 1.8e-5 away on CesiumMan
//! (`tests/models.rs`,
//! `dib_of_two_influences_is_sclerp_to_rounding`). Before (2026-12-05), a lane of two took
//! the update from DLB's start and stopped after it (the pass that would show convergence
//! left out, as the lemma allows), and a block of one influence a lane computed that update
//! too, unused. Best of 30 rounds at 10⁵ vertices, one core, sixteen lanes, the old and new
//! builds in turn twice (`examples/dib_influences`, M vertices/s): one influence
//! 124.8–140.5 → 203.2–234.2 (2.44–2.48× → 1.47–1.49× DQS's time), two 90.2–94.1 →
//! 113.9–130.7 (3.60–3.69× → 2.63–2.68×), four unchanged (7.0×); the Fox 79.6–90.3 →
//! 127.7–134.2 (3.58–3.64× → 2.34–2.43×), CesiumMan 68.1–78.7 → 78.1–80.8 (4.40–4.48× →
//! 4.29–4.38×), RiggedFigure 59.1–67.8 → 67.1–69.7 (3.88–3.97× → 3.75–3.90×). A block that
//! mixes lanes of two with lanes of three or more pays for both the iteration and the
//! ScLERP (2 and 4 alternating, ungrouped: 44.5–46.4 → 41.1), so the fast path groups
//! vertices by count where that pays (`fast::grouped`'s cost). A block whose lanes all have
//! two influences makes no DLB start either (its lanes do not read it): two influences
//! 126.9–128.4 → 128.0–132.4 M vertices/s on sixteen lanes and 86.0–87.4 → 95.7–98.3 on
//! eight, RiggedSimple 154.9–159.6 → 170.9–175.1, the other characters within 3 % (the
//! same command, the builds in turn twice).
//!
//! **Subnormal numbers.** A lane of one influence never steps, but in a block with a lane
//! of three influences or more its block's passes compute its update all the same (in one
//! with a lane of two, a ScLERP from its joint to itself at t = 0, which it does not keep
//! either: since the evening of 2026-12-05 a weighted sum whose weights there are exact
//! zeros, no logarithm): the logarithm of `b̂* q̂` with `b̂ = q̂` to rounding,
//! a logarithm whose vector parts are of 1e-15 and dual ones of 1e-28 where cancellations
//! leave that little (the Fox, RiggedFigure). The moments' and the exponential's
//! products of those are subnormal numbers, for which an x86 core takes microcode assists
//! (Rust assumes flush-to-zero and denormals-are-zero are off, so the kernel cannot turn
//! them on). Its update takes weight 0, which makes them exact zeros and changes no
//! lane's numbers (the old and new kernels' outputs were compared bit for bit on the
//! characters' clips and the synthetic meshes). Over the characters' clips at seven
//! times each (best of 20 runs, one core, binaries in turn): the Fox 20.0–20.9 →
//! 57.5–59.9 M vertices/s, RiggedFigure 38.0–40.3 → 46.5–48.0, CesiumMan and the synthetic
//! mesh unchanged. A test-only lane type notes every operation that meets such a number
//! (`watch`); lanes of more influences still meet a few where their logarithms have
//! components of 1e-13 and less (0–400 lane operations a Fox pose): flushing the step's
//! tiny components to zero took most of them away and measured no faster.
//!
//! No trigonometric calls, no square root, no division and no reduction of the angle. For
//! `r̂ = b̂* q̂ᵢ` taken to `w ≥ 0`, with `r0 = (w, a)`, `rε = (wε, b)`, `n = ‖a‖`, `s = n²`
//! (eq. 2 and the library's `DualQuat::log`):
//!
//! ```text
//! log r̂ = [½ ln‖r0‖², h a] + ε [r0·rε / ‖r0‖², h b + a (2 ∂h/∂s a·b − wε / ‖r0‖²)],
//! h = atan2(n, w) / n
//! ```
//!
//! On the unit sphere, with `θ = atan2(n, w)` in [0, π/2] and `v = 1 − w = 1 − cos θ` in
//! [0, 1], `h` and `∂h/∂s` (at fixed w) are smooth in v (their singularity is at v = 2):
//!
//! ```text
//! h     = θ / sin θ = acos(1 − v)/√(v (2 − v))   ≈ H(v)
//! ∂h/∂s = (w − h)/(2s) = ((1 − v) − h)/(2v (2 − v)) ≈ H_S(v)
//! ```
//!
//! with [`H`] and [`H_S`] polynomials of ten and eleven terms fitted near minimax on
//! [0, 1] (`scripts/fit_dib_log.py`: 0.22 and 0.25 f32 ulp with their f32 coefficients,
//! 0.74 and 0.91 evaluated in f32; CI checks the bounds 0.3 and 1). Where v loses relative
//! precision (small angles, `1 − w` of rounded numbers) the polynomials stay near their
//! constant terms, so h keeps f32's precision. A logarithm's chain from the product
//! `b̂* q̂ᵢ` to `h` is one subtraction and Horner's rule, and `1/‖r0‖²` is taken as
//! `2 − ‖r0‖²` (r̂ is unit to rounding: off by `(‖r0‖² − 1)²`, under 1e-12), which measured
//! 1.5 % faster than the division on the synthetic mesh (46.6–46.9 → 47.4–47.5 M
//! vertices/s, four runs each in turn; the characters within 1 %).
//!
//! This replaced a reduction of `t = n/w` to `|t| ≤ tan(π/8)` by three rows of formulas (`t`
//! as `n/w`, `w/n` or `(n − w)/(n + w)`, polynomials for `atan(√z)/√z` and the library's
//! derivative series in `t²`), which took a square root, four divisions and ten selects on
//! that chain. Over the characters' clips at seven times each and 10⁵ synthetic vertices of
//! four influences (best of 20, one core, old and new binaries in turn four times, M
//! vertices/s): sixteen lanes 34.9–36.7 → 42.9–44.7 on the synthetic mesh, the Fox
//! 59.1–60.9 → 68.5–70.5, RiggedFigure 46.9–48.2 → 58.6–58.8, CesiumMan 47.2–50.4 →
//! 58.9–61.4; eight lanes (AVX2 alone, three times) 23.2–24.6 → 29.4–30.5, 44.6–47.2 →
//! 54.6–55.3, 31.8–35.3 → 41.4–44.5 and 35.7–38.1 → 43.2–46.1. A first version took
//! `z = tan²(θ/2) = s/(1 + w)²` and polynomials of eight and seven terms in z (`h = (1 + z)
//! atan(√z)/√z`): its division `1/(1 + w)` sat on the chain, and v measured 1–4 % faster
//! (four runs each in turn).
//!
//! The formula takes `‖r0‖` as 1 — to first order, where the `½ ln‖r0‖²` shortcut below
//! is off only to second: with `‖r0‖ = 1 + δ`, h is off by about δ relatively and `∂h/∂s`
//! by about 3δ. δ is a few 1e-7 for the products of unit dual quaternions the kernels take
//! logarithms of (joints off unit length are normalized before: `palette::dib_unit`). Over
//! 20 000 such products in f32 (`the_lane_log_of_products_is_f64s`) the logarithm's vector
//! parts are within 2.3e-7 (rotation) and 1.9e-7 (dual part) of f64's logarithm of the same
//! product, relatively; the reduction's were within 2.3e-7 and 2.0e-7. Over 40 000 blends
//! of two to four joints (a scratch comparison) DIB's results stand as far from f64's DIB
//! as before (largest 6.04e-5, mean 4.56e-6: the stopping rule's reach).
//!
//! Tried on z and not kept: the norm to first order (`(1 + ‖r0‖²)/2` for `‖r0‖` in z,
//! products of h and `∂h/∂s` by `(3 − ‖r0‖²)/2` and `(5 − 3‖r0‖²)/2`; on single unit dual
//! quaternions the logarithm's error 2.9e-7 → 2.3e-7), 5–7 % slower with the chain it
//! lengthens; Estrin's scheme for the two polynomials (four runs each in
//! turn): the synthetic mesh 41.4–43.6 → 43.0–45.6, but the Fox 67.5–68.2 → 46.3–48.9, as
//! `z⁴` underflows in a lane of one influence, whose `z` is about 1e-30 (see "Subnormal
//! numbers" above), where Horner's rule only adds products to the coefficients.
//!
//! After an update `b̂ exp(δ̂)` is made unit again by one Newton step for `1/‖q0‖` from 1
//! ([`renormalize`]) rather than a square root and a division. The logarithms' vector
//! parts are half-angles of at most π/2, so `‖x̂‖ ≤ π/2`, `tr M ≤ (π/2)²` and the
//! second-order step's real part is at most `(π/2)(1 + (π/2)²/3) < 2.9` long. There the
//! exponential's series are unit to within 6.2e-5, and the Newton step leaves under 1e-8:
//! the results are `normalize`'s to f32's rounding (2.2e-7; the test
//! `renormalizing_after_an_update_is_normalizing`). Over the characters' clips
//! and the synthetic mesh (best of 20, one core, four runs each in turn, M vertices/s):
//! the synthetic mesh 46.1–47.3 → 47.6–49.0, the Fox 72.8–73.1 → 75.2–76.2, RiggedFigure
//! 61.1–62.8 → 62.8–63.7, CesiumMan 62.3–64.3 → 64.8–66.0. DLB's start, a weighted sum of
//! any length, keeps `normalize`.
//!
//! The exponential's `cos √s`, `sinc √s` and `d sinc √s / ds` are Taylor series in `s = ‖a‖²`
//! for the step's `a`, truncated below 1e-8 at `s = (π/2)²` (a convex blend of half-angles
//! in [0, π/2] stays in it; the second-order step can reach a little past it, where the
//! neglected terms stay below 1e-7, and a step's error costs only speed: the stopping rule
//! looks at the logarithms, not at the step). Two shortcuts, both exact after the normalization
//! that follows, which only the update's norm sees: the exponential's scalar factor `e^ŵ`
//! (a positive dual number, which normalizing removes) is left out, and `½ ln‖r0‖²` is taken
//! as `½ (‖r0‖² − 1)` (r̂ is a product of unit dual quaternions: off by under 1e-14).

mod convergence;
mod sclerp;
mod second_order;

use super::wide::Wide;
use super::{dot, dqmul, horner, taylor, Lane};
use crate::skinning::{DIB_PRECISION, DIB_UPDATES};
use chasles::blend::STALL_FACTOR;
use convergence::update_by_sum;
use sclerp::sclerp;
use second_order::Spread;

/// `h(v) = θ/n = acos(1 − v)/√(v (2 − v))` on `0 ≤ v ≤ 1` (`v = 1 − w = 1 − cos θ`),
/// constant term first: fitted near minimax by `scripts/fit_dib_log.py` (0.22 f32 ulp with
/// these f32 coefficients, 0.74 evaluated in f32).
pub(in crate::fast) const H: [f32; 10] = [
    1.0,
    0.33333573,
    0.13325739,
    0.05807404,
    0.01965973,
    0.031536825,
    -0.036094006,
    0.053518295,
    -0.03396176,
    0.011470096,
];
/// `∂h/∂s = (w − h)/(2s) = ((1 − v) − h)/(2v (2 − v))` on the same interval, fitted likewise
/// (0.25 f32 ulp, 0.91 evaluated in f32).
pub(in crate::fast) const H_S: [f32; 11] = [
    -0.33333334,
    -0.19999798,
    -0.11436395,
    -0.06231956,
    -0.043566186,
    0.02059792,
    -0.11560331,
    0.17268972,
    -0.18701775,
    0.10726626,
    -0.029749975,
];
/// `cos √s = Σ (−1)ᵏ sᵏ/(2k)!`: next term below 7e-9 at `s = (π/2)²`.
pub(in crate::fast) const COS: [f32; 7] = taylor(0);
/// `sinc √s = Σ (−1)ᵏ sᵏ/(2k+1)!`: next term below 5e-10 at `s = (π/2)²`.
pub(in crate::fast) const SINC: [f32; 7] = taylor(1);
/// `d sinc √s / ds`, the derivative of [`SINC`]'s series term by term (one term fewer).
pub(in crate::fast) const D_SINC: [f32; 6] = derivative(SINC);

/// The coefficients of the derivative of `Σ cₖ sᵏ`: `(k + 1) cₖ₊₁`.
const fn derivative<const N: usize, const M: usize>(c: [f32; N]) -> [f32; M] {
    let mut out = [0f32; M];
    let mut k = 0;
    while k < M {
        out[k] = (k + 1) as f32 * c[k + 1];
        k += 1;
    }
    out
}

/// `[f(0), …, f(7)]`, written out (no closures left as calls in the kernels).
#[inline(always)]
fn eight<L>(f: impl Fn(usize) -> L) -> [L; 8] {
    [f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7)]
}

/// The unit dual quaternion of `q` (real part to unit length, dual part made orthogonal
/// to it), as `DualQuat::normalize`.
#[inline(always)]
pub(in crate::fast) fn normalize<L: Lane>(q: &[L; 8]) -> [L; 8] {
    unit_by(q, L::splat(1.0).div(dot(&q[..4], &q[..4]).sqrt()))
}

/// [`normalize`] for a `q` whose real part is unit to within about 1e-4, as `b̂ exp(δ̂)`
/// after an update is (module docs): `1/‖q0‖` by one Newton step from 1, `(3 − ‖q0‖²)/2`,
/// off by `(3/8)(‖q0‖² − 1)²` (under 1e-8) where `normalize` takes a square root and a
/// division.
#[inline(always)]
pub(in crate::fast) fn renormalize<L: Lane>(q: &[L; 8]) -> [L; 8] {
    unit_by(q, dot(&q[..4], &q[..4]).nmadd(L::splat(0.5), L::splat(1.5)))
}

/// `q` times `inv` (`1/‖q0‖`), its dual part then made orthogonal to its real part.
#[inline(always)]
fn unit_by<L: Lane>(q: &[L; 8], inv: L) -> [L; 8] {
    let u = eight(|c| q[c].mul(inv));
    let along = dot(&u[..4], &u[4..]);
    eight(|c| {
        if c < 4 {
            u[c]
        } else {
            u[c - 4].nmadd(along, u[c])
        }
    })
}

/// `log r̂` of the module docs, for `r̂` or `−r̂`, whichever has `w ≥ 0`.
#[inline(always)]
pub(in crate::fast) fn log<L: Lane>(r: &[L; 8]) -> [L; 8] {
    let r = eight(|c| r[c].flip_by_sign_of(r[0]));
    let (w, wd) = (r[0], r[4]);
    let s = dot(&r[1..4], &r[1..4]);
    let ab = dot(&r[1..4], &r[5..8]);
    let n2 = w.madd(w, s);
    // 1/‖r0‖² to second order about 1 (module docs).
    let inv_n2 = L::splat(2.0).sub(n2);
    let v = L::splat(1.0).sub(w);
    let h = horner(&H, v);
    let h_s = horner(&H_S, v);
    // ∂h = ∂h/∂s · 2 a·b − wε / ‖r0‖².
    let h_du = h_s.add(h_s).msub(ab, inv_n2.mul(wd));
    let ln = L::splat(0.5).mul(n2.sub(L::splat(1.0)));
    let ln_du = w.madd(wd, ab).mul(inv_n2);
    eight(|c| match c {
        0 => ln,
        1..=3 => r[c].mul(h),
        4 => ln_du,
        _ => r[c].madd(h, r[c - 4].mul(h_du)),
    })
}

/// `exp x̂` of a dual quaternion's vector parts (`a + ε b`), its scalar factor `e^ŵ` left out
/// (see the module docs): `[cos √s, k a] + ε [−k a·b, k b + 2 ∂k/∂s a·b a]`, `k = sinc √s`.
#[inline(always)]
pub(in crate::fast) fn exp<L: Lane>(x: &[L; 8]) -> [L; 8] {
    let s = dot(&x[1..4], &x[1..4]);
    let ab = dot(&x[1..4], &x[5..8]);
    let (k, cos) = (horner(&SINC, s), horner(&COS, s));
    let k_du = ab.add(ab).mul(horner(&D_SINC, s));
    eight(|c| match c {
        0 => cos,
        1..=3 => k.mul(x[c]),
        4 => L::splat(0.0).sub(k.mul(ab)),
        _ => k.madd(x[c], k_du.mul(x[c - 4])),
    })
}

/// Whether each lane's iteration goes on (`keep_going` of the library): the update's
/// `norm` is finite, not below the precision, and not stuck (no smaller than the `last`
/// while within `STALL_FACTOR` × the precision).
#[inline(always)]
fn keep_going<L: Lane>(norm: L, last: L) -> L::Mask {
    let precision = L::splat(DIB_PRECISION);
    let above = precision.le(norm);
    let finite = norm.lt(L::splat(f32::INFINITY));
    let stuck = L::and(
        last.le(norm),
        norm.lt(L::splat(DIB_PRECISION * STALL_FACTOR as f32)),
    );
    L::and_not(stuck, L::and(above, finite))
}

/// Takes the update's `norm` into the lanes' stopping rule ([`keep_going`]): whether every
/// lane has stopped; `last` becomes `norm`.
#[inline(always)]
fn stopped<L: Lane>(norm: L, active: &mut L::Mask, last: &mut L) -> bool {
    *active = L::and(*active, keep_going(norm, *last));
    *last = norm;
    !L::any(*active)
}

/// A vertex's weights `raw` (in slots of K) as DIB takes them: the positive ones scaled to
/// sum to 1 (in the scalar kernel's order), the others 0; which slots are used; and how
/// many slots count — trailing slots unused in every lane are left out (in a mesh, vertices
/// side by side tend to have as many influences): their terms would be exact zeros. (One
/// reciprocal of the sum and K products instead of K divisions measured the same on
/// CesiumMan, 12.65–13.43 against 12.75–13.46 ns a vertex, three runs each in turn,
/// 2026-12-05: the divisions do not bound the kernel.)
#[inline(always)]
pub(in crate::fast) fn convex<L: Lane, const K: usize>(
    raw: [L; K],
) -> ([L; K], [L::Mask; K], usize) {
    let zero = L::splat(0.0);
    let used = raw.map(|w| zero.lt(w));
    let mut positive = [zero; K];
    let mut sum = zero;
    for k in 0..K {
        positive[k] = L::select(used[k], raw[k], zero);
        sum = sum.add(positive[k]);
    }
    let slots = (0..K).rev().find(|&k| L::any(used[k])).map_or(0, |k| k + 1);
    (positive.map(|x| x.div(sum)), used, slots)
}

/// The DIB blend of the first `slots` joint dual quaternions `q` with the convex weights
/// `w` ([`convex`]), in each lane: DLB against the pivot, then the iteration of the module
/// docs; the positive weights may sit in any of the slots. Every slot must hold a finite
/// dual quaternion, and unused ones weight 0 in every lane (the SIMD kernels put the
/// identity there).
#[inline(always)]
pub(in crate::fast) fn dib<L: Lane, const K: usize>(
    q: &[[L; 8]; K],
    w: &[L; K],
    slots: usize,
) -> [L; 8] {
    let zero = L::splat(0.0);
    // DIB of one transform is that transform, DLB's start already: a lane of one influence
    // takes no update. Lemma 3: DIB of two is ScLERP, which a lane of two influences takes
    // in closed form (`sclerp`) rather than by an update from DLB's start and the pass that
    // would show it converged; a lane of three or more iterates. All three rules count a
    // lane's positive weights wherever they sit (a layout built by hand need not put them
    // first), so they hold a lane whatever its block-mates do: a vertex's numbers do not
    // depend on its neighbours. A block with no lane of three influences or more makes no
    // update, one with no lane of two no ScLERP, and one whose lanes all have two no DLB.
    let one = L::splat(1.0);
    let mut count = zero;
    // By index, as the other loops over `slots` here (an iterator form of this loop,
    // `take(slots).skip(2)`, left a call to `nth` in the kernel).
    #[allow(clippy::needless_range_loop)]
    for k in 0..slots {
        count = count.add(L::select(zero.lt(w[k]), one, zero));
    }
    let pair = L::and(L::splat(1.5).lt(count), count.lt(L::splat(2.5)));
    // The lanes that iterate: three influences or more.
    let mut active = L::splat(2.5).lt(count);
    // DLB's start, read by the lanes of one influence and those that iterate.
    let mut b = if L::any(count.lt(L::splat(1.5))) || L::any(active) {
        dlb(q, w, slots)
    } else {
        q[0]
    };
    if L::any(active) {
        // The update's weights: 0 in a lane that never steps (module docs, "Subnormal
        // numbers").
        let mut wu = [zero; K];
        for k in 0..slots {
            wu[k] = L::select(active, w[k], zero);
        }
        let mut last = L::splat(f32::INFINITY);
        for k in 0..DIB_UPDATES {
            // After the first update, the pass that shows whether it converged takes the
            // update by one product ([`update_by_sum`]); a lane that goes on takes it again
            // with its moments.
            if k > 0 {
                let x = update_by_sum(&b, q, &wu, slots);
                if stopped(dot(&x, &x).sqrt(), &mut active, &mut last) {
                    break;
                }
            }
            let (x, spread) = update(&b, q, &wu, slots);
            // The vector parts' norm, as `update_by_sum`'s: the logarithms' scalar parts are
            // 0 but for rounding (`r̂` is unit), and so left out of the kernel altogether.
            let vector = [x[1], x[2], x[3], x[5], x[6], x[7]];
            if k == 0 && stopped(dot(&vector, &vector).sqrt(), &mut active, &mut last) {
                break;
            }
            let next = renormalize(&dqmul(&b, &exp(&spread.step(&x))));
            b = eight(|c| L::select(active, next[c], b[c]));
        }
    }
    if L::any(pair) {
        let screw = sclerp(q, w, slots);
        b = eight(|c| L::select(pair, screw[c], b[c]));
    }
    b
}

/// DLB in each lane against its pivot, the first of the heaviest (slot 0 in a
/// `FastRig::new`): DIB's start.
#[inline(always)]
fn dlb<L: Lane, const K: usize>(q: &[[L; 8]; K], w: &[L; K], slots: usize) -> [L; 8] {
    let zero = L::splat(0.0);
    let (mut pivot, mut heaviest) = (q[0], w[0]);
    for k in 1..slots {
        let more = heaviest.lt(w[k]);
        pivot = eight(|c| L::select(more, q[k][c], pivot[c]));
        heaviest = L::select(more, w[k], heaviest);
    }
    let mut sum = [zero; 8];
    for k in 0..slots {
        let wk = w[k].neg_where(dot(&q[k][..4], &pivot[..4]).lt(zero));
        sum = eight(|c| wk.madd(q[k][c], sum[c]));
    }
    normalize(&sum)
}

/// The dual dot product `⟨â, b̂⟩ = c + ε c_ε` — the scalar parts of `â* b̂`, `c = ⟨a0, b0⟩`,
/// `c_ε = ⟨a0, bε⟩ + ⟨aε, b0⟩` — taken to `c ≥ 0` (those of `±â* b̂`, as [`log`]'s `w ≥ 0`:
/// the shorter screw): `(|c|, ±c_ε, c)`, `c` itself for its sign. [`mod@sclerp`]'s ScLERP
/// and [`update_by_sum`]'s pass both start from it.
#[inline(always)]
fn shorter_dot<L: Lane>(a: &[L; 8], b: &[L; 8]) -> (L, L, L) {
    let c = dot(&a[..4], &b[..4]);
    let c_du = dot(&a[..4], &b[4..]).add(dot(&a[4..], &b[..4]));
    (c.flip_by_sign_of(c), c_du.flip_by_sign_of(c), c)
}

/// `q̂*`, the quaternion conjugate of both parts (the vector parts negated), in each lane.
#[inline(always)]
fn conjugate<L: Lane>(q: &[L; 8]) -> [L; 8] {
    let minus = L::splat(-1.0);
    eight(|c| match c {
        0 | 4 => q[c],
        _ => q[c].flip_by_sign_of(minus),
    })
}

/// One DIB update at `b̂` in each lane: `x̂ = Σ wᵢ log(b̂* q̂ᵢ)` over the first `slots`
/// influences, and the logarithms' moments for the second-order step. The logarithms are
/// taken two at a time, interleaved ([`Wide`]), and where `slots` is odd the last alone,
/// after the pairs (one copy of it in the kernel). Before 2026-12-05 the last was paired
/// with the slot past `slots` (the identity, weight 0 in every lane), whose terms were
/// `+0 · log` added to the sums: a block of three influences took four logarithms a pass.
/// Those terms could change only the sign of a sum that is exactly 0, and such a zero is
/// read only squared (the norm), through `0 − ·`, or as a product added to +0 or to a
/// number not 0 ([`Spread::step`]), each the same bits either way: so the results are the
/// same bits (the bit-for-bit tests pass unchanged). A change to the step must keep that. Alone, with `vertex_order`
/// sorting vertices of three apart from those of four (best of 30, one core, sixteen lanes,
/// the builds in turn three times, `examples/dib_influences`): CesiumMan cut to at most
/// three influences 4.00–4.10× → 3.72–3.83× DQS's time, CesiumMan 4.14–4.19× →
/// 3.92–3.96×, RiggedFigure 3.62–3.64× → 3.24–3.32×; the last alone without the new order
/// gave CesiumMan 4.09–4.11×, its blocks mixing three and four. With eight influence slots
/// (`FastRig<8>`, 5·10⁴ synthetic vertices cut to 3, 4, 5 and 8 influences, best of 15,
/// two runs each): 3 influences 42.2–42.3 → 46.0 M vertices/s, 5 32.1–32.7 → 34.6–35.5, 4
/// and 8 unchanged. (The pass that shows
/// the update converged does not need the moments; a kernel that left only them out there,
/// taking the logarithms again with their moments where a lane goes on, was 3–5 % slower:
/// 16.7 → 16.2 M vertices/s on four influences, 38.3 → 36.4 on two — a third copy of this
/// code, inlined, cost more than the 18 multiply-adds a logarithm it saved. The pass now
/// takes no logarithm at all: [`update_by_sum`].)
#[inline(always)]
fn update<L: Lane, const K: usize>(
    b: &[L; 8],
    q: &[[L; 8]; K],
    w: &[L; K],
    slots: usize,
) -> ([L; 8], Spread<L>) {
    let conj = conjugate(b).map(|c| Wide([c; 2]));
    let mut x = [L::splat(0.0); 8];
    let mut spread = Spread::default();
    // Up to K, known when compiled, rather than `slots`: 3–4 % faster on sixteen lanes, the
    // same on eight (best of runs, binaries in turn).
    for g in (0..K).step_by(2) {
        if g + 1 >= slots {
            break;
        }
        let q2 = eight(|c| Wide([q[g][c], q[g + 1][c]]));
        let l2 = log(&dqmul(&conj, &q2));
        for i in 0..2 {
            let l = eight(|c| l2[c].0[i]);
            x = eight(|c| w[g + i].madd(l[c], x[c]));
            spread.add(w[g + i], &l);
        }
    }
    // The last of an odd count alone, after the pairs (one copy of it in the kernel).
    if slots % 2 == 1 {
        let k = slots - 1;
        let l = log(&dqmul(&conj.map(|c| c.0[0]), &q[k]));
        x = eight(|c| w[k].madd(l[c], x[c]));
        spread.add(w[k], &l);
    }
    (x, spread)
}

#[cfg(test)]
mod tests;
