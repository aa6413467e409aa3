//! Where the SIMD kernels' results go: eight vertices' six lane vectors stored into the
//! caller's layout ([`Dest`]) after transposes within register halves — into an
//! interleaved vertex buffer or split arrays by each vertex's own stores, into the packed
//! layout by six whole-register stores (streamed past the cache for big meshes); each
//! kernel's loop compiled once per layout ([`Store`], [`by_layout!`]). Kavan et al. 2006,
//! §6: the skinned vertices go to the buffer that draws them, with no copy between.

use super::super::dest::{Dest, Layout};
use super::transpose4_halves;
use std::arch::x86_64::*;

/// An output layout fixed when a kernel's loop is compiled ([`Layout`]): each SIMD kernel's
/// loop is made once per layout ([`by_layout!`]), so the packed loop carries none of the
/// other layouts' stores. One loop with the layout chosen per block held the packed output
/// of LBS and DQS 8 % slower (10⁵ vertices, one core, best of 200 runs: LBS 230 → 209, DQS
/// 247 → 227 M vertices/s), though the branch always went the same way.
pub(in crate::fast) trait Store {
    /// The layout.
    const LAYOUT: Layout;
}
/// [`Layout::Packed`] for [`Store`].
pub(super) struct Packed;
/// [`Layout::Interleaved`] for [`Store`].
pub(super) struct Interleaved;
/// [`Layout::Split`] for [`Store`].
pub(super) struct Split;
/// [`Layout::Scattered`] for [`Store`].
pub(super) struct Scattered;
impl Store for Packed {
    const LAYOUT: Layout = Layout::Packed;
}
impl Store for Interleaved {
    const LAYOUT: Layout = Layout::Interleaved;
}
impl Store for Split {
    const LAYOUT: Layout = Layout::Split;
}
impl Store for Scattered {
    const LAYOUT: Layout = Layout::Scattered;
}

/// `$body` with the type `$s` naming the [`Store`] of `$o`'s layout: a kernel's loop
/// monomorphized for each layout, the one for `$o` run. A scattered `$o` is DIB's alone
/// (`fast::grouped`): only the form `by_layout!(scattered $o, …)`, DIB's, compiles a loop
/// for it; in the other kernels that arm cannot be reached.
macro_rules! by_layout {
    (scattered $o:expr, $s:ident => $body:expr) => {
        if $o.layout() == $crate::fast::dest::Layout::Scattered {
            type $s = $crate::fast::avx2::store::Scattered;
            $body
        } else {
            $crate::fast::avx2::store::by_layout!($o, $s => $body)
        }
    };
    ($o:expr, $s:ident => $body:expr) => {
        match $o.layout() {
            $crate::fast::dest::Layout::Scattered => {
                unreachable!("a scattered output goes to DIB's kernels alone")
            }
            $crate::fast::dest::Layout::Packed => {
                type $s = $crate::fast::avx2::store::Packed;
                $body
            }
            $crate::fast::dest::Layout::Interleaved => {
                type $s = $crate::fast::avx2::store::Interleaved;
                $body
            }
            $crate::fast::dest::Layout::Split => {
                type $s = $crate::fast::avx2::store::Split;
                $body
            }
        }
    };
}
pub(in crate::fast) use by_layout;

/// Writes eight vertices' results (six lane vectors) to vertices `i … i + 7` of `o`, in its
/// layout `S`. Packed: as the block's 48 floats in six registers ([`pack6`]), by six whole
/// stores, or with `stream` (where vertex i is 32-byte aligned) by non-temporal ones
/// ([`stream_rows`]). Interleaved and split: by [`store_apart`], each vertex's six floats
/// exactly, so an interleaved buffer's other attributes are not touched. Nothing past the
/// block is written.
///
/// The packed output once went by a full 8×8 transpose (24 shuffles a block), seven whole
/// stores each overwriting the next vertex's first two floats, and one 6-lane masked store
/// (on AMD's Zen a masked store to memory is microcoded: eight a block held LBS at 10⁶
/// vertices to 93 M vertices/s, one a block let it reach 165), and its streamed form by that
/// transpose and 16 more shuffles. Best of runs on the same AMD EPYC (Zen 4; 10⁵ vertices,
/// one core, `examples/best_of`, binaries in turn), [`store_apart`]'s sixteen narrow stores
/// took LBS from 230 to 246–250 and DQS from 248 to 267–269 M vertices/s; [`pack6`]'s six
/// whole stores then LBS to 255–257 (DQS, Log and QLB within 2 %). Streamed, [`pack6`]
/// in place of the full transpose and its packing took DQS at 10⁶ vertices on one core from
/// 151–161 to 203–212 (best of 40 runs, three rounds; on two threads within the noise).
///
/// # Safety
/// `i + 8 <= o.len()`, `o` of layout `S`; `stream` only for a packed `o` whose vertex `i` is
/// 32-byte aligned.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(in crate::fast) unsafe fn store_rows<S: Store>(
    o: &mut Dest<'_>,
    i: usize,
    r: [__m256; 6],
    stream: bool,
) {
    unsafe {
        debug_assert!(i + 8 <= o.len() && o.layout() == S::LAYOUT);
        if S::LAYOUT == Layout::Scattered {
            store_scattered(o, i, r);
            return;
        }
        let (ob, nb) = o.at(i);
        if S::LAYOUT != Layout::Packed {
            store_apart(ob, nb, o.stride(), S::LAYOUT == Layout::Split, r);
        } else if stream {
            stream_rows(ob, r);
        } else {
            for (k, x) in pack6(r).into_iter().enumerate() {
                _mm256_storeu_ps(ob.add(8 * k), x);
            }
        }
    }
}

/// Eight vertices' results (six lane vectors: x, y, z, nx, ny, nz) stored where vertex l's
/// position is `p + l·stride` and its normal `n + l·stride`, writing those 6 floats and no
/// other. Each half of a register holds four vertices after 4×4 transposes
/// ([`transpose4_halves`]), so no lane crosses a half before its store. Interleaved (`n =
/// p + 3`, `stride > 6`): x y z nx by one 16-byte store, ny nz by one 8-byte store.
/// Split (`stride = 3`): x y z and nx ny nz each by a 16-byte store whose fourth float lands
/// on the next vertex's first, which that vertex's own store (the next in program order)
/// then writes; the last vertex by an 8-byte and a 4-byte store, so nothing past the block
/// is touched.
///
/// # Safety
/// The 6 floats of each of the eight vertices must be writable.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn store_apart(p: *mut f32, n: *mut f32, stride: usize, split: bool, r: [__m256; 6]) {
    unsafe {
        let (a, yz) = halves(r);
        if split {
            let b = transpose4_halves([r[3], r[4], r[5], r[0]]);
            for (t, base) in [(&a, p), (&b, n)] {
                for l in 0..7 {
                    _mm_storeu_ps(base.add(3 * l), half(t, l));
                }
                three(base.add(21), half(t, 7));
            }
            return;
        }
        let yz = pairs(yz);
        for l in 0..8 {
            _mm_storeu_ps(p.add(l * stride), half(&a, l));
        }
        for (k, t) in yz.iter().enumerate() {
            two(p.add(2 * k * stride + 4), *t);
            two_high(p.add((2 * k + 1) * stride + 4), *t);
        }
    }
}

/// Vertex `l`'s four floats from registers whose halves hold vertices 0–3 (low) and 4–7
/// (high), as [`halves`] leaves them.
#[inline]
#[target_feature(enable = "avx2,fma")]
fn half(t: &[__m256; 4], l: usize) -> __m128 {
    if l < 4 {
        _mm256_castps256_ps128(t[l])
    } else {
        _mm256_extractf128_ps::<1>(t[l - 4])
    }
}

/// The ny nz of vertices (0, 1), (2, 3), (4, 5), (6, 7) from [`halves`]' `yz`, a pair to
/// a register (the first vertex's in floats 0–1, the second's in 2–3).
#[inline]
#[target_feature(enable = "avx2,fma")]
fn pairs(yz: [__m256; 2]) -> [__m128; 4] {
    [
        _mm256_castps256_ps128(yz[0]),
        _mm256_castps256_ps128(yz[1]),
        _mm256_extractf128_ps::<1>(yz[0]),
        _mm256_extractf128_ps::<1>(yz[1]),
    ]
}

/// Floats 0–1 of `x` to `at`, which may be only 4-byte aligned: an unaligned 8-byte write
/// (`vmovlps`), not `_mm_store_sd`, which writes a typed f64 and so asks for 8-byte
/// alignment.
///
/// # Safety
/// The two floats at `at` must be writable.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn two(at: *mut f32, x: __m128) {
    unsafe { (at as *mut f64).write_unaligned(_mm_cvtsd_f64(_mm_castps_pd(x))) }
}

/// Floats 2–3 of `x` to `at`, as [`two`] writes 0–1 (`vmovhps`, not `_mm_storeh_pd`).
///
/// # Safety
/// The two floats at `at` must be writable.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn two_high(at: *mut f32, x: __m128) {
    let x = _mm_castps_pd(x);
    unsafe { (at as *mut f64).write_unaligned(_mm_cvtsd_f64(_mm_unpackhi_pd(x, x))) }
}

/// Floats 0–2 of `x` to `at`: an 8-byte and a 4-byte write, nothing past them.
///
/// # Safety
/// The three floats at `at` must be writable.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn three(at: *mut f32, x: __m128) {
    unsafe {
        two(at, x);
        _mm_store_ss(at.add(2), _mm_movehl_ps(x, x));
    }
}

/// Eight vertices' results (six lane vectors: x, y, z, nx, ny, nz) written to the slots
/// that the scattered `o` names for vertices `i … i + 7` (`Dest::slot`), each vertex's six
/// floats and no other, in any order: into a packed or interleaved buffer (the normal after
/// the position) x y z nx by one 16-byte store and ny nz by one 8-byte store, as
/// [`store_apart`] does; into split arrays each three floats by an 8-byte and a 4-byte
/// store (a 16-byte one would write a float of a slot that may be written already).
///
/// # Safety
/// `i + 8 <= o.len()`, `o` scattered.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn store_scattered(o: &Dest<'_>, i: usize, r: [__m256; 6]) {
    unsafe {
        let (a, yz) = halves(r);
        // Split arrays have a stride of 3; packed and interleaved ones 6 or more.
        debug_assert!(o.stride() == 3 || o.stride() >= 6);
        if o.stride() == 3 {
            let b = transpose4_halves([r[3], r[4], r[5], r[0]]);
            for l in 0..8 {
                let (p, n) = o.slot(i + l);
                three(p, half(&a, l));
                three(n, half(&b, l));
            }
            return;
        }
        let yz = pairs(yz);
        for l in 0..8 {
            let (p, _) = o.slot(i + l);
            _mm_storeu_ps(p, half(&a, l));
            if l % 2 == 0 {
                two(p.add(4), yz[l / 2]);
            } else {
                two_high(p.add(4), yz[l / 2]);
            }
        }
    }
}

/// Eight vertices' results (six lane vectors: x, y, z, nx, ny, nz) with four vertices in
/// each register half (10 shuffles): `a[c]` holds vertex c's x y z nx in its low half and
/// vertex c + 4's in its high half; `yz[0]` the ny nz of vertices 0, 1 (low) and 4, 5
/// (high), `yz[1]` those of 2, 3 and 6, 7. The start of [`store_apart`] and [`pack6`].
#[inline]
#[target_feature(enable = "avx2,fma")]
fn halves(r: [__m256; 6]) -> ([__m256; 4], [__m256; 2]) {
    let a = transpose4_halves([r[0], r[1], r[2], r[3]]);
    let yz = [
        _mm256_unpacklo_ps(r[4], r[5]),
        _mm256_unpackhi_ps(r[4], r[5]),
    ];
    (a, yz)
}

/// Eight vertices' results (six lane vectors: x, y, z, nx, ny, nz) as the 48 floats of
/// the packed layout, in six registers in memory order: [`halves`] (10 shuffles), four
/// in-lane shuffles, and per register one join of two halves (6) — 20 shuffles a block (a
/// full 8×8 transpose and then packing its rows took 40).
#[inline]
#[target_feature(enable = "avx2,fma")]
fn pack6(r: [__m256; 6]) -> [__m256; 6] {
    let (a, [b01, b23]) = halves(r);
    // Per half, vertices 0–3 (low) or 4–7 (high), each four floats of the layout:
    // x0 y0 z0 nx0 | ny0 nz0 x1 y1 | z1 nx1 ny1 nz1 | x2 y2 z2 nx2 | ny2 nz2 x3 y3 | z3 nx3 ny3 nz3
    let m = _mm256_shuffle_ps::<0x44>(b01, a[1]);
    let n = _mm256_shuffle_ps::<0xEE>(a[1], b01);
    let p = _mm256_shuffle_ps::<0x44>(b23, a[3]);
    let q = _mm256_shuffle_ps::<0xEE>(a[3], b23);
    [
        _mm256_permute2f128_ps::<0x20>(a[0], m),
        _mm256_permute2f128_ps::<0x20>(n, a[2]),
        _mm256_permute2f128_ps::<0x20>(p, q),
        _mm256_permute2f128_ps::<0x31>(a[0], m),
        _mm256_permute2f128_ps::<0x31>(n, a[2]),
        _mm256_permute2f128_ps::<0x31>(p, q),
    ]
}

/// Eight vertices' results written to the 32-byte aligned `ob` in the packed layout
/// ([`pack6`]) by non-temporal stores: the written lines go to memory without first being
/// read into the cache (a store that misses reads its line first), so a mesh streamed from
/// memory moves 72 bytes a vertex, not 96. The caller fences (`_mm_sfence`) before others
/// read the output.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn stream_rows(ob: *mut f32, r: [__m256; 6]) {
    unsafe {
        for (k, x) in pack6(r).into_iter().enumerate() {
            _mm256_stream_ps(ob.add(8 * k), x);
        }
    }
}
