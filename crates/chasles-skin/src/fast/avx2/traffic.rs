//! The SIMD kernels' loads and stores with nothing between (`fast::traffic`): each block's
//! heads by [`load_head`] (its prefetch included; the vertices' lines are read whole), its
//! positions and normals stored into the caller's layout by [`store_rows`], as every
//! kernel's block does.

use super::super::dest::Dest;
use super::super::Vertex;
use super::{by_target, load_head, store_rows, Store};

/// The first `v.len() / 8 * 8` vertices' positions and normals into `o`; returns how many
/// were done (the joints and the table are units: nothing to read).
///
/// # Safety
/// The processor must have AVX2 and FMA, K must be 4 or 8, and `o.len() >= v.len()`; with
/// `stream`, `o` must be packed and 32-byte aligned.
#[target_feature(enable = "avx2,fma")]
pub unsafe fn traffic<const K: usize>(
    v: &[Vertex<K>],
    _: &[()],
    _: &(),
    o: Dest<'_>,
    stream: bool,
) -> usize {
    unsafe { by_target!(o, S => blocks::<K, S>(v, o, stream)) }
}

/// [`traffic`]'s loop for the layout `S`.
///
/// # Safety
/// Only from AVX2+FMA code (`by_target!`'s builds, each its own copy, or `by_layout!` in
/// an AVX2 function), with the preconditions of the kernel that calls it.
#[inline(always)]
unsafe fn blocks<const K: usize, S: Store>(
    v: &[Vertex<K>],
    mut o: Dest<'_>,
    stream: bool,
) -> usize {
    unsafe {
        let blocks = v.len() / 8;
        for blk in 0..blocks {
            let i = blk * 8;
            let [px, py, pz, nx, ny, nz, _, _] = load_head(v, i);
            store_rows::<S>(&mut o, i, [px, py, pz, nx, ny, nz], stream);
        }
        blocks * 8
    }
}
