//! The fast paths' memory traffic without their arithmetic (Kavan et al. 2006, §6: what
//! skinning costs): every vertex read whole and its position and normal written as they are,
//! by the SIMD kernels' own loads, prefetches and stores (`avx2::traffic`: the same chunks,
//! overlapping end blocks, layouts and non-temporal stores for big meshes). No method's
//! fast path moves less, so a kernel's speed over this one is the share it reaches of what
//! its loads and stores alone run at. A copy of the same bytes (`peers::copy_bound`) reads
//! and writes equal halves, where a kernel reads 48 bytes a vertex (72 with eight
//! influences) and writes 24; on one thread out of the cache this bound is the tighter one.
//!
//! On the 2-core AMD EPYC (Zen 4) of the README's figures (three runs of `chasles skin
//! --bench --bench-vertices 100000,1000000,4000000 --bench-threads 1,2`, 2026-12-03), out of
//! the cache this traffic ran at 1.07–1.44 times the copy's vertex rate on one thread and at
//! 0.89–1.18 on two (medians of the rounds' ratios). One-thread DQS ran there at 0.56–0.69
//! of it; in a scratch loop of best-of-20 runs (8 at 4·10⁶), each size in turn, at
//! 0.86–0.94 of its own in-cache speed while the shared machine's memory was quick (this
//! traffic at 365–616 M vertices/s) and at 0.6–0.8 while it was slow (300–355): one core of
//! DQS is bound mostly by its arithmetic, and loses more when the memory is slow, its
//! arithmetic hiding little of the waiting. Prefetching 32 vertices ahead instead of 64, or
//! into L2 instead of L1, and transparent huge pages made no difference beyond the noise.

use super::{run, FastRig, Kernel, Out, Output, Vertex};
use crate::error::Result;

/// The traffic kernel: no joints (a unit per joint, so that the job's size checks hold),
/// no table.
struct TrafficKernel;
impl<const K: usize> Kernel<K> for TrafficKernel {
    type Joint = ();
    type Table = ();
    fn table(_: &[()], _: usize) {}
    #[cfg(target_arch = "x86_64")]
    const AVX2: Option<super::SimdKernel<K, (), ()>> = Some(super::avx2::traffic::traffic::<K>);
    #[inline(always)]
    fn vertex(v: &Vertex<K>, _: &[()]) -> Out {
        [v.p[0], v.p[1], v.p[2], v.n[0], v.n[1], v.n[2]]
    }
}

/// Writes every vertex's bind position and normal into `out` (any [`Output`] layout), on
/// all threads when `parallel`, with the fast paths' own loads and stores and nothing
/// between: the bound of every method's fast path's loads and stores ([`super::lbs`],
/// [`super::dqs`], …) on this rig and this machine. An error where `out` does not hold one
/// output per vertex.
pub fn traffic<'a, const K: usize>(
    rig: &FastRig<K>,
    out: impl Into<Output<'a>>,
    parallel: bool,
) -> Result<()> {
    let units = vec![(); rig.joints()];
    run::<K, TrafficKernel>(rig, &units, out.into(), parallel)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::dest::Dest;
    use crate::fast::{simd, simd_start, STREAM_VERTICES};
    use crate::synthetic;

    /// Each vertex's bind position and normal, as the traffic kernel must write them.
    fn bind<const K: usize>(rig: &FastRig<K>) -> Vec<Out> {
        rig.vertices()
            .iter()
            .map(|v| [v.p[0], v.p[1], v.p[2], v.n[0], v.n[1], v.n[2]])
            .collect()
    }

    /// Every vertex gets its own bind position and normal, bit for bit, and nothing else is
    /// written: in a packed output (streamed for a mesh of `STREAM_VERTICES` or more), an
    /// interleaved one of stride 7 (its seventh float kept) and split arrays; on one thread
    /// and on all; 4 and 8 influences; meshes of 5 vertices (the scalar kernel), 1003 (SIMD
    /// blocks and an overlapping last one) and past the streaming size.
    #[test]
    fn every_vertex_gets_its_bind_position_and_normal_in_every_layout() {
        fn check<const K: usize>(n: usize) {
            let rig = synthetic::rig_with::<K>(n, 54, 3);
            let want = bind(&rig);
            for parallel in [false, true] {
                let mut packed = vec![[f32::NAN; 6]; n];
                // The big mesh's packed output is streamed (a heap buffer reaches 32-byte
                // alignment within its first four vertices).
                if n >= STREAM_VERTICES && simd(K) {
                    let (_, streams) = simd_start(&Dest::packed(&mut packed), true);
                    assert!(streams, "K = {K}: not streamed");
                }
                traffic(&rig, &mut packed[..], parallel).unwrap();
                assert_eq!(packed, want, "K = {K}, n = {n}, packed");
                let mut inter = vec![-7.0f32; n * 7];
                traffic(
                    &rig,
                    Output::Interleaved {
                        data: &mut inter,
                        stride: 7,
                    },
                    parallel,
                )
                .unwrap();
                for (k, (v, w)) in inter.chunks_exact(7).zip(&want).enumerate() {
                    assert_eq!((&v[..6], v[6]), (&w[..], -7.0), "K = {K}, vertex {k}");
                }
                let (mut p, mut nr) = (vec![[f32::NAN; 3]; n], vec![[f32::NAN; 3]; n]);
                traffic(
                    &rig,
                    Output::Split {
                        positions: &mut p,
                        normals: &mut nr,
                    },
                    parallel,
                )
                .unwrap();
                for (k, w) in want.iter().enumerate() {
                    assert_eq!((&p[k][..], &nr[k][..]), (&w[..3], &w[3..]), "split {k}");
                }
            }
        }
        for n in [5, 1003, STREAM_VERTICES + 13] {
            check::<4>(n);
            check::<8>(n);
        }
    }

    /// An output of the wrong size is a typed error naming the sizes; nothing is written.
    #[test]
    fn an_output_of_the_wrong_size_is_an_error() {
        let rig = synthetic::rig(100, 54, 3);
        let mut out = vec![[1f32; 6]; 99];
        let e = traffic(&rig, &mut out[..], false).unwrap_err();
        assert!(e.to_string().contains("output vertices"), "{e}");
        assert!(out.iter().flatten().all(|x| *x == 1.0));
    }
}
