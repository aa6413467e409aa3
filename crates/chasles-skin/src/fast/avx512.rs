//! DIB (Kavan et al. 2006, §4, the box "DIB") sixteen vertices at a time with AVX-512F,
//! where the processor has it and AVX-512VL (chosen at run time, as the other kernels'
//! 32-register builds are, `avx2::registers`; `set_avx512` forbids both): the lane
//! algebra's branch-free DIB (`lane::dib`) on `__m512`, one vertex a lane, with the AVX2
//! kernel's loads, transposes and stores on each half of eight. Every operation is the
//! eight-lane one's on twice the lanes (`lane::avx512`), so each vertex gets the AVX2
//! kernel's very bits, and a mesh's last block of eight goes through that kernel.
//!
//! Why sixteen lanes help DIB (and only DIB): its update keeps more values alive than
//! AVX2's sixteen registers hold — the eight-lane kernel's loop body spills about a third
//! of its operands to the stack — while AVX-512's thirty-two hold them, its comparisons
//! land in mask registers, and one instruction does sixteen lanes' work. The other methods
//! are a few dozen instructions a vertex, bound by how many the core issues a cycle and by
//! the memory; they take AVX-512's registers alone, on their eight lanes
//! (`avx2::registers`).
//!
//! Tried on sixteen lanes and not kept (best of runs at 10⁵ vertices, one core, the
//! variants in turn, 2026-12-04):
//! - A block pays for the iteration where any of its lanes has three influences or more,
//!   and sixteen lanes make mixed blocks likelier (CesiumMan: 145 of its 205 blocks of
//!   sixteen iterate; 72 would, its vertices grouped by count). Taking each window of 256
//!   vertices in an order made at run time — those of two influences or fewer first, by
//!   a gather of slot 2's weights and two compressing stores, then loads by index and each
//!   vertex's own stores — made blocks of two 23 % slower and of four 16 % slower (63 → 49,
//!   29.9 → 25.2 M vertices/s), so that the alternating 2/4 mix gained nothing (29.8 both)
//!   and CesiumMan and the Fox lost 3–4 %: the indexed loads and stores, and the vertex
//!   pointers spilled with them, cost more than the iterating blocks saved. The order is
//!   now made once a rig, and the kernel runs on a grouped copy of the vertices
//!   (`fast::grouped`).
//! - Where one half of a block needs the iteration and the other not, the halves by the
//!   eight-vertex kernel: no faster (a block of sixteen iterates 1.4× as fast a vertex as
//!   one of eight, so one iterating half and one of pairs cost as much as sixteen).
//! - Each influence's logarithm alone, not two interleaved: one influence 1.3× faster,
//!   four 4 % slower; four interleaved: calls left in the loop, 4.5× slower.
//! - A block whose lanes all have one influence returning before the update it does not
//!   take: such blocks 2× faster, blocks of two 12 % slower, the characters unchanged.
//! - Leaving the moments out of the pass that shows convergence (taking the logarithms
//!   again with them where a lane goes on): four influences 3 % faster, one and two 5–8 %
//!   slower, the characters unchanged. Tried again once blocks of one and two influences
//!   no longer iterated (2026-12-05, `examples/dib_influences`, two rounds): eight lanes
//!   unchanged or a little faster (four influences 29.4–30.0 → 30.4–33.0), but sixteen
//!   three times slower (45.0–45.2 → 14.4–15.0; CesiumMan 68.4–78.7 → 33.0–33.5), with a
//!   third inlined copy of the update; why, not looked into.
//! - The block's blend and head carried into the next turn and transformed there, after
//!   the next block's loads and iteration (as the other kernels' loops take their next
//!   block ahead: `avx2`'s module docs): CesiumMan 74.0–75.2 against 72.9–76.3 M
//!   vertices/s (`chasles skin --rig … --bench --bench-threads 1`, two runs each in turn,
//!   2026-12-05): a block's time is its iteration, not the chain to its stores. By
//!   influence count (`examples/dib_influences`, one run each): one influence 212 → 245 M
//!   vertices/s, two and four unchanged (131.9 → 131.8, 44.7 → 44.6), CesiumMan 83.4 →
//!   82.9 (its vertices of one influence are 5 % of its time).
//! - Two blocks in a row whose every vertex has two influences, their ScLERPs interleaved
//!   as one `Wide` lane of two (the chain of a product, a logarithm, an exponential, a
//!   product and a normalization, side by side): the lane operations' closures stayed
//!   calls (`perf report`: `_mm512_castps_si512` and the logarithm's closure among the
//!   top symbols), two influences 133.5 → 36.4 M vertices/s and CesiumMan 83.2 → 48.0
//!   (`examples/dib_influences`, one run each, 2026-12-05).
//!
//! Where the time goes (2026-12-05, a 2-core Intel Xeon with AVX-512F, best of 20 runs
//! over 10⁵ synthetic vertices of four influences, one core, M vertices/s). The processor
//! retires 1.9–2.0 independent 512-bit multiply-adds a cycle (as many as 256-bit ones) at
//! 3.6–3.8 GHz (a scratch loop of twelve independent chains, clocked by one chain of
//! 4-cycle multiply-adds). In the compiled kernel (`objdump` of `dib_blocks`) a pair of
//! influences — the products `b̂* q̂ᵢ`, two logarithms, the update's and the moments' sums
//! — is a loop body of 379 instructions: 244 of them 512-bit arithmetic, 18 logic, 74
//! moves to and from the stack and 25 broadcasts of the series' coefficients; the step,
//! exponential, product and Newton step are 217 more (169 arithmetic). A block of sixteen
//! vertices of four influences runs that body four times (the update and the pass that
//! shows it converged), about 1500 arithmetic instructions with the start and the
//! transform: some 750 cycles at two a cycle, 75–80 M vertices/s, where it runs at 44–49 —
//! the ports about 60 % busy. Not the polynomials' chain: splitting each Horner sum in two
//! halves joined by `v⁵` (20 cycles of latency instead of 36, and no subnormal power:
//! `|v| ≥ 2⁻²⁴` where it is not 0) measured 44.2–47.6 against 44.9–47.6, three runs each
//! in turn. What an algorithm could save: leaving the convergence pass out altogether (a
//! bound, not a kernel: it breaks the stopping rule) gave 58.8–65.6 against 43.7–46.7,
//! still 4.7–5.9× DQS's time at 10⁵ vertices, where DQS skins 310–345 M vertices/s from
//! the cache; on the characters 1.1–1.25×. Grouping a mesh's vertices by influence count
//! (`fast::grouped`, [`crate::vertex_order`]) makes the characters faster and keeps the
//! rule.
//!
//! On the characters no lane should wait on a block-mate's second update: in f64 with the
//! second-order step, every vertex of three influences or more needs one update at most
//! over their first clips at five times (none and one: CesiumMan 1773 and 3912,
//! RiggedFigure 713 and 322, the Fox 15 and 180; `examples/dib_step`, 2026-12-05). An
//! iterating block there is DLB's start, one update and the pass that shows it converged,
//! so refilling converged lanes would gain nothing; that pass was what was left (the
//! evening of 2026-12-05: it now takes the update by one product, no logarithm,
//! `lane::dib::convergence`, which with ScLERP as a weighted sum, `lane::dib::sclerp`, took
//! four influences from 7.5–7.7× to 6.4–7.1× DQS's time and CesiumMan from 4.32× to
//! 3.88–3.90×). Leaving the old pass out altogether (the bound above, which breaks the
//! rule), measured with `examples/dib_influences` earlier that day: CesiumMan 74.3 → 84.8
//! M vertices/s, 4.31× → 3.57× DQS's time; four influences 47.6 → 58.2, 7.28× → 5.31×.
//! Stopping after an update whose successor a bound shows below the precision was
//! looked at in f64 and not built. The step's remainder's leading terms bound the next
//! update by about ‖x̂‖ (A⁴ + A³B + ‖x̂‖ A), with A and B the largest rotation and
//! translation parts of the logarithms (measured: at most 0.06 of it on the characters,
//! 0.39 on random blends of rotations up to 3 rad). Where that is under a quarter of the
//! precision it would spare the pass in 51 of CesiumMan's 340 iterating blocks of sixteen
//! over those five poses, 22 of RiggedFigure's 38 and 15 of the Fox's 25, and in none on
//! the synthetic mesh (there ‖x̂‖ ≈ 1e-3 and A² ≈ 0.2): a few per cent on CesiumMan, for a
//! rule resting on a bound not proved and two more maxima a logarithm on every rig (a
//! scratch computation; the blocks taken over the five poses' vertices end to end).
//!
//! CesiumMan's time by influence count (2026-12-05, `examples/dib_influences`, which also
//! skins its vertices cut to their first one, two and three influences; best of 30, one
//! core): cut to one, DIB takes 1.46× DQS's time; to two, 2.56×; whole, 4.17×. So in DQS's
//! time a vertex, its 458 vertices of one influence take 1.46 (DLB's start, its weights
//! and joints put in lanes), its 1678 of two 2.74 (ScLERP in closed form) and its 1137 of
//! three or four 7.37 (DLB's start, one update and the pass that shows it converged): 5 %,
//! 34 % and 61 % of its time. Tried the same day and not kept: DQS's transform with its
//! factor `2/‖b0‖²` taken as 2 (DIB's blends were unit to 1e-8 — its pairs' are now to
//! 4.8e-7 in `‖b0‖²`, not normalized after `lane::dib::sclerp` — so one division and a
//! norm fewer a block): CesiumMan 4.12–4.22× against 4.14–4.17× DQS's time, one influence
//! 1.44–1.46× against 1.47–1.53× (three runs each in turn), within the noise.

use super::avx2::dib::{joints, weights};
use super::avx2::{eight, load_head, store_rows, Store};
use super::dest::Dest;
use super::lane::dib::{convex, dib as blend};
use super::lane::transform;
use super::Vertex;
use std::arch::x86_64::*;

/// `lo` in lanes 0–7 and `hi` in lanes 8–15.
#[inline]
#[target_feature(enable = "avx512f")]
fn join(lo: __m256, hi: __m256) -> __m512 {
    let lo = _mm512_castpd256_pd512(_mm256_castps_pd(lo));
    _mm512_castpd_ps(_mm512_insertf64x4::<1>(lo, _mm256_castps_pd(hi)))
}

/// Lanes 0–7 and lanes 8–15 of `x`.
#[inline]
#[target_feature(enable = "avx512f")]
fn split(x: __m512) -> (__m256, __m256) {
    let hi = _mm512_extractf64x4_pd::<1>(_mm512_castps_pd(x));
    (_mm512_castps512_ps256(x), _mm256_castpd_ps(hi))
}

/// DIB for the first `v.len() / 16 * 16` vertices into `o` (layout `S`), as the AVX2
/// kernel's loop does for blocks of eight; returns how many were done.
///
/// # Safety
/// The processor must have AVX-512F (and so AVX2 and FMA); otherwise as for the AVX2
/// kernel (`avx2::dib::dib`): K is 4 or 8, every joint index in `v` is below `d.len()`,
/// `o.len() >= v.len()`, and with `stream` `o` is packed and 32-byte aligned.
#[inline(never)]
#[target_feature(enable = "avx512f,avx2,fma")]
pub(super) unsafe fn dib_blocks<const K: usize, S: Store>(
    v: &[Vertex<K>],
    d: &[[f32; 8]],
    o: &mut Dest<'_>,
    stream: bool,
) -> usize {
    chasles::frame::align_frame();
    unsafe {
        let db = d.as_ptr() as *const f32;
        let zero = _mm512_setzero_ps();
        let identity: [__m512; 8] = eight(|c| if c == 0 { _mm512_set1_ps(1.0) } else { zero });
        let blocks = v.len() / 16;
        for blk in 0..blocks {
            let i = blk * 16;
            let (h0, h1) = (load_head(v, i), load_head(v, i + 8));
            let head: [__m512; 6] = core::array::from_fn(|c| join(h0[c], h1[c]));
            // Weights and joints in lanes (vertex l in lane l), as the AVX2 kernel takes
            // them, for each eight.
            let (lo, hi) = (weights(v, i), weights(v, i + 8));
            let (w, used, slots) =
                convex::<__m512, K>(core::array::from_fn(|k| join(lo[k], hi[k])));
            // Unused joints replaced by the identity.
            let mut q = [identity; K];
            for k in 0..slots {
                let (lo, hi) = (joints(v, db, i, k), joints(v, db, i + 8, k));
                q[k] = eight(|c| _mm512_mask_blend_ps(used[k], identity[c], join(lo[c], hi[c])));
            }
            let b = blend(&q, &w, slots);
            let r = transform(b, [head[0], head[1], head[2]], [head[3], head[4], head[5]]);
            let halves: [(__m256, __m256); 6] = core::array::from_fn(|c| split(r[c]));
            store_rows::<S>(o, i, halves.map(|h| h.0), stream);
            store_rows::<S>(o, i + 8, halves.map(|h| h.1), stream);
        }
        blocks * 16
    }
}

#[cfg(test)]
mod tests {
    use crate::fast::avx2::dib::dib_with;
    use crate::fast::avx2::dib::tests::{joints, with_counts};
    use crate::fast::dest::Dest;
    use crate::fast::{Out, Vertex};
    use crate::synthetic;

    /// The DIB kernel on `v` by eight alone or with the sixteen-vertex kernel, into a
    /// packed output marked with NaNs: the outputs, and how many vertices were done.
    fn run<const K: usize>(v: &[Vertex<K>], d: &[[f32; 8]], sixteen: bool) -> (Vec<Out>, usize) {
        assert!(crate::fast::simd(K) && (!sixteen || std::is_x86_feature_detected!("avx512f")));
        let mut out = vec![[f32::NAN; 6]; v.len()];
        // SAFETY: AVX2, FMA and, with `sixteen`, AVX-512F checked above; the joint indices are below
        // d.len() (the rigs' joint counts are the poses'), `out` is as long as `v`.
        let done = unsafe { dib_with(v, d, Dest::packed(&mut out), false, sixteen) };
        (out, done)
    }

    /// Each vertex gets the eight-vertex kernel's bits from the sixteen-vertex one: 4 and 8
    /// influences, counts 1 to K mixed within blocks and in runs of blocks (a run of
    /// sixteen of at most two takes no update, a mixed one the iteration), at 60° poses
    /// and at every angle, meshes of 16k, 16k + 8 (a last block by eight) and odd lengths,
    /// every vertex a lane of every position (the mesh shifted by 0–15, so that blocks of
    /// sixteen whose halves need different passes come up), and a used NaN joint (NaN out
    /// for its vertices, the same as by eight). On a processor with AVX-512F and VL the other
    /// DIB kernel tests (`avx2::dib`) run mostly the sixteen-vertex kernel through `dib`;
    /// without them this test skips, those run the eight-vertex one, and `tests/avx512.rs`
    /// compares the AVX2 code with itself.
    #[test]
    fn sixteen_lanes_give_each_vertex_the_bits_of_eight() {
        if !(crate::fast::simd(4) && std::is_x86_feature_detected!("avx512f")) {
            eprintln!("no AVX-512F here: nothing to compare");
            return;
        }
        fn check<const K: usize>() {
            let base = synthetic::rig_with::<K>(1203, 54, 9);
            let mixed = with_counts(&base, |i| 1 + (i * 7919) % K);
            let runs = with_counts(&base, |i| {
                if (i / 48) % 2 == 0 {
                    1 + i % 2
                } else {
                    1 + (i * 31) % K
                }
            });
            let every = crate::fast::dual_quats8(&synthetic::joints(54, 3));
            let mut wild = joints(54);
            for rig in [&base, &mixed, &runs] {
                for d in [&every, &wild] {
                    let shifts = (0..16)
                        .map(|from| (from, 1203))
                        .chain([(0, 1200), (0, 1192)]);
                    for (from, to) in shifts {
                        let v = &rig.vertices()[from..to];
                        let (eight, done) = run(v, d, false);
                        let (sixteen, done16) = run(v, d, true);
                        assert_eq!((done, done16), (v.len() / 8 * 8, v.len() / 8 * 8));
                        for (k, (a, b)) in eight.iter().zip(&sixteen).enumerate() {
                            assert_eq!(
                                a.map(f32::to_bits),
                                b.map(f32::to_bits),
                                "K = {K}, vertices {from}..{to}, vertex {k}: {a:?} against {b:?}"
                            );
                        }
                    }
                }
            }
            // A used joint that is NaN: NaN out for the vertices it moves, as by eight.
            let j = usize::from(mixed.vertices()[5].j[0]);
            wild[j][0] = f32::NAN;
            let (eight, _) = run(mixed.vertices(), &wild, false);
            let (sixteen, _) = run(mixed.vertices(), &wild, true);
            assert!(sixteen[5].iter().all(|x| x.is_nan()));
            for (a, b) in eight.iter().zip(&sixteen) {
                assert_eq!(a.map(f32::to_bits), b.map(f32::to_bits));
            }
        }
        check::<4>();
        check::<8>();
    }

    /// Every lane operation on `__m512` is the `__m256` one's, bit for bit, on edge inputs:
    /// ties, ±0, ±∞, NaN, subnormals, the largest and smallest normals (comparisons, choices,
    /// sign flips, the mask operations, the arithmetic and Horner's rule).
    #[test]
    fn each_lane_operation_is_the_eight_lanes_one() {
        use crate::fast::lane::Lane;
        use std::arch::x86_64::*;
        if !(crate::fast::simd(4) && std::is_x86_feature_detected!("avx512f")) {
            eprintln!("no AVX-512F here: nothing to compare");
            return;
        }
        let edge = [
            0.0f32,
            -0.0,
            1.0,
            -1.0,
            1.5,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
            1e-45,
            -1e-40,
            f32::MAX,
            f32::MIN_POSITIVE,
            3.0,
            0.25,
            -7.5,
        ];
        // Every pair (and a third operand) over the sixteen edges: 16 rotations.
        for r in 0..16 {
            for t in 0..4 {
                let a: [f32; 16] = core::array::from_fn(|l| edge[l]);
                let b: [f32; 16] = core::array::from_fn(|l| edge[(l + r) % 16]);
                let c: [f32; 16] = core::array::from_fn(|l| edge[(l + r + t + 1) % 16]);
                // SAFETY: AVX2, FMA and AVX-512F checked above; every load and store is of
                // sixteen (or twice eight) floats of these arrays.
                unsafe { compare(a, b, c) };
            }
        }

        #[target_feature(enable = "avx512f,avx2,fma")]
        unsafe fn compare(a: [f32; 16], b: [f32; 16], c: [f32; 16]) {
            unsafe {
                let wide = |x: &[f32; 16]| _mm512_loadu_ps(x.as_ptr());
                let half = |x: &[f32; 16], h: usize| _mm256_loadu_ps(x.as_ptr().add(8 * h));
                let (a16, b16, c16) = (wide(&a), wide(&b), wide(&c));
                let bits16 = |x: __m512| {
                    let mut o = [0f32; 16];
                    _mm512_storeu_ps(o.as_mut_ptr(), x);
                    o.map(f32::to_bits)
                };
                let bits8 = |lo: __m256, hi: __m256| {
                    let mut o = [0f32; 16];
                    _mm256_storeu_ps(o.as_mut_ptr(), lo);
                    _mm256_storeu_ps(o.as_mut_ptr().add(8), hi);
                    o.map(f32::to_bits)
                };
                // A __m256 mask as sixteen bits (lane l's sign bit).
                let mask8 = |lo: __m256, hi: __m256| {
                    (_mm256_movemask_ps(lo) as u16) | ((_mm256_movemask_ps(hi) as u16) << 8)
                };
                let each = |f16: &dyn Fn(__m512, __m512, __m512) -> __m512,
                            f8: &dyn Fn(__m256, __m256, __m256) -> __m256,
                            what: &str| {
                    let lo = f8(half(&a, 0), half(&b, 0), half(&c, 0));
                    let hi = f8(half(&a, 1), half(&b, 1), half(&c, 1));
                    assert_eq!(
                        bits16(f16(a16, b16, c16)),
                        bits8(lo, hi),
                        "{what}: {a:?} {b:?} {c:?}"
                    );
                };
                each(&|x, y, _| x.add(y), &|x, y, _| x.add(y), "add");
                each(&|x, y, _| x.sub(y), &|x, y, _| x.sub(y), "sub");
                each(&|x, y, _| x.mul(y), &|x, y, _| x.mul(y), "mul");
                each(&|x, y, _| x.div(y), &|x, y, _| x.div(y), "div");
                each(&|x, _, _| x.sqrt(), &|x, _, _| x.sqrt(), "sqrt");
                each(&|x, y, z| x.madd(y, z), &|x, y, z| x.madd(y, z), "madd");
                each(&|x, y, z| x.msub(y, z), &|x, y, z| x.msub(y, z), "msub");
                each(&|x, y, z| x.nmadd(y, z), &|x, y, z| x.nmadd(y, z), "nmadd");
                each(
                    &|x, y, _| x.flip_by_sign_of(y),
                    &|x, y, _| x.flip_by_sign_of(y),
                    "flip",
                );
                let coef = [1.0f32, -0.5, 0.25, -0.125];
                each(
                    &|x, _, _| __m512::horner(&coef, x),
                    &|x, _, _| __m256::horner(&coef, x),
                    "horner",
                );
                each(
                    &|x, y, z| __m512::select(x.lt(y), y, z),
                    &|x, y, z| __m256::select(x.lt(y), y, z),
                    "select lt",
                );
                each(
                    &|x, y, z| __m512::select(x.le(y), y, z),
                    &|x, y, z| __m256::select(x.le(y), y, z),
                    "select le",
                );
                each(
                    &|x, y, z| x.neg_where(y.le(z)),
                    &|x, y, z| x.neg_where(y.le(z)),
                    "neg_where",
                );
                // The mask operations and `any`, as sixteen bits.
                let (a0, a1, b0, b1, c0, c1) = (
                    half(&a, 0),
                    half(&a, 1),
                    half(&b, 0),
                    half(&b, 1),
                    half(&c, 0),
                    half(&c, 1),
                );
                let (p16, q16) = (a16.lt(b16), b16.le(c16));
                let (p0, p1, q0, q1) = (a0.lt(b0), a1.lt(b1), b0.le(c0), b1.le(c1));
                assert_eq!(p16, mask8(p0, p1), "lt");
                assert_eq!(q16, mask8(q0, q1), "le");
                assert_eq!(
                    __m512::and(p16, q16),
                    mask8(__m256::and(p0, q0), __m256::and(p1, q1)),
                    "and"
                );
                assert_eq!(
                    __m512::and_not(p16, q16),
                    mask8(__m256::and_not(p0, q0), __m256::and_not(p1, q1)),
                    "and_not"
                );
                assert_eq!(__m512::any(p16), __m256::any(p0) || __m256::any(p1), "any");
            }
        }
    }
}
