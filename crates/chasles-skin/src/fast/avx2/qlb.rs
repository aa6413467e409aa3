//! QLB and SBS (`super::super::qlb`) eight vertices at a time with AVX2 and FMA: each
//! vertex's K joint rows are whole-register loads (three registers a row, two for SBS) and
//! blended in registers — the rotation quaternions with the antipodality signs, from the
//! pose's signed copies of the rows (`Antipodes::rows`: the copy named by the pivot's row
//! of offsets, or each row's plain copy where no pair flips) or, where there is no table,
//! the scalar kernel's dot products; the matrices and origins with the plain weights — then
//! eight blends are transposed into lanes and moved about their centres lane-parallel, with
//! fused multiply-adds (the scalar kernel's formulas, so the two agree to rounding).
//!
//! Tried and not kept (2026-12-04, the job alone at 2.5·10⁴ and 10⁵ synthetic vertices,
//! one core, old and new binaries in turn four times): the centres (four floats a vertex)
//! by 4×4 transposes within register halves, as LBS's row 2, instead of the third 8×8
//! transpose — 12 fewer shuffles a block (24 → 12) and the same bits, but QLB 146–163 →
//! 146–168 and SBS 145–175 → 141–168 M vertices/s: the shuffles do not bound these loops.
//!
//! Each turn of the loop (four influences) takes the next block as far as it goes without
//! its rotation — its loads, blends, centres and transposes, then `2/‖q‖²`, the blended
//! matrix applied to the centre and p − c — and carries those 14 registers of lanes into
//! the next turn, where the rotations of p − c and of n end it: what DQS's loop does
//! (`super`'s module docs), with a lighter carry. Carrying the block's 19 lanes of blends
//! and centres with its position and normal (25 registers) instead, the compiler spilled
//! them: QLB 5.52–5.62 → 5.25–5.47 ns a vertex at 2·10⁴, SBS 5.99–6.04 → 5.98–6.42 at
//! 2·10⁵; and through a stack buffer of two blocks written and read as such, slower still
//! (QLB 5.23–5.42 → 5.84–6.18). With the 14 (the job alone, one core, best of 15, the builds
//! in turn five times, 2026-12-05, ns a vertex): QLB 5.23–5.38 → 4.90–5.01 at 2·10⁴
//! vertices, SBS 5.01–5.27 → 4.61–4.76 there and 5.75–5.90 → 5.19–5.37 at 2·10⁵; with AVX2's
//! sixteen registers alone SBS 5.49–5.61 → 5.35–5.37. Eight influences take each block in
//! its own turn: ahead, their blends kept more registers alive and QLB ran 12.96–13.34 →
//! 14.05–14.44 ns a vertex (5·10⁴ vertices).

use super::super::dest::Dest;
use super::super::{real_dot, Antipodes, Vertex};
use super::{
    blocks_ahead, by_target, eight, load_head, rotate, store_rows, transpose8, two_over_norm2,
    Store, PREFETCH,
};
use std::arch::x86_64::*;

/// Floats per joint row (`super::super::qlb::Row`).
const ROW: usize = 24;

/// The antipodality sign of each influence (−0.0 to flip, +0.0 to keep, in all lanes),
/// from the scalar kernel's dot products: the kernel's way where the pose has no table
/// ([`blend_copies`] reads the table's signed copies instead). `inline(always)` for
/// [`blend`]'s reason: as an `#[inline]` AVX2 function it stayed a call, one per vertex,
/// with eight influences.
///
/// # Safety
/// Only from AVX2+FMA code (`blocks`), with [`qlb`]'s preconditions.
#[inline(always)]
unsafe fn signs<const K: usize>(vx: &Vertex<K>, rows: &[[f32; ROW]]) -> [__m256; K] {
    unsafe {
        if K == 4 {
            return signs4(vx, rows);
        }
        // Eight influences: by loops, each index widened where it is used (as in
        // `blend_copies`); array maps of closures stayed calls here.
        let j = |k: usize| usize::from(vx.j[k]);
        let mut s = [_mm256_setzero_ps(); K];
        let pivot = rows.get_unchecked(j(0));
        for (k, s) in s.iter_mut().enumerate() {
            let neg = real_dot(rows.get_unchecked(j(k)), pivot) < 0.0;
            *s = _mm256_set1_ps(if neg { -0.0 } else { 0.0 });
        }
        s
    }
}

/// [`signs`] for four influences as it was written before the AVX-512 build: an `#[inline]`
/// AVX2 function with array maps, inlined into both builds (by loops, the AVX2 build of QLB
/// ran 150 → 140 M vertices/s at 2.5·10⁴ vertices).
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn signs4<const K: usize>(vx: &Vertex<K>, rows: &[[f32; ROW]]) -> [__m256; K] {
    unsafe {
        let j = vx.j.map(usize::from);
        let pivot = rows.get_unchecked(j[0]);
        j.map(|j| {
            let neg = real_dot(rows.get_unchecked(j), pivot) < 0.0;
            _mm256_set1_ps(if neg { -0.0 } else { 0.0 })
        })
    }
}

/// One vertex's blended row: `[Σ ±wₖ qₖ, Σ wₖ (row 0 of [R|t])ₖ]`, `[rows 1 and 2]`, and
/// unless `SBS` (whose centres come from the clusters), `[Σ wₖ cₖ, 0…]`.
///
/// `inline(always)` without `target_feature` (the two cannot go together): as a plain
/// `#[inline]` AVX2 function it stayed a call, one per vertex; it is only called from the
/// AVX2 kernel body, into which it and its intrinsics are inlined.
#[inline(always)]
unsafe fn blend<const K: usize, const SBS: bool>(
    vx: &Vertex<K>,
    rows: &[[f32; ROW]],
) -> [__m256; 3] {
    unsafe {
        let rb = rows.as_ptr() as *const f32;
        let low = _mm256_setr_ps(-0.0, -0.0, -0.0, -0.0, 0.0, 0.0, 0.0, 0.0);
        let s = signs(vx, rows);
        let mut out = [_mm256_setzero_ps(); 3];
        // By index: zipped iterators over the three arrays compiled to slower code.
        #[allow(clippy::needless_range_loop)]
        for k in 0..K {
            let r = rb.add(usize::from(vx.j[k]) * ROW);
            let w = _mm256_broadcast_ss(&vx.w[k]);
            // The sign touches the quaternion's four lanes only.
            let sw = _mm256_xor_ps(w, _mm256_and_ps(s[k], low));
            out[0] = _mm256_fmadd_ps(sw, _mm256_loadu_ps(r), out[0]);
            out[1] = _mm256_fmadd_ps(w, _mm256_loadu_ps(r.add(8)), out[1]);
            if !SBS {
                out[2] = _mm256_fmadd_ps(w, _mm256_loadu_ps(r.add(16)), out[2]);
            }
        }
        out
    }
}

/// [`blend`] from the pose's signed copies of the rows (`Antipodes::rows`): the pivot's row
/// of offsets names, for each joint, its row as it is or with its rotation negated, so each
/// influence is a broadcast weight, the offset and the row's registers (two with `SBS`)
/// with a fused multiply-add each, and no sign to apply: the bits of [`blend`]'s signed
/// weights (`w·(−q) = (−w)·q` exactly). The pivot is never negated; where no pair flips
/// (`PLAIN`) no offset is read. The copies start a cache line and are 32-byte aligned, so
/// no load spans two lines, where the palette's rows may lie anywhere.
///
/// # Safety
/// As for [`blend`], with `copies` and `at` those of a table made from the rows
/// (`joints` of them), and `PLAIN` only where none of its pairs flips.
#[inline(always)]
unsafe fn blend_copies<const K: usize, const SBS: bool, const PLAIN: bool>(
    vx: &Vertex<K>,
    copies: *const u8,
    at: *const u16,
    joints: usize,
) -> [__m256; 3] {
    unsafe {
        // A joint's row and its copy: 2 · 24 floats.
        const STRIDE: usize = 2 * ROW * 4;
        let j = |k: usize| usize::from(vx.j[k]);
        let row = at.add(j(0) * joints);
        let mut out = [_mm256_setzero_ps(); 3];
        // By index, as in `blend`.
        #[allow(clippy::needless_range_loop)]
        for k in 0..K {
            let offset = if PLAIN || k == 0 {
                j(k) * STRIDE
            } else {
                usize::from(*row.add(j(k)))
            };
            let r = copies.add(offset) as *const f32;
            let w = _mm256_broadcast_ss(&vx.w[k]);
            out[0] = _mm256_fmadd_ps(w, _mm256_loadu_ps(r), out[0]);
            out[1] = _mm256_fmadd_ps(w, _mm256_loadu_ps(r.add(8)), out[1]);
            if !SBS {
                out[2] = _mm256_fmadd_ps(w, _mm256_loadu_ps(r.add(16)), out[2]);
            }
        }
        out
    }
}

/// QLB for the first `v.len() / 8 * 8` vertices, each about the blend of its joints'
/// origins; returns how many were done.
///
/// # Safety
/// The processor must have AVX2 and FMA, K must be 4 or 8, every joint index in `v` must be below
/// `rows.len()`, `table` must be empty or made from `rows`, and `o.len() >= v.len()`; with
/// `stream`, `o` must be packed and 32-byte aligned.
#[target_feature(enable = "avx2,fma")]
pub unsafe fn qlb<const K: usize>(
    v: &[Vertex<K>],
    rows: &[[f32; ROW]],
    table: &Antipodes,
    o: Dest<'_>,
    stream: bool,
) -> usize {
    unsafe { about::<K, false>(v, rows, table, &[], &[], o, stream) }
}

/// QLB (`SBS` false: each vertex about the blend of its joints' origins, `cluster` and
/// `centres` unread) or SBS (each vertex about its cluster's centre, `centres[cluster[i]]`,
/// padded to 4 floats) for the first `v.len() / 8 * 8` vertices; returns how many were
/// done. The blend is the one the table allows: the dot products' signs ([`blend`]) where
/// there is no table, else its copies ([`blend_copies`]), with or without offsets as a pair
/// of the pose flips.
///
/// # Safety
/// As for [`qlb`], and with `SBS` every `cluster[i]` (for `i < v.len()`) must be below
/// `centres.len()`.
#[allow(clippy::too_many_arguments)]
#[inline]
#[target_feature(enable = "avx2,fma")]
pub unsafe fn about<const K: usize, const SBS: bool>(
    v: &[Vertex<K>],
    rows: &[[f32; ROW]],
    table: &Antipodes,
    cluster: &[u32],
    centres: &[[f32; 4]],
    o: Dest<'_>,
    stream: bool,
) -> usize {
    debug_assert!(
        table.at.is_empty() || table.floats() == ROW,
        "QLB's rows' copies"
    );
    unsafe {
        if table.at.is_empty() {
            by_target!(o, S => blocks::<K, SBS, S>(v, cluster, centres, o, stream, #[inline(always)] |vx| blend::<K, SBS>(vx, rows)))
        } else {
            let (copies, at) = (table.copies.as_ptr() as *const u8, table.at.as_ptr());
            if table.flips {
                by_target!(o, S => blocks::<K, SBS, S>(v, cluster, centres, o, stream, #[inline(always)] |vx| blend_copies::<K, SBS, false>(vx, copies, at, table.joints)))
            } else {
                by_target!(o, S => blocks::<K, SBS, S>(v, cluster, centres, o, stream, #[inline(always)] |vx| blend_copies::<K, SBS, true>(vx, copies, at, table.joints)))
            }
        }
    }
}

/// The body over whole blocks of eight: each vertex's blended row, and its centre — its
/// cluster's with `SBS` (`centres[cluster[i]]`), else the blend of its joints' origins.
/// Generic over `SBS` (a closure choosing the centre stayed a call) and over the output's
/// layout `S`; the blend, [`blend`] or [`blend_copies`], comes as an `#[inline(always)]`
/// closure, as DQS's does (`avx2::dqs_blocks`).
///
/// # Safety
/// Only from AVX2+FMA code (`by_target!`'s builds, each its own copy, or `by_layout!` in
/// an AVX2 function), with the preconditions of the kernel that calls it.
#[inline(always)]
unsafe fn blocks<const K: usize, const SBS: bool, S: Store>(
    v: &[Vertex<K>],
    cluster: &[u32],
    centres: &[[f32; 4]],
    mut o: Dest<'_>,
    stream: bool,
    blend: impl Fn(&Vertex<K>) -> [__m256; 3],
) -> usize {
    chasles::frame::align_frame();
    unsafe {
        // Four influences take the next block as far as it goes without its rotation
        // before this one is rotated; eight take each block in its own turn (module docs).
        blocks_ahead(
            v.len() / 8,
            K == 4,
            #[inline(always)]
            |i| {
                if SBS {
                    // The centres of the block PREFETCH vertices ahead: a rig of many
                    // clusters reads its centre table at random (on the synthetic rig,
                    // 3·10⁵ centres of 16 bytes), and the loads would otherwise wait on the
                    // cache misses.
                    for l in i + PREFETCH..(i + PREFETCH + 8).min(v.len()) {
                        // A prefetch of any address is harmless; the pointer is never read.
                        let c = centres
                            .as_ptr()
                            .wrapping_add(*cluster.get_unchecked(l) as usize);
                        super::super::ask_cache(c);
                    }
                }
                let [px, py, pz, nx, ny, nz, _, _] = load_head(v, i);
                let r = eight(
                    #[inline(always)]
                    |l| {
                        let [a, b, c] = blend(v.get_unchecked(i + l));
                        if SBS {
                            let c = centres.get_unchecked(*cluster.get_unchecked(i + l) as usize);
                            [a, b, _mm256_castps128_ps256(_mm_loadu_ps(c.as_ptr()))]
                        } else {
                            [a, b, c]
                        }
                    },
                );
                let lanes = |k: usize| transpose8(eight(|l| r[l][k]));
                let [w0, x0, y0, z0, m00, m01, m02, m03] = lanes(0);
                let [m10, m11, m12, m13, m20, m21, m22, m23] = lanes(1);
                let [cx, cy, cz, _, _, _, _, _] = lanes(2);
                let sub = |a, b| _mm256_sub_ps(a, b);
                let fma = |a, b, c| _mm256_fmadd_ps(a, b, c);
                let s = two_over_norm2(&[w0, x0, y0, z0]);
                // y = Σ wₖ (Rₖ c + tₖ), the blended matrix applied to c.
                let y = [
                    fma(m02, cz, fma(m01, cy, fma(m00, cx, m03))),
                    fma(m12, cz, fma(m11, cy, fma(m10, cx, m13))),
                    fma(m22, cz, fma(m21, cy, fma(m20, cx, m23))),
                ];
                // The rotation's quaternion and 2 / ‖q‖², y, p − c and n.
                (
                    [w0, x0, y0, z0, s],
                    y,
                    [sub(px, cx), sub(py, cy), sub(pz, cz)],
                    [nx, ny, nz],
                )
            },
            #[inline(always)]
            |i, ([w0, x0, y0, z0, s], y, pc, n)| {
                let add = |a, b| _mm256_add_ps(a, b);
                // p − c and n rotated by r / ‖r‖.
                let rotate = |x| rotate(w0, [x0, y0, z0], s, x);
                let (d, n) = (rotate(pc), rotate(n));
                let p = [add(y[0], d[0]), add(y[1], d[1]), add(y[2], d[2])];
                store_rows::<S>(&mut o, i, [p[0], p[1], p[2], n[0], n[1], n[2]], stream);
            },
        )
    }
}
