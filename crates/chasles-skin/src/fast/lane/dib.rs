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
//! are taken two at a time, interleaved ([`Wide`]).
//!
//! **One and two influences** (the paper's own identities): DIB of one transform is that
//! transform, so a lane of one influence keeps DLB's start and takes no update; for two,
//! Lemma 3 shows that one update reaches the blend (ScLERP) and that the next pass only
//! finds ‖x̂‖ = 0 — so a lane of two influences stops after its first update, the pass that
//! would show it is left out (on one screw the second-order step is the paper's, so the
//! lemma holds for it: [`second_order`]'s tests), and a block of lanes of at most two makes
//! that one update alone: 1.4× faster on such meshes (`examples/dib_influences`: 27 → 38.5
//! M vertices/s, 6.8× → 4.8× DQS's time; the Fox, 85 % of whose blocks are such, 26 → 32).
//! Both rules look at a lane's own weights only, so a vertex's numbers do not depend on its
//! block-mates (the kernel's tests shift every block and compare bits); the GPU shader
//! takes ScLERP in closed form for such a vertex.
//!
//! No trigonometric calls. For `r̂ = b̂* q̂ᵢ` taken to `w ≥ 0`, with `r0 = (w, a)`,
//! `rε = (wε, b)`, `n = ‖a‖`, `s = n²` (eq. 2 and the library's `DualQuat::log`):
//!
//! ```text
//! log r̂ = [½ ln‖r0‖², h a] + ε [r0·rε / ‖r0‖², h b + a (2 ∂h/∂s a·b − wε / ‖r0‖²)],
//! h = atan2(n, w) / n
//! ```
//!
//! The angle is reduced to `|t| ≤ tan(π/8)` and summed by a polynomial for
//! `Q(z) = atan(√z)/√z = Σ (−1)ᵏ zᵏ/(2k+1)`, z = t² ≤ 0.172: six terms fitted near minimax on
//! that interval (`scripts/fit_dib_log.py`, checked by CI), exact to 6e-10 where the
//! Taylor series took ten to 1e-9:
//!
//! ```text
//! n ≤ tan(π/8) w:   t = n/w,             h = Q(t²)/w,  ∂h/∂s = −G(t²)/(2w³)
//! n ≥ w/tan(π/8):   t = w/n,             θ = π/2 − t Q(t²)
//! between:          t = (n − w)/(n + w), θ = π/4 + t Q(t²)
//! ```
//!
//! with `G(z) = Σ (−1)ᵏ 2(k+1)/(2k+3) zᵏ` (the library's series; fitted likewise, seven
//! terms to 3e-10 where the series took eleven to 4e-9 — both fits as accurate as the
//! series in f32, and four multiply-adds fewer on each of a logarithm's two longest chains:
//! best of runs at 10⁵ vertices, one core, binaries in turn: 4 influences 28.2 → 29.6 M
//! vertices/s on sixteen lanes and 21.2 → 22.6 on eight, CesiumMan 40.0 → 42.4 and
//! 33.7 → 36.3) and, in the last two rows
//! (n > 0.38 ‖r0‖, no cancellation), `h = θ/n`, `∂h/∂s = (w n/‖r0‖² − θ)/(2 n s)`. The
//! exponential's `cos √s`, `sinc √s` and `d sinc √s / ds` are Taylor series in `s = ‖a‖²`
//! for the step's `a`, truncated below 1e-8 at `s = (π/2)²` (a convex blend of half-angles
//! in [0, π/2] stays in it; the second-order step can reach a little past it, where the
//! neglected terms stay below 1e-7, and a step's error costs only speed: the stopping rule
//! looks at the logarithms, not at the step). Two shortcuts, both exact after the normalization
//! that follows, which only the update's norm sees: the exponential's scalar factor `e^ŵ`
//! (a positive dual number, which normalizing removes) is left out, and `½ ln‖r0‖²` is taken
//! as `½ (‖r0‖² − 1)` (r̂ is a product of unit dual quaternions: off by under 1e-14).

mod second_order;

use super::wide::Wide;
use super::{dot, dqmul, horner, taylor, Lane};
use crate::skinning::{DIB_PRECISION, DIB_UPDATES};
use chasles::blend::STALL_FACTOR;
use second_order::Spread;

/// `tan(π/8) = √2 − 1`: where the angle reductions change.
const TAN_PI_8: f32 = 0.414_213_57;
/// `Q(z) = atan(√z)/√z` on `0 ≤ z ≤ tan²(π/8)`, constant term first: fitted near minimax by
/// `scripts/fit_dib_log.py` (exact to 6e-10; 0.011 f32 ulp with these f32 coefficients).
pub(in crate::fast) const Q: [f32; 6] = [
    1.0,
    -0.33333308,
    0.1999821,
    -0.14239983,
    0.10572814,
    -0.060332417,
];
/// `G(z) = (atan √z − √z/(1+z))/z^{3/2}` on the same interval (the series
/// `(−1)ᵏ 2(k+1)/(2k+3)`), fitted likewise: exact to 3e-10, 0.34 f32 ulp with these f32
/// coefficients (most of it 2/3 rounded to f32, as in the series' table).
pub(in crate::fast) const G: [f32; 7] = [
    0.6666667,
    -0.79999983,
    0.85712785,
    -0.8883507,
    0.89979506,
    -0.83857864,
    0.52866524,
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
    let inv = L::splat(1.0).div(dot(&q[..4], &q[..4]).sqrt());
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
    let zero = L::splat(0.0);
    let r = eight(|c| r[c].flip_by_sign_of(r[0]));
    let (w, wd) = (r[0], r[4]);
    let s = dot(&r[1..4], &r[1..4]);
    let ab = dot(&r[1..4], &r[5..8]);
    let n2 = w.madd(w, s);
    let inv_n2 = L::splat(1.0).div(n2);
    let n = s.sqrt();
    let near = n.le(L::splat(TAN_PI_8).mul(w));
    let far = w.lt(L::splat(TAN_PI_8).mul(n));
    let num = L::select(near, n, L::select(far, w, n.sub(w)));
    let den = L::select(near, w, L::select(far, n, n.add(w)));
    let t = num.div(den);
    let z = t.mul(t);
    let q = horner(&Q, z);
    let offset = L::select(
        near,
        zero,
        L::select(
            far,
            L::splat(std::f32::consts::FRAC_PI_2),
            L::splat(std::f32::consts::FRAC_PI_4),
        ),
    );
    let theta = t.neg_where(far).madd(q, offset);
    let h = L::select(near, q, theta).div(L::select(near, w, n));
    let h_s = L::select(near, zero.sub(horner(&G, z)), w.mul(n).msub(inv_n2, theta))
        .div(L::select(near, w.add(w).mul(w.mul(w)), n.add(n).mul(s)));
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

/// A vertex's weights `raw` (in slots of K) as DIB takes them: the positive ones scaled to
/// sum to 1 (in the scalar kernel's order), the others 0; which slots are used; and how
/// many slots count — trailing slots unused in every lane are left out (in a mesh, vertices
/// side by side tend to have as many influences): their terms would be exact zeros.
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
/// dual quaternion, and unused ones weight 0 in every lane (the AVX2 kernel puts the
/// identity there): where `slots` is odd, the slot after it is computed with its pair and
/// adds exact zeros.
#[inline(always)]
pub(in crate::fast) fn dib<L: Lane, const K: usize>(
    q: &[[L; 8]; K],
    w: &[L; K],
    slots: usize,
) -> [L; 8] {
    let zero = L::splat(0.0);
    // DLB against the pivot: the first of the heaviest (slot 0 in a `FastRig::new`).
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
    let mut b = normalize(&sum);
    // DIB of one transform is that transform, DLB's start already: a lane of one influence
    // takes no update. Lemma 3: for two, one update reaches the blend (ScLERP), and the
    // next pass only finds ‖x̂‖ = 0. So a lane of two influences stops after its first
    // update — the pass that would show it converged is left out — and a block of lanes of
    // at most two (in the first two slots) makes that one update and no more. Both rules
    // count a lane's positive weights wherever they sit (a layout built by hand need not
    // put them first), so they hold a lane whatever its block-mates do: a vertex's numbers
    // do not depend on its neighbours. (A block of one influence a lane still computes the
    // update it does not take: returning before it, here or in the kernel, made the
    // iteration's code 3–5 % slower on CesiumMan.)
    let mut count = zero;
    // By index, as the other loops over `slots` here (an iterator form of this loop,
    // `take(slots).skip(2)`, left a call to `nth` in the kernel).
    #[allow(clippy::needless_range_loop)]
    for k in 0..slots {
        count = count.add(L::select(zero.lt(w[k]), L::splat(1.0), zero));
    }
    let pair = count.lt(L::splat(2.5));
    // Where a block's lanes all have two influences or fewer but some sit past slot 1 (a
    // hand-built layout), the loop still takes its second pass, which stops every lane at
    // once: it costs time, not bits. Capping by `count` instead made every block 4–6 %
    // slower (2 influences 38.8 → 36.5 M vertices/s, 4 influences 16.7 → 16.1).
    let updates = if slots <= 2 { 1 } else { DIB_UPDATES };
    let mut last = L::splat(f32::INFINITY);
    let mut active = L::splat(1.5).lt(count);
    for _ in 0..updates {
        let (x, spread) = update(&b, q, w, slots);
        let norm = dot(&x, &x).sqrt();
        active = L::and(active, keep_going(norm, last));
        if !L::any(active) {
            break;
        }
        last = norm;
        let next = normalize(&dqmul(&b, &exp(&spread.step(&x))));
        b = eight(|c| L::select(active, next[c], b[c]));
        active = L::and_not(pair, active);
    }
    b
}

/// One DIB update at `b̂` in each lane: `x̂ = Σ wᵢ log(b̂* q̂ᵢ)` over the first `slots`
/// influences, and the logarithms' moments for the second-order step. The logarithms are
/// taken two at a time, interleaved ([`Wide`]); where `slots` is odd the last pair's second,
/// past `slots`, adds exact zeros (weight 0, a finite log: see [`dib`]). Testing `k < K`
/// (known when compiled) rather than `k < slots` measured 1.1× faster. (The pass that shows
/// the update converged does not need the moments, but a kernel that left them out there,
/// taking the logarithms again with their moments where a lane goes on, was 3–5 % slower:
/// 16.7 → 16.2 M vertices/s on four influences, 38.3 → 36.4 on two — a third copy of this
/// code, inlined, costs more than the 18 multiply-adds a logarithm it saves.)
#[inline(always)]
fn update<L: Lane, const K: usize>(
    b: &[L; 8],
    q: &[[L; 8]; K],
    w: &[L; K],
    slots: usize,
) -> ([L; 8], Spread<L>) {
    let minus = L::splat(-1.0);
    let conj = eight(|c| match c {
        0 | 4 => Wide([b[c]; 2]),
        _ => Wide([b[c].flip_by_sign_of(minus); 2]),
    });
    let mut x = [L::splat(0.0); 8];
    let mut spread = Spread::default();
    // Up to K, known when compiled, rather than `slots`: 3–4 % faster on sixteen lanes, the
    // same on eight (best of runs, binaries in turn).
    for g in (0..K).step_by(2) {
        if g >= slots {
            break;
        }
        let at = |i: usize| (g + i).min(K - 1);
        let q2 = eight(|c| Wide([q[at(0)][c], q[at(1)][c]]));
        let l2 = log(&dqmul(&conj, &q2));
        for i in 0..2 {
            let k = g + i;
            if k < K {
                let l = eight(|c| l2[c].0[i]);
                x = eight(|c| w[k].madd(l[c], x[c]));
                spread.add(w[k], &l);
            }
        }
    }
    (x, spread)
}

#[cfg(test)]
mod tests {
    use super::*;
    use chasles::{DualQuat, Quat, Vec3};

    /// `Σ cₖ sᵏ` in f64: the value of a series' f32 coefficients.
    fn sum64(c: &[f32], s: f64) -> f64 {
        c.iter().rev().fold(0.0, |a, k| a * s + f64::from(*k))
    }

    /// The fitted `Q` and `G` are their closed forms on `[0, tan²(π/8)]` as
    /// `scripts/fit_dib_log.py` documents (relative: 0.02 f32 ulp for Q, 0.4 for G with their
    /// f32 coefficients; 0.5 and 1 ulp evaluated in f32), the exponential's Taylor series
    /// theirs up to `s = (π/2)²`.
    #[test]
    fn the_series_are_the_closed_forms() {
        let ulp = f64::from(f32::EPSILON);
        // The closed forms at z; G near 0 by its series (its closed form cancels there).
        let q_of = |z: f64| {
            if z == 0.0 {
                1.0
            } else {
                z.sqrt().atan() / z.sqrt()
            }
        };
        let g_of = |z: f64| {
            if z < 0.01 {
                (0..30).rev().fold(0.0, |a, k| {
                    let k = f64::from(k);
                    a * -z + 2.0 * (k + 1.0) / (2.0 * k + 3.0)
                })
            } else {
                let r = z.sqrt();
                (r.atan() - r / (1.0 + z)) / (z * r)
            }
        };
        let rel = |got: f64, want: f64| (got - want).abs() / want / ulp;
        for i in 0..=1000 {
            let f = f64::from(i) / 1000.0;
            // Q and G up to tan²(π/8): exactly (their f32 coefficients), and in f32 at the
            // f32 nearest z.
            let z = f * (2f64.sqrt() - 1.0).powi(2);
            assert!(rel(sum64(&Q, z), q_of(z)) <= 0.02, "Q({z})");
            assert!(rel(sum64(&G, z), g_of(z)) <= 0.4, "G({z})");
            let z32 = z as f32;
            let (q32, g32) = (horner(&Q, z32), horner(&G, z32));
            let z = f64::from(z32);
            assert!(rel(f64::from(q32), q_of(z)) <= 0.5, "Q({z}) in f32: {q32}");
            assert!(rel(f64::from(g32), g_of(z)) <= 1.0, "G({z}) in f32: {g32}");
            // cos √s, sinc √s and its derivative up to s = (π/2)².
            let x = f * std::f64::consts::FRAC_PI_2;
            let s = x * x;
            assert!((sum64(&COS, s) - x.cos()).abs() < 5e-8, "cos {x}");
            if x > 0.1 {
                assert!((sum64(&SINC, s) - x.sin() / x).abs() < 5e-8, "sinc {x}");
                let d = (x.cos() - x.sin() / x) / (2.0 * s);
                assert!((sum64(&D_SINC, s) - d).abs() < 5e-8, "d sinc {x}");
            }
        }
    }

    /// A unit dual quaternion turning by `angle` about a varying axis and moving by up to 2.
    fn rigid(f: f32, angle: f32) -> DualQuat<f32> {
        let axis = Vec3::new(1.0, 3.0 * f - 1.0, (7.0 * f).sin());
        let q = Quat::from_axis_angle(axis, angle).unwrap();
        let t = Vec3::new(2.0 * f, 1.0 - f, (3.0 * f).cos());
        DualQuat::from_rotation_translation(q, t)
    }

    /// On one lane the series' logarithm and exponential are the library's `DualQuat::log`
    /// and `exp` (eq. 2 and its inverse; the exponential up to its positive scalar factor,
    /// which the normalization removes) at every angle of all three reduction rows, both
    /// hemispheres, −0 included.
    #[test]
    fn the_lane_log_and_exp_are_the_librarys() {
        for i in 0..=400 {
            let f = i as f32 / 400.0;
            // Half-angles 0 … π: w from 1 through 0 to −1.
            let d = rigid(f, std::f32::consts::TAU * f);
            let got = log(&d.to_array());
            let want = if d.real.w < 0.0 { -d } else { d }
                .log()
                .unwrap()
                .to_array();
            for c in 0..8 {
                let tol = 2e-6 * (1.0 + want[c].abs());
                assert!((got[c] - want[c]).abs() < tol, "{f}: {got:?} vs {want:?}");
            }
            // The exponential of a convex blend's update: half-angles up to π/2.
            let mut x = rigid(f, std::f32::consts::PI * f).log().unwrap().to_array();
            x[0] = 0.0;
            x[4] = 0.0;
            let got = normalize(&exp(&x));
            let want = DualQuat::from_array(x)
                .exp()
                .normalize()
                .unwrap()
                .to_array();
            for c in 0..8 {
                assert!((got[c] - want[c]).abs() < 2e-6, "{f}: {got:?} vs {want:?}");
            }
        }
        // w = −0: the sign bit alone takes r̂ to −r̂ (the identity's antipode's log is 0).
        let mut antipode = [0f32; 8];
        antipode[0] = -1.0;
        assert_eq!(log(&antipode), [0.0; 8]);
        let mut half_turn = [0f32; 8];
        (half_turn[0], half_turn[1]) = (-0.0, -1.0);
        let l = log(&half_turn);
        assert!((l[1] - std::f32::consts::FRAC_PI_2).abs() < 1e-6, "{l:?}");
    }

    /// The second-order step does what its derivation says: from the DLB start of random
    /// blends of four joints (rotated by up to 60°, moved by up to 2), one step leaves a
    /// residual `‖Σ wᵢ log(b̂* q̂ᵢ)‖` over 20× smaller on average than the paper's step does
    /// (43× when written) — third order against first order times the spread² — and never
    /// a larger one beyond f32's rounding.
    #[test]
    fn the_second_order_step_leaves_a_smaller_residual() {
        let residual = |b: &[f32; 8], q: &[[f32; 8]; 4], w: &[f32; 4]| update(b, q, w, 4);
        let norm = |x: &[f32; 8]| dot(x, x).sqrt();
        let (mut plain, mut second) = (0f64, 0f64);
        for i in 0..500 {
            let f = i as f32 / 500.0;
            let q = [0.13, 0.37, 0.61, 0.83]
                .map(|g| rigid((f * 7.0 + g) % 1.0, 1.05 * ((f * 13.0 + g) % 1.0)).to_array());
            let raw = [0.4, 0.3 * f + 0.05, 0.2, 0.1 + 0.2 * (1.0 - f)];
            let (w, _, _) = convex(raw);
            let qs: Vec<DualQuat<f32>> = q.iter().map(|a| DualQuat::from_array(*a)).collect();
            let b = chasles::blend::dlb::dlb(&qs, &w).unwrap().to_array();
            let (x, spread) = residual(&b, &q, &w);
            let after = |d: [f32; 8]| norm(&residual(&normalize(&dqmul(&b, &exp(&d))), &q, &w).0);
            let (p, s) = (after(x), after(spread.step(&x)));
            // f32's rounding floor of the residual: about 1e-7.
            assert!(s <= p.max(3e-7), "{i}: {s} against {p} (from {})", norm(&x));
            plain += f64::from(p);
            second += f64::from(s);
        }
        assert!(
            second * 20.0 < plain,
            "mean residual {second} against {plain}"
        );
    }

    /// Lemma 3 on one lane: a blend of two joints (or one) takes a single update and no
    /// pass to show it converged, and still ends at ScLERP — within 1e-5 (relative to
    /// 1 + |x|) of the library's f64 `sclerp` at every relative angle up to 178°, moved by
    /// up to 2, either hemisphere — and where
    /// the pass that was left out would have stopped at once (its update is below the
    /// precision). One joint gives the joint itself.
    #[test]
    fn two_joints_end_at_sclerp_after_one_update() {
        // (f32's rounding along the chain of products, logarithm and exponential: 6.1e-6 at
        // worst when written.)
        for i in 0..=300 {
            let f = i as f32 / 300.0;
            let p = rigid(f, 2.0 * f - 1.0);
            let rel = rigid((f * 7.0) % 1.0, 3.1 * f);
            let mut qj = p * rel;
            if i % 2 == 1 {
                qj = -qj; // the other hemisphere: the same transformation
            }
            for t in [0.0f32, 0.1, 0.37, 0.5, 0.8] {
                let (w, _, slots) = convex([1.0 - t, t, 0.0, 0.0]);
                let identity = DualQuat::<f32>::identity().to_array();
                let q = [p.to_array(), qj.to_array(), identity, identity];
                let got = dib::<f32, 4>(&q, &w, slots);
                let want = chasles::blend::sclerp::sclerp(
                    p.cast::<f64>(),
                    qj.cast::<f64>(),
                    f64::from(w[1]),
                )
                .unwrap();
                let want = if want.real.dot(DualQuat::from_array(got).real.cast()) < 0.0 {
                    -want
                } else {
                    want
                };
                for (c, (g, x)) in got.iter().zip(want.to_array()).enumerate() {
                    assert!(
                        (f64::from(*g) - x).abs() < 1e-5 * (1.0 + x.abs()),
                        "{i}, t = {t}, {c}: {got:?} against {want:?}"
                    );
                }
                let (x, _) = update(&got, &q, &w, slots);
                let norm = dot(&x, &x).sqrt();
                assert!(norm < DIB_PRECISION, "{i}, t = {t}: {norm}");
            }
        }
        let p = rigid(0.3, 1.2).to_array();
        let (w, _, slots) = convex([1.0f32, 0.0, 0.0, 0.0]);
        let identity = DualQuat::<f32>::identity().to_array();
        let got = dib::<f32, 4>(&[p, identity, identity, identity], &w, slots);
        for c in 0..8 {
            assert!((got[c] - p[c]).abs() < 1e-6, "{got:?} against {p:?}");
        }
    }

    /// The positive weights may sit in any slots (weights of 0 between them, the identity
    /// in those slots, as the kernel puts it): on one lane DIB gives the same bits as with
    /// them in the first slots, for every count from one to K (4 and 8), pairs beyond slot
    /// 1 included (the counts that decide no update, one update, or the iteration).
    #[test]
    fn influences_in_any_slots_give_the_same_bits() {
        fn check<const K: usize>() {
            let identity = DualQuat::<f32>::identity().to_array();
            for i in 0..400 {
                let f = i as f32 / 400.0;
                let count = 1 + i % K;
                // `count` increasing slots out of K, by the bits of a mixed number.
                let mut at: Vec<usize> = Vec::new();
                let mut h = (i * 7919 + 13) % (1 << K);
                for k in 0..K {
                    if at.len() + (K - k) == count || (h & 1 == 1 && at.len() < count) {
                        at.push(k);
                    }
                    h >>= 1;
                }
                assert_eq!(at.len(), count);
                let joints: Vec<[f32; 8]> = (0..count)
                    .map(|c| {
                        rigid(
                            (f * 5.0 + 0.17 * c as f32) % 1.0,
                            1.4 * ((f + 0.3 * c as f32) % 1.0),
                        )
                        .to_array()
                    })
                    .collect();
                let raw: Vec<f32> = (0..count)
                    .map(|c| 0.2 + ((f * 11.0 + c as f32 * 0.37) % 1.0))
                    .collect();
                let lay = |slot: &dyn Fn(usize) -> usize| {
                    let (mut q, mut w) = ([identity; K], [0f32; K]);
                    for c in 0..count {
                        (q[slot(c)], w[slot(c)]) = (joints[c], raw[c]);
                    }
                    let (w, _, slots) = convex(w);
                    dib::<f32, K>(&q, &w, slots)
                };
                let (compact, scattered) = (lay(&|c| c), lay(&|c| at[c]));
                assert_eq!(
                    compact.map(f32::to_bits),
                    scattered.map(f32::to_bits),
                    "K = {K}, {i}: slots {at:?}: {compact:?} against {scattered:?}"
                );
            }
        }
        check::<4>();
        check::<8>();
    }

    /// On one lane the branch-free DIB is the library's DIB: the same blend to within the
    /// stopping rule's reach, on convex weights of two to four joints at every angle, and a
    /// NaN joint with weight gives NaN (or stops at once) rather than a number.
    #[test]
    fn the_lane_dib_is_the_librarys() {
        for i in 0..200 {
            let f = i as f32 / 200.0;
            let joints = [0.1, 0.4, 0.7, 0.9].map(|g| rigid((f + g) % 1.0, 2.8 * (f + g)));
            let raw = [
                0.5 * (1.0 - f),
                0.3,
                0.2 * f,
                if i % 3 == 0 { 0.0 } else { 0.1 },
            ];
            let (w, used, slots) = convex(raw);
            let q = std::array::from_fn(|k| {
                if used[k] {
                    joints[k].to_array()
                } else {
                    DualQuat::<f32>::identity().to_array()
                }
            });
            let got = DualQuat::from_array(dib::<f32, 4>(&q, &w, slots));
            let (qs, ws): (Vec<DualQuat<f64>>, Vec<f64>) = (0..4)
                .filter(|&k| used[k])
                .map(|k| (joints[k].cast::<f64>(), f64::from(w[k])))
                .unzip();
            let (want, _) = chasles::blend::dib::dib(&qs, &ws, 1e-12, 200).unwrap();
            let p = Vec3::new(0.5f32, -1.0, 2.0);
            let exact = want.transform_point(p.cast::<f64>());
            let off = (got.transform_point(p).cast::<f64>() - exact).norm();
            // The stopping rule's reach at a lever of ‖p‖ ≈ 2.3, and rounding.
            let reach = 2.0 * f64::from(DIB_PRECISION) * (1.0 + 2.0 * 2.3) + 1e-5;
            assert!(off <= reach, "{i}: {off}");
        }
        let mut q = [DualQuat::<f32>::identity().to_array(); 4];
        q[1][2] = f32::NAN;
        let (w, _, slots) = convex([0.5f32, 0.5, 0.0, 0.0]);
        assert!(dib::<f32, 4>(&q, &w, slots).iter().all(|c| c.is_nan()));
    }
}
