//! Eight vertices at a time with AVX2 and FMA (x86-64, chosen at run time), the formulas
//! of the scalar kernels with fused multiply-adds, so the results agree with them to
//! rounding. DQS: each vertex's K (4 or 8) joint dual
//! quaternions are whole-register loads and its blend runs in one register, each joint's
//! copy with the antipodality sign (the joint or its negation) named by a per-pose table
//! (`Antipodes::copies`) or, for rigs too large for one, the signs from dot products;
//! eight blends, and eight vertices' positions and normals, are
//! transposed into lanes for the transformation, normalized by one division (no square
//! root). LBS likewise: each vertex's K joint matrices are whole-register loads blended in
//! two registers, eight blends transposed into lanes for the transformation (fused, it
//! measured 1.1× the unfused kernel that matched the scalar one bit for bit). Both prefetch
//! the input ahead and write their results back by transposes within register halves,
//! straight into the caller's layout — packed (six whole stores a block; non-temporal for
//! big meshes), an interleaved vertex buffer or split arrays (each vertex's own stores) —
//! each kernel's loop compiled once per layout (`store_rows`, `Store`). Log, QLB/SBS and
//! DIB are in the submodules; DIB ends with DQS's transformation (`transform`).
//!
//! What bounds DQS where the mesh is in the cache (a 2-core Xeon at 3.5 GHz, AVX-512's
//! register build, four influences, 2026-12-04): its loop is 338 instructions a block of
//! eight — about 130 scalar ones for the indices and the table's offsets, 87 vector
//! multiply-adds, 60 shuffles (the input's, the blends' and the output's transposes) and
//! the loads — and takes about 88 cycles a block in the second-level cache (2·10⁴
//! vertices), an IPC of 3.8. Three changes were measured and not kept. The first two each
//! took a tenth of one kind of instruction away and moved it by less than the noise, so no
//! one port or the front end bounds it alone (old and new binaries in turn, `chasles skin
//! --bench` at 10⁵ vertices, one thread, six to eight runs):
//! - each joint index read by its own 16-bit load, where the compiler loads the four in one
//!   word and shifts them apart (338 → 305 instructions): 2.5 % faster in the
//!   second-level cache, no change at 10⁵;
//! - the input's registers loaded as two 16-byte halves (vertex l below, l + 4 above, the
//!   upper by an insert from memory), so that 4×4 transposes within the halves take 12
//!   shuffles where the 8×8 transpose took 22: DQS 0–3 % faster, but LBS, which shares
//!   `load_head`, 4–5 % slower; with both changes for DQS alone, 271 → 281 in one run of
//!   eight and 285 → 283 M vertices/s in the next of six;
//! - two blocks a turn of the loop, their loads, blends, transforms and stores side by
//!   side (in case one block's chain of dependent steps — index, offset, copy, blend,
//!   transpose, norm, division, rotation — left the core idle): slower, 63 → 66 µs a pose
//!   at 2·10⁴ vertices and 316–334 → 322–352 µs at 10⁵ (a scratch loop of the job alone,
//!   three runs each); again on 2026-12-05 with the two blocks' transforms as one `Wide`
//!   lane (each operation on both in turn): 302–319 → 326–338 µs at 10⁵ (four runs each).
//!
//! **The next block ahead** (2026-12-05). Each turn of the DQS loop now blends the next
//! block — its loads, its chain of index, offset and copy, its transpose — before it
//! transforms this one, and carries those 14 registers of lanes (blend, position, normal)
//! into the next turn; LBS takes the next block up to its normals by the cofactors, not
//! yet of unit length, and carries 9. In one turn a block's steps hang on one another —
//! index, offset, copy, blend, transpose, norm, division, rotation — and the core had
//! waited on that chain: now the next block's loads are under way while this one's
//! division and rotation run. (Two blocks side by side in a turn, above, carried both
//! blocks' blends whole and spilled them.) The job alone, one core, best of 15 (a scratch
//! loop over `SkinningJob::run`), the builds in turn three times, ns a vertex: DQS
//! 3.06–3.14 → 2.78–2.82 at 2·10⁴ vertices (the second-level cache) and 3.49–3.67 →
//! 3.19–3.36 at 2·10⁵; LBS 3.75–3.84 → 3.40–3.42 and 4.22–4.48 → 3.87–4.13; with eight
//! influences (5·10⁴ vertices) DQS 5.18–5.32 → 4.62–4.77 and LBS 7.56–8.06 → 6.76–6.99.
//! With AVX2's sixteen registers alone (`set_avx512(false)`) DQS is unchanged (3.23–3.33
//! against 3.20–3.38) and LBS 4.10–4.21 → 3.67–3.95. In `chasles skin --bench`
//! (`--bench-vertices 100000,200000 --bench-threads 1 --bench-rounds 31`, with the same
//! change in Log, QLB, SBS and SBS's centre solve, three runs each in turn) DQS over the
//! careful glam DQS went 4.62–4.69× → 4.90–5.04× at 10⁵ and 4.42–4.62× → 4.78–4.90× at
//! 2·10⁵. Tried on top of it and not kept (the same loop, ns a vertex):
//! - DQS's transform split at its division (`‖b0‖²`, the terms its factor scales, p and n:
//!   13 registers carried, the turn's end only the division and six multiply-adds):
//!   2.78–2.82 → 3.06–3.19 at 2·10⁴;
//! - the copies table's indices (`64 j₀` and `j₀·joints + jₖ`) made in lanes from the
//!   head's words of joint indices, stored and read back a block ahead: 377 → 329
//!   instructions a block, and no faster than the blends ahead alone (2.95–3.05 against
//!   2.94–3.01 at 4096 and 2·10⁴ vertices);
//! - each joint index by its own 16-bit load, again: 2.66–2.82 against 2.73–2.83;
//! - the input asked for 128 or 256 vertices ahead rather than 64 (DQS at 2·10⁵ 3.32–3.56
//!   → 3.49–3.96 and 3.85–4.04), or 256 ahead into the second-level cache as well (3.54–3.59
//!   → 3.38–4.13; at 10⁶ 3.29–3.53 → 3.59–3.87);
//! - the packed output streamed from 2¹⁶ vertices rather than [`super::STREAM_VERTICES`]
//!   (at 2·10⁵ DQS 3.34–3.45 → 3.22–3.34, LBS unchanged): within the noise, and the output
//!   would leave the cache that its reader finds it in.
//!
//! (Past 500 lines for these docs: what was measured and tried, kept beside the code.)

use super::dest::Dest;
use super::lane::{rotate, transform, two_over_norm2};
use super::{Antipodes, Vertex};
use registers::by_target;
use std::arch::x86_64::*;
pub(in crate::fast) use store::by_layout;
pub(super) use store::{store_rows, Store};

pub mod dib;
pub mod log;
pub mod qlb;
pub(in crate::fast) mod registers;
mod store;
pub mod traffic;

/// How many vertices ahead the kernels prefetch their input (tried: 32, 64, 128; and, on
/// two threads at 10⁶ vertices, 160 and the L2 hint instead of L1: neither better). On 16
/// cores at 10⁷ vertices none ahead took DQS from 1276–1329 to 979–1046 M vertices/s and
/// 256 ahead gave 1333–1375, but 256 took one thread of LBS on a 2-core Xeon from 176 to
/// 146 (README, "Scaling with cores").
const PREFETCH: usize = 64;

/// The first 8 floats of vertices `i … i + 7` in lanes, by eight loads and a transpose:
/// x, y, z, nx, ny, nz and the first two words of joint indices (as float bits). A
/// `Vertex<K>` is `6 + K/2 + K` floats: p 0–2, n 3–5, joints as u32 words of u16 pairs,
/// weights. Also asks for the cache lines of the block [`PREFETCH`] vertices ahead: meshes
/// streamed from memory skin about 1.4 times faster for it (measured at 10⁶ vertices).
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(super) unsafe fn load_head<const K: usize>(v: &[Vertex<K>], i: usize) -> [__m256; 8] {
    unsafe {
        let stride = size_of::<Vertex<K>>() / 4;
        // A prefetch past the end of the mesh is harmless; the pointer is never read.
        let ahead = v.as_ptr().wrapping_add(i + PREFETCH) as *const u8;
        for line in 0..(8 * size_of::<Vertex<K>>()).div_ceil(64) {
            super::ask_cache(ahead.wrapping_add(line * 64));
        }
        let vb = v.as_ptr().add(i) as *const f32;
        transpose8(core::array::from_fn(|l| {
            _mm256_loadu_ps(vb.add(l * stride))
        }))
    }
}

/// The 8-float joint rows of each influence, `base + 8 j`, as whole-register loads (DQS's
/// dual quaternions, Log's twists). Four influences' as one array map, as measured; eight
/// one by one: as one map, the AVX-512 build (`registers`) made their indices 512-bit
/// vector code, and the kernels ran a quarter slower.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(super) unsafe fn joint_rows<const K: usize>(j: &[u16; K], base: *const f32) -> [__m256; K] {
    unsafe {
        let load = |j: u16| _mm256_loadu_ps(base.add(usize::from(j) * 8));
        if K == 4 {
            return j.map(load);
        }
        let mut rows = [_mm256_setzero_ps(); K];
        // By index: zipped with `j`, the indices became 512-bit vector code again.
        for (k, row) in rows.iter_mut().enumerate() {
            *row = load(j[k]);
        }
        rows
    }
}

/// One vertex's blended dual quaternion `Σ ±wₖ q̂ₖ` (8 floats in one register): its K
/// joints' dual quaternions are whole-register loads, not gathers; the antipodality signs
/// come from the dot products with the pivot (the heaviest influence), four at a time,
/// summed in the scalar kernel's order after a 4×4 transpose, so the signs are the same.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn blend_one<const K: usize>(vx: &Vertex<K>, db: *const f32) -> __m256 {
    unsafe {
        let q = joint_rows(&vx.j, db);
        let pivot = _mm256_castps256_ps128(q[0]);
        let mut b = _mm256_setzero_ps();
        for g in 0..K / 4 {
            let m = |k: usize| _mm_mul_ps(_mm256_castps256_ps128(q[4 * g + k]), pivot);
            let (mut m0, mut m1, mut m2, mut m3) = (m(0), m(1), m(2), m(3));
            _MM_TRANSPOSE4_PS(&mut m0, &mut m1, &mut m2, &mut m3);
            let dots = _mm_add_ps(_mm_add_ps(_mm_add_ps(m0, m1), m2), m3);
            let neg = _mm_and_ps(_mm_cmplt_ps(dots, _mm_setzero_ps()), _mm_set1_ps(-0.0));
            let w = _mm_xor_ps(_mm_loadu_ps(vx.w.as_ptr().add(4 * g)), neg);
            let w = _mm256_set_m128(w, w);
            b = _mm256_fmadd_ps(_mm256_permute_ps::<0x00>(w), q[4 * g], b);
            b = _mm256_fmadd_ps(_mm256_permute_ps::<0x55>(w), q[4 * g + 1], b);
            b = _mm256_fmadd_ps(_mm256_permute_ps::<0xAA>(w), q[4 * g + 2], b);
            b = _mm256_fmadd_ps(_mm256_permute_ps::<0xFF>(w), q[4 * g + 3], b);
        }
        b
    }
}

/// `[f(0), …, f(7)]`, written out: through `array::from_fn` the kernels' per-vertex blends
/// stayed calls, one per vertex.
#[inline(always)]
pub(super) fn eight<R>(f: impl Fn(usize) -> R) -> [R; 8] {
    [f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7)]
}

/// `Σ cₖ sᵏ` in f64: the tests' value of a series' f32 coefficients.
#[cfg(test)]
fn sum64(c: &[f32], s: f64) -> f64 {
    c.iter().rev().fold(0.0, |a, k| a * s + f64::from(*k))
}

/// Transposes 8 registers of 8 floats: row k of the result is element k of every input.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(super) fn transpose8(r: [__m256; 8]) -> [__m256; 8] {
    let [s0, s1, s2, s3] = transpose4_halves([r[0], r[1], r[2], r[3]]);
    let [s4, s5, s6, s7] = transpose4_halves([r[4], r[5], r[6], r[7]]);
    [
        _mm256_permute2f128_ps::<0x20>(s0, s4),
        _mm256_permute2f128_ps::<0x20>(s1, s5),
        _mm256_permute2f128_ps::<0x20>(s2, s6),
        _mm256_permute2f128_ps::<0x20>(s3, s7),
        _mm256_permute2f128_ps::<0x31>(s0, s4),
        _mm256_permute2f128_ps::<0x31>(s1, s5),
        _mm256_permute2f128_ps::<0x31>(s2, s6),
        _mm256_permute2f128_ps::<0x31>(s3, s7),
    ]
}

/// Transposes the 4×4 blocks of 4 registers in each 128-bit half: element k of result row c
/// is element c of input k, within the low half and within the high half.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(super) fn transpose4_halves(r: [__m256; 4]) -> [__m256; 4] {
    let t0 = _mm256_unpacklo_ps(r[0], r[1]);
    let t1 = _mm256_unpackhi_ps(r[0], r[1]);
    let t2 = _mm256_unpacklo_ps(r[2], r[3]);
    let t3 = _mm256_unpackhi_ps(r[2], r[3]);
    [
        _mm256_shuffle_ps::<0x44>(t0, t2),
        _mm256_shuffle_ps::<0xEE>(t0, t2),
        _mm256_shuffle_ps::<0x44>(t1, t3),
        _mm256_shuffle_ps::<0xEE>(t1, t3),
    ]
}

/// One vertex's blended dual quaternion `Σ ±wₖ q̂ₖ`, as [`blend_one`], from the pose's
/// signed copies (`Antipodes::copies`): the pivot's row of offsets names, for each joint,
/// its dual quaternion or its negation, so each influence is a broadcast weight (a load),
/// one load of the copy and one fused multiply-add: no sign to apply and no shuffle. The
/// first joint, the pivot, is never negated (`⟨q̂₀, q̂₀⟩ ≥ 0`).
///
/// # Safety
/// As for [`dqs`]: AVX2 and FMA; `copies` and `at` are those of a table made from the
/// joints of `joints` entries that `vx`'s indices are below.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn blend_copies<const K: usize>(
    vx: &Vertex<K>,
    copies: *const u8,
    at: *const u16,
    joints: usize,
) -> __m256 {
    unsafe {
        let j = vx.j.map(usize::from);
        let row = at.add(j[0] * joints);
        let copy = |offset: usize| _mm256_loadu_ps(copies.add(offset) as *const f32);
        let mut b = _mm256_mul_ps(_mm256_broadcast_ss(&vx.w[0]), copy(j[0] * 64));
        // By index, as in the other kernels' blends: zipped iterators can compile slower.
        #[allow(clippy::needless_range_loop)]
        for k in 1..K {
            let q = copy(usize::from(*row.add(j[k])));
            b = _mm256_fmadd_ps(_mm256_broadcast_ss(&vx.w[k]), q, b);
        }
        b
    }
}

/// DQS for the first `v.len() / 8 * 8` vertices; returns how many were done. Each
/// vertex's blend runs in one register ([`blend_copies`] with a table, else
/// [`blend_one`]); eight blends are transposed into lanes, and the normalization and
/// transformation run lane-parallel.
///
/// # Safety
/// The processor must have AVX2 and FMA, K must be 4 or 8, every joint index in `v` must be
/// below `d.len()`, `antipodes` must be empty or made from `d` (its copies are read, if it
/// has them), and `o.len() >= v.len()`; with `stream`, `o` must be packed and 32-byte
/// aligned (see [`store_rows`]).
#[target_feature(enable = "avx2,fma")]
pub unsafe fn dqs<const K: usize>(
    v: &[Vertex<K>],
    d: &[[f32; 8]],
    antipodes: &Antipodes,
    o: Dest<'_>,
    stream: bool,
) -> usize {
    unsafe {
        let db = d.as_ptr() as *const f32;
        // A table's offsets, else the dot products (no table).
        debug_assert!(
            antipodes.at.is_empty() || antipodes.floats() == 8,
            "DQS's copies"
        );
        if antipodes.at.is_empty() {
            by_target!(o, S => dqs_blocks::<K, S>(v, o, stream, |vx| blend_one(vx, db)))
        } else {
            let copies = antipodes.copies.as_ptr() as *const u8;
            let (at, joints) = (antipodes.at.as_ptr(), antipodes.joints);
            by_target!(o, S => dqs_blocks::<K, S>(v, o, stream, |vx| blend_copies(vx, copies, at, joints)))
        }
    }
}

/// A kernel's loop over `blocks` whole blocks of eight ([`super::take_ahead`] by blocks):
/// `take(i)` makes the block of vertices `i … i + 7` as far as it goes without its last
/// steps, and `end(i, t)` ends it and stores it, with `ahead` the next block taken before
/// this one ends (module docs, "The next block ahead"). Returns the vertices done,
/// `8 blocks`.
#[inline(always)]
pub(super) fn blocks_ahead<T: Copy>(
    blocks: usize,
    ahead: bool,
    take: impl Fn(usize) -> T,
    mut end: impl FnMut(usize, T),
) -> usize {
    super::take_ahead(
        blocks,
        ahead,
        #[inline(always)]
        |b| take(8 * b),
        #[inline(always)]
        |b, t| end(8 * b, t),
    );
    blocks * 8
}

/// The DQS kernel's body over whole blocks of eight for the layout `S`, with `blend` giving
/// each vertex's blended dual quaternion.
///
/// # Safety
/// Only from AVX2+FMA code (`by_target!`'s builds, each its own copy, or `by_layout!` in
/// an AVX2 function), with the preconditions of the kernel that calls it.
#[inline(always)]
unsafe fn dqs_blocks<const K: usize, S: Store>(
    v: &[Vertex<K>],
    mut o: Dest<'_>,
    stream: bool,
    blend: impl Fn(&Vertex<K>) -> __m256,
) -> usize {
    chasles::frame::align_frame();
    unsafe {
        // The next block blended before this one is transformed (its chain of loads —
        // index, offset, copy — under way while this one's transform runs).
        blocks_ahead(
            v.len() / 8,
            true,
            #[inline(always)]
            |i| {
                let [px, py, pz, nx, ny, nz, _, _] = load_head(v, i);
                let b = transpose8(eight(|l| blend(v.get_unchecked(i + l))));
                (b, [px, py, pz], [nx, ny, nz])
            },
            #[inline(always)]
            |i, (b, p, n)| store_rows::<S>(&mut o, i, transform(b, p, n), stream),
        )
    }
}

/// One vertex's blended matrix `Σ wₖ Mₖ` in two registers, rows 0–1 (8 floats) and row 2
/// (4): its K joints' rows are whole-register loads, not gathers, summed by fused
/// multiply-adds in the scalar kernel's order.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn lbs_blend<const K: usize>(vx: &Vertex<K>, mb: *const f32) -> (__m256, __m128) {
    unsafe {
        // Eight influences' indices are widened where they are used: as one array, the
        // AVX-512 build made them 512-bit vector code (slower by a quarter); four's stay
        // an array, as they were measured.
        let j4 = if K == 4 {
            vx.j.map(|j| usize::from(j) * 12)
        } else {
            [0; K]
        };
        let j = |k: usize| {
            if K == 4 {
                j4[k]
            } else {
                usize::from(vx.j[k]) * 12
            }
        };
        let w = |k: usize| _mm256_broadcast_ss(&vx.w[k]);
        let rows01 = |k: usize| _mm256_loadu_ps(mb.add(j(k)));
        let row2 = |k: usize| _mm_loadu_ps(mb.add(j(k) + 8));
        let w0 = w(0);
        let (mut a, mut b) = (
            _mm256_mul_ps(w0, rows01(0)),
            _mm_mul_ps(_mm256_castps256_ps128(w0), row2(0)),
        );
        for k in 1..K {
            let wk = w(k);
            a = _mm256_fmadd_ps(wk, rows01(k), a);
            b = _mm_fmadd_ps(_mm256_castps256_ps128(wk), row2(k), b);
        }
        (a, b)
    }
}

/// LBS for the first `v.len() / 8 * 8` vertices, the formulas of [`super::lbs_vertex`] with
/// fused multiply-adds (so it agrees with it to rounding) and the normal scaled by one
/// reciprocal of its length; returns how many were done. Where the blended matrix has rank
/// 1 or less (every cofactor zero in exact arithmetic: no normal to transform), the fused
/// cofactors keep the rounding of one product, so such a vertex may get a unit normal of
/// rounding noise where the scalar kernel keeps the bind normal; all-zero matrices keep it
/// in both. Each vertex's matrix is blended in
/// registers ([`lbs_blend`]); eight are transposed into twelve lane vectors (rows 0–1 by
/// [`transpose8`], row 2 by [`transpose4_halves`]) for the transformation.
///
/// # Safety
/// As for [`dqs`], with `m` the joints' 3×4 matrices.
#[target_feature(enable = "avx2,fma")]
pub unsafe fn lbs<const K: usize>(
    v: &[Vertex<K>],
    m: &[[f32; 12]],
    _: &(),
    o: Dest<'_>,
    stream: bool,
) -> usize {
    unsafe { by_target!(o, S => lbs_blocks::<K, S>(v, m, o, stream)) }
}

/// [`lbs`]'s loop for the layout `S`.
///
/// # Safety
/// Only from AVX2+FMA code (`by_target!`'s builds, each its own copy, or `by_layout!` in
/// an AVX2 function), with the preconditions of the kernel that calls it.
#[inline(always)]
unsafe fn lbs_blocks<const K: usize, S: Store>(
    v: &[Vertex<K>],
    m: &[[f32; 12]],
    mut o: Dest<'_>,
    stream: bool,
) -> usize {
    chasles::frame::align_frame();
    unsafe {
        let mb = m.as_ptr() as *const f32;
        let zero = _mm256_setzero_ps();
        let one = _mm256_set1_ps(1.0);
        let mul = |p, q| _mm256_mul_ps(p, q);
        let fma = |p, q, r| _mm256_fmadd_ps(p, q, r);
        // The next block taken to its normals by the cofactors before this one's are made
        // of unit length.
        blocks_ahead(
            v.len() / 8,
            true,
            #[inline(always)]
            |i| {
                let [x, y, z, nx, ny, nz, _, _] = load_head(v, i);
                let b = eight(|l| lbs_blend(v.get_unchecked(i + l), mb));
                let [a0, a1, a2, a3, a4, a5, a6, a7] = transpose8(eight(|l| b[l].0));
                // Row 2 of vertices l and l + 4 side by side, then 4×4 transposes per half.
                let row2 = |l: usize| _mm256_set_m128(b[l + 4].1, b[l].1);
                let h = transpose4_halves([row2(0), row2(1), row2(2), row2(3)]);
                let a = [a0, a1, a2, a3, a4, a5, a6, a7, h[0], h[1], h[2], h[3]];
                let fms = |p, q, r| _mm256_fmsub_ps(p, q, r);
                // Row r times (x, y, z, 1).
                let row = |r: usize| {
                    fma(
                        a[4 * r + 2],
                        z,
                        fma(a[4 * r + 1], y, fma(a[4 * r], x, a[4 * r + 3])),
                    )
                };
                let (px, py, pz) = (row(0), row(1), row(2));
                // Cofactors c = a·b − c·d, the second product rounded, the first fused.
                let cof = |p, q, r, s| fms(p, q, mul(r, s));
                let c00 = cof(a[5], a[10], a[6], a[9]);
                let c01 = cof(a[6], a[8], a[4], a[10]);
                let c02 = cof(a[4], a[9], a[5], a[8]);
                let c10 = cof(a[2], a[9], a[1], a[10]);
                let c11 = cof(a[0], a[10], a[2], a[8]);
                let c12 = cof(a[1], a[8], a[0], a[9]);
                let c20 = cof(a[1], a[6], a[2], a[5]);
                let c21 = cof(a[2], a[4], a[0], a[6]);
                let c22 = cof(a[0], a[5], a[1], a[4]);
                let mx = fma(c02, nz, fma(c01, ny, mul(c00, nx)));
                let my = fma(c12, nz, fma(c11, ny, mul(c10, nx)));
                let mz = fma(c22, nz, fma(c21, ny, mul(c20, nx)));
                [px, py, pz, mx, my, mz, nx, ny, nz]
            },
            #[inline(always)]
            |i, [px, py, pz, mx, my, mz, nx, ny, nz]| {
                let l2 = fma(mz, mz, fma(my, my, mul(mx, mx)));
                let ok = _mm256_cmp_ps::<_CMP_GT_OQ>(l2, zero);
                let inv = _mm256_div_ps(one, _mm256_sqrt_ps(l2));
                let mx = _mm256_blendv_ps(nx, mul(mx, inv), ok);
                let my = _mm256_blendv_ps(ny, mul(my, inv), ok);
                let mz = _mm256_blendv_ps(nz, mul(mz, inv), ok);
                store_rows::<S>(&mut o, i, [px, py, pz, mx, my, mz], stream);
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use crate::fast::{dest::Dest, lbs_vertex, matrices12, simd, Out};
    use crate::synthetic;

    /// The SIMD LBS kernel against the scalar one, to rounding (fused multiply-adds): random
    /// rigid joints, and all-zero matrices (every normal's cofactor vanishes: the normal is
    /// kept, exactly).
    #[test]
    fn the_simd_lbs_is_the_scalar_one_to_rounding() {
        if !simd(4) {
            eprintln!("no AVX2+FMA here: nothing to check");
            return;
        }
        let rig = synthetic::rig(1003, 54, 5);
        let rigid = matrices12(&synthetic::joints(54, 5));
        for (m, tol) in [(rigid, 2e-6), (vec![[0.0; 12]; 54], 0.0)] {
            let mut out: Vec<Out> = vec![[f32::NAN; 6]; 1003];
            // SAFETY: the processor has AVX2 and FMA (`simd`), the synthetic rig's joint
            // indices are below 54 and `out` is as long as the vertices.
            let done =
                unsafe { super::lbs(rig.vertices(), &m, &(), Dest::packed(&mut out), false) };
            assert_eq!(done, 1000);
            for (v, o) in rig.vertices().iter().zip(&out[..done]) {
                let want = lbs_vertex(v, &m);
                let d = o
                    .iter()
                    .zip(&want)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0f32, f32::max);
                assert!(d <= tol, "{o:?} vs {want:?}");
            }
        }
    }
}
