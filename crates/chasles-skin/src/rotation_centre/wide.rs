//! Four clusters solved at once, one in each lane of AVX2's four f64, or eight in
//! AVX-512F's: a cluster's solve is about 270 instructions one at a time (35 ns), the sums
//! over the joints by SSE2's pairs and the rest scalar; the compiler's own vectorization
//! of a four-lane form shuffled more than it computed, so the lanes are written with
//! intrinsics here. Eight lanes halve the solve's arithmetic and the sums' loads and adds
//! a cluster; the lanes are the same operations in the same order, so every width gives
//! the same bits. Both widths also choose between the solution and the prior and round to
//! f32 in the lanes (`pick`'s test, one lane at a time from the stored lanes, had taken
//! about a third of the eight-lane solve).

use super::{solve, solve_symmetric, system, Clusters, Motions, Num, Priors, Slot, FIELDS};
use std::arch::x86_64::*;
use std::ops::{Add, Div, Mul, Sub};

/// Four clusters' values of one quantity. Private to this module: its operators run AVX2
/// instructions, and only [`four`] (which requires AVX2) makes one.
#[derive(Clone, Copy)]
struct W(__m256d);

/// Eight clusters' values of one quantity, as [`W`] for AVX-512F ([`eights`]).
#[derive(Clone, Copy)]
struct W8(__m512d);

macro_rules! op {
    ($w:ident, $trait:ident, $f:ident, $intrinsic:ident) => {
        impl $trait for $w {
            type Output = $w;
            #[inline(always)]
            fn $f(self, o: $w) -> $w {
                // SAFETY: a `W` is made only inside `four`, which runs with AVX2, and a
                // `W8` only inside `eights` and what it inlines, which run with AVX-512F.
                $w(unsafe { $intrinsic(self.0, o.0) })
            }
        }
    };
}
op!(W, Add, add, _mm256_add_pd);
op!(W, Sub, sub, _mm256_sub_pd);
op!(W, Mul, mul, _mm256_mul_pd);
op!(W, Div, div, _mm256_div_pd);
op!(W8, Add, add, _mm512_add_pd);
op!(W8, Sub, sub, _mm512_sub_pd);
op!(W8, Mul, mul, _mm512_mul_pd);
op!(W8, Div, div, _mm512_div_pd);

/// [`Num`] for a lane type: `splat` by `$set1`, `at_most_one` by `$min` with 1.
macro_rules! num {
    ($w:ident, $set1:ident, $min:ident) => {
        impl Num for $w {
            #[inline(always)]
            fn splat(x: f64) -> Self {
                // SAFETY: as for the operators.
                $w(unsafe { $set1(x) })
            }
            #[inline(always)]
            fn at_most_one(self) -> Self {
                // n − 1 for a joint count n, never NaN: the same as `f64::min(n − 1, 1)`.
                // SAFETY: as for the operators.
                $w(unsafe { $min(self.0, $set1(1.0)) })
            }
        }
    };
}
num!(W, _mm256_set1_pd, _mm256_min_pd);
num!(W8, _mm512_set1_pd, _mm512_min_pd);

/// Each of `N` clusters' sums over its joints of their motions' 16 fields, in `R` registers
/// of `L` lanes (`L R = 16`): `add(a, m)` adds the `L` fields `m` of a motion to `a`. One
/// cluster after the other: all four clusters' accumulators at once (24 registers, when a
/// motion had 24 fields) spilled to the stack at every joint.
#[inline(always)]
fn sums<V: Copy, const N: usize, const R: usize, const L: usize>(
    joints: [&[u16]; N],
    motions: &Motions,
    zero: V,
    add: impl Fn(V, &[f64; L]) -> V,
) -> [[V; R]; N] {
    const { assert!(L * R == FIELDS) };
    let mut s = [[zero; R]; N];
    for (s, joints) in s.iter_mut().zip(joints) {
        let mut acc = [zero; R];
        for &j in joints {
            let m = motions.of(j);
            for (a, m) in acc.iter_mut().zip(m.as_chunks::<L>().0) {
                *a = add(*a, m);
            }
        }
        *s = acc;
    }
    s
}

/// The centres of four clusters about their priors (x, y, z, four lanes each): each one's
/// sums over its joints in four registers, transposed into one register per field, then
/// `solve` on the registers.
///
/// # Safety
/// The processor must have AVX2.
#[target_feature(enable = "avx2")]
pub(super) unsafe fn four(
    joints: [&[u16]; 4],
    motions: &Motions,
    priors: &[[f32; 4]; 3],
    out: &mut [Slot; 4],
) {
    chasles::frame::align_frame();
    let s: [[__m256d; 4]; 4] = sums(joints, motions, _mm256_setzero_pd(), |a, m: &[f64; 4]| {
        // SAFETY: `m` holds the four f64 loaded.
        _mm256_add_pd(a, unsafe { _mm256_loadu_pd(m.as_ptr()) })
    });
    let mut f = [W(_mm256_setzero_pd()); FIELDS];
    for r in 0..4 {
        let t0 = _mm256_unpacklo_pd(s[0][r], s[1][r]);
        let t1 = _mm256_unpackhi_pd(s[0][r], s[1][r]);
        let t2 = _mm256_unpacklo_pd(s[2][r], s[3][r]);
        let t3 = _mm256_unpackhi_pd(s[2][r], s[3][r]);
        f[4 * r] = W(_mm256_permute2f128_pd::<0x20>(t0, t2));
        f[4 * r + 1] = W(_mm256_permute2f128_pd::<0x20>(t1, t3));
        f[4 * r + 2] = W(_mm256_permute2f128_pd::<0x31>(t0, t2));
        f[4 * r + 3] = W(_mm256_permute2f128_pd::<0x31>(t1, t3));
    }
    let n = joints.map(|j| j.len() as f64);
    let n = W(_mm256_setr_pd(n[0], n[1], n[2], n[3]));
    // SAFETY: each row holds four f32.
    let prior = priors.map(|p| W(_mm256_cvtps_pd(unsafe { _mm_loadu_ps(p.as_ptr()) })));
    let (x, det) = solve(|i| f[i], n, prior);
    pick4(x, prior, det, out)
}

/// `pick` in four lanes, into `out` padded (one by one, the lanes' stores and reloads and
/// the scalar tests had taken about a third of the solve): the solution where 0 < det < ∞
/// (ordered: not NaN), else the prior, rounded to f32 as `as` rounds (to nearest), and the
/// four centres transposed out of the lanes in registers, one store each.
#[inline]
#[target_feature(enable = "avx2")]
fn pick4(x: [W; 3], prior: [W; 3], det: W, out: &mut [Slot; 4]) {
    let ok = _mm256_and_pd(
        _mm256_cmp_pd::<_CMP_GT_OQ>(det.0, _mm256_setzero_pd()),
        _mm256_cmp_pd::<_CMP_LT_OQ>(det.0, _mm256_set1_pd(f64::INFINITY)),
    );
    let [mut cx, mut cy, mut cz] =
        [0, 1, 2].map(|i| _mm256_cvtpd_ps(_mm256_blendv_pd(prior[i].0, x[i].0, ok)));
    let mut zero = _mm_setzero_ps();
    _MM_TRANSPOSE4_PS(&mut cx, &mut cy, &mut cz, &mut zero);
    for (o, c) in out.iter_mut().zip([cx, cy, cz, zero]) {
        // SAFETY: `o` holds four f32.
        unsafe { _mm_storeu_ps(o.as_mut_ptr().cast::<f32>(), c) };
    }
}

/// Transposes 8 registers of 8 f64: element k of result row c is element c of input k.
#[inline]
#[target_feature(enable = "avx512f")]
fn transpose8(a: [__m512d; 8]) -> [__m512d; 8] {
    // Pairs: t[2i] = (a[2i]₀, a[2i+1]₀, a[2i]₂, a[2i+1]₂, …), t[2i+1] the odd elements.
    let t: [__m512d; 8] = core::array::from_fn(|k| {
        let (x, y) = (a[k & !1], a[k | 1]);
        if k % 2 == 0 {
            _mm512_unpacklo_pd(x, y)
        } else {
            _mm512_unpackhi_pd(x, y)
        }
    });
    // Quads, by 128-bit lanes: u[4h + 0] = elements 0 and 4 of inputs 4h … 4h + 3, u[4h + 1]
    // elements 2 and 6, u[4h + 2] elements 1 and 5, u[4h + 3] elements 3 and 7.
    let quads = |h: usize| {
        let (e0, o0, e1, o1) = (t[4 * h], t[4 * h + 1], t[4 * h + 2], t[4 * h + 3]);
        [
            _mm512_shuffle_f64x2::<0x88>(e0, e1),
            _mm512_shuffle_f64x2::<0xDD>(e0, e1),
            _mm512_shuffle_f64x2::<0x88>(o0, o1),
            _mm512_shuffle_f64x2::<0xDD>(o0, o1),
        ]
    };
    let (lo, hi) = (quads(0), quads(1));
    // Element e of every input: e = 0, 4 from u[0]; 2, 6 from u[1]; 1, 5 from u[2];
    // 3, 7 from u[3].
    let row = |u: usize, high: bool| {
        if high {
            _mm512_shuffle_f64x2::<0xDD>(lo[u], hi[u])
        } else {
            _mm512_shuffle_f64x2::<0x88>(lo[u], hi[u])
        }
    };
    [
        row(0, false),
        row(2, false),
        row(1, false),
        row(3, false),
        row(0, true),
        row(2, true),
        row(1, true),
        row(3, true),
    ]
}

/// Groups of eight clusters' centres about their priors, as [`four`] on AVX-512F's eight
/// lanes, groups `g0 … g0 + out.len() / 8` (exclusive) into `out`, eight slots a group:
/// each group's sums over its joints in two registers, transposed into one register per
/// field ([`system8`]), then solved ([`end8`]). Each group's system is made before the
/// group before it is solved, so that its loads and sums are under way while that group's
/// division runs (the division ends each group's chain).
///
/// # Safety
/// The processor must have AVX-512F. (`out.len()` must be a multiple of 8 for every slot to
/// be written, and the groups must be whole groups of `clusters`, or the indexing panics.)
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn eights(
    clusters: &Clusters,
    g0: usize,
    motions: &Motions,
    priors: &[Priors],
    out: &mut [Slot],
) {
    chasles::frame::align_frame();
    debug_assert!(out.len().is_multiple_of(8), "whole groups");
    let groups = out.len() / 8;
    let at: *const [f32; 4] = out.as_ptr().cast();
    /// Group `g`'s system, the tables of the group [`super::AHEAD`] on asked for (`slots`:
    /// group g's first slot). A function, not a closure: a closure here stayed a call,
    /// compiled without AVX-512, its lanes' operations calls.
    ///
    /// # Safety
    /// As for [`eights`].
    #[inline(always)]
    unsafe fn take(
        clusters: &Clusters,
        g: usize,
        motions: &Motions,
        priors: &[Priors],
        slots: *const [f32; 4],
    ) -> System8 {
        clusters.ask_ahead(g, priors, slots);
        let j = |l: usize| clusters.joints(8 * g + l);
        let joints = [j(0), j(1), j(2), j(3), j(4), j(5), j(6), j(7)];
        // SAFETY: the caller's.
        unsafe { system8(joints, motions, &priors[g]) }
    }
    let slots = out.as_chunks_mut::<8>().0;
    // SAFETY (each take and end8): AVX-512F, as the caller promises.
    crate::fast::take_ahead(
        groups,
        true,
        #[inline(always)]
        |k| unsafe { take(clusters, g0 + k, motions, priors, at.wrapping_add(8 * k)) },
        #[inline(always)]
        |k, system| unsafe { end8(system, &mut slots[k]) },
    );
}

/// A group's system: A's lower triangle and b with the Tikhonov term, and the priors, in
/// lanes.
type System8 = ([W8; 6], [W8; 3], [W8; 3]);

/// Eight clusters' systems ([`super::system`]) from their joints' motions: each one's sums
/// over its joints in two registers, transposed into one register per field.
///
/// # Safety
/// Only from code that runs with AVX-512F ([`eights`], into which it is inlined; it cannot
/// carry `target_feature` with `inline(always)`).
#[inline(always)]
unsafe fn system8(joints: [&[u16]; 8], motions: &Motions, priors: &Priors) -> System8 {
    // SAFETY (each intrinsic): AVX-512F, as the caller promises; `m` holds the eight f64
    // loaded, `n` eight f64 and each row of priors eight f32.
    let s: [[__m512d; 2]; 8] = sums(
        joints,
        motions,
        W8::splat(0.0).0,
        |a, m: &[f64; 8]| unsafe { _mm512_add_pd(a, _mm512_loadu_pd(m.as_ptr())) },
    );
    let mut f = [W8::splat(0.0); FIELDS];
    for r in 0..2 {
        let rows = unsafe { transpose8(core::array::from_fn(|c| s[c][r])) };
        for (k, row) in rows.into_iter().enumerate() {
            f[8 * r + k] = W8(row);
        }
    }
    let n = joints.map(|j| j.len() as f64);
    let n = W8(unsafe { _mm512_loadu_pd(n.as_ptr()) });
    let prior = priors.map(|p| W8(unsafe { _mm512_cvtps_pd(_mm256_loadu_ps(p.as_ptr())) }));
    let (a, b) = system(|i| f[i], n, prior);
    (a, b, prior)
}

/// A group's centres from its system ([`super::solve_symmetric`], then [`pick8`]) into
/// `out`.
///
/// # Safety
/// As for [`system8`].
#[inline(always)]
unsafe fn end8((a, b, prior): System8, out: &mut [Slot; 8]) {
    let (x, det) = solve_symmetric(a, b);
    // SAFETY: the caller's.
    unsafe { pick8(x, prior, det, out) }
}

/// [`pick4`] in eight lanes: the centres transposed out of the lanes two a register, four
/// stores. The centres went out one float at a time before (stored by lanes, reloaded as
/// floats and stored padded), and that write took about a fifth of the eight-lane solve's
/// time by its samples (`perf record`, 2026-12-05).
#[inline]
#[target_feature(enable = "avx512f")]
fn pick8(x: [W8; 3], prior: [W8; 3], det: W8, out: &mut [Slot; 8]) {
    let ok = _mm512_cmp_pd_mask::<_CMP_GT_OQ>(det.0, _mm512_setzero_pd())
        & _mm512_cmp_pd_mask::<_CMP_LT_OQ>(det.0, _mm512_set1_pd(f64::INFINITY));
    let [cx, cy, cz] =
        [0, 1, 2].map(|i| _mm512_cvtpd_ps(_mm512_mask_blend_pd(ok, prior[i].0, x[i].0)));
    let zero = _mm256_setzero_ps();
    // Lanes l and l + 4 of each: (x, y) and (z, 0) pairs, then whole centres.
    let (xy_lo, xy_hi) = (_mm256_unpacklo_ps(cx, cy), _mm256_unpackhi_ps(cx, cy));
    let (z0_lo, z0_hi) = (_mm256_unpacklo_ps(cz, zero), _mm256_unpackhi_ps(cz, zero));
    // c[k] holds centres k (low half) and k + 4 (high half).
    let c = [
        _mm256_shuffle_ps::<0x44>(xy_lo, z0_lo),
        _mm256_shuffle_ps::<0xEE>(xy_lo, z0_lo),
        _mm256_shuffle_ps::<0x44>(xy_hi, z0_hi),
        _mm256_shuffle_ps::<0xEE>(xy_hi, z0_hi),
    ];
    let pairs = [
        _mm256_permute2f128_ps::<0x20>(c[0], c[1]),
        _mm256_permute2f128_ps::<0x20>(c[2], c[3]),
        _mm256_permute2f128_ps::<0x31>(c[0], c[1]),
        _mm256_permute2f128_ps::<0x31>(c[2], c[3]),
    ];
    for (o, p) in out.chunks_exact_mut(2).zip(pairs) {
        // SAFETY: `o` holds two centres of four f32, eight f32 side by side.
        unsafe { _mm256_storeu_ps(o.as_mut_ptr().cast::<f32>(), p) };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lanes' choice of solution or prior and its rounding are `pick`'s, bit for bit, on
    /// every kind of determinant (NaN, ±∞, ±0, negative, subnormal, tiny, huge) and of
    /// value (NaN, ±∞, f64's extremes, values that round, halfway cases) in every lane.
    #[test]
    fn the_lanes_pick_as_pick_does() {
        let dets = [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            0.0,
            -0.0,
            -1.0,
            f64::MIN_POSITIVE / 4.0,
            1e-300,
            1.0,
            f64::MAX,
        ];
        let values = [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
            -f64::MAX,
            1e-310,
            1.0 + f64::EPSILON,
            0.1,
            -3.5,
            f64::from(f32::MAX) * 1.5,
            1.0 + 2f64.powi(-24),
        ];
        let x8 =
            |k: usize| -> [f64; 8] { core::array::from_fn(|l| values[(k + 3 * l) % values.len()]) };
        let p8 = |k: usize| -> [f64; 8] {
            core::array::from_fn(|l| values[(k + 5 * l + 1) % values.len()])
        };
        let all = super::super::Lanes::allowed(true, true);
        let have = (all.avx2, all.avx512);
        for shift in 0..dets.len() {
            let det: [f64; 8] = core::array::from_fn(|l| dets[(l + shift) % dets.len()]);
            let (x, prior) = (
                [0, 1, 2].map(|i| x8(shift + i)),
                [0, 1, 2].map(|i| p8(shift + i)),
            );
            let want: [[f32; 4]; 8] = core::array::from_fn(|l| {
                super::super::pad(super::super::pick(
                    [x[0][l], x[1][l], x[2][l]],
                    [prior[0][l], prior[1][l], prior[2][l]],
                    det[l],
                ))
            });
            let bits = |v: &[[f32; 4]]| v.iter().map(|c| c.map(f32::to_bits)).collect::<Vec<_>>();
            if have.0 {
                for h in [0, 4] {
                    // SAFETY: the processor has AVX2; each array holds four f64 from `h`.
                    let got = unsafe { four_lanes(&x, &prior, &det, h) };
                    assert_eq!(bits(&got), bits(&want[h..h + 4]), "shift {shift} half {h}");
                }
            }
            if have.1 {
                // SAFETY: the processor has AVX-512F.
                let got = unsafe { eight_lanes(&x, &prior, &det) };
                assert_eq!(bits(&got), bits(&want), "shift {shift}");
            }
        }
        if !have.1 {
            eprintln!("no AVX-512F here: the eight lanes' pick was not checked");
        }
    }

    /// [`pick4`] on lanes `h … h + 3` of the arrays (into centres of NaN, all overwritten).
    #[target_feature(enable = "avx2")]
    unsafe fn four_lanes(
        x: &[[f64; 8]; 3],
        p: &[[f64; 8]; 3],
        det: &[f64; 8],
        h: usize,
    ) -> [[f32; 4]; 4] {
        // SAFETY: `h` is 0 or 4, so each load reads four f64 of an array of eight.
        let w = |a: &[f64; 8]| W(unsafe { _mm256_loadu_pd(a.as_ptr().add(h)) });
        let mut out = super::super::nan_slots();
        pick4(x.each_ref().map(w), p.each_ref().map(w), w(det), &mut out);
        // SAFETY: the slots of `nan_slots` hold values.
        unsafe { super::super::read_slots(out) }
    }

    /// [`pick8`] on the arrays (into centres of NaN, all overwritten).
    #[target_feature(enable = "avx512f")]
    unsafe fn eight_lanes(x: &[[f64; 8]; 3], p: &[[f64; 8]; 3], det: &[f64; 8]) -> [[f32; 4]; 8] {
        // SAFETY: each load reads the eight f64 of an array of eight.
        let w = |a: &[f64; 8]| W8(unsafe { _mm512_loadu_pd(a.as_ptr()) });
        let mut out = super::super::nan_slots();
        pick8(x.each_ref().map(w), p.each_ref().map(w), w(det), &mut out);
        // SAFETY: the slots of `nan_slots` hold values.
        unsafe { super::super::read_slots(out) }
    }
}
