//! DIB's SIMD kernels over a rig's vertices grouped by influence count (Kavan et al. 2006,
//! §4, the box "DIB"; §6, its cost in skinning), without changing the rig's order. A block
//! of eight or sixteen vertices pays for DIB's iteration — the update and the pass of
//! logarithms that shows it converged — wherever one of its vertices has three influences
//! or more, and for a ScLERP wherever one has two (`lane::dib`), and on a character such
//! vertices are strewn along the mesh. On a rig where grouping takes a tenth or more off
//! what the blocks cost ([`Groups::of`], by `cost`: blocks of sixteen that iterate, the
//! Fox 26 → 5 of 108, RiggedFigure 22 → 13 of 24, CesiumMan 145 → 77 of 205; none on the
//! synthetic meshes, whose vertices all have four; one and two influences in turn gain
//! 1.2×: `examples/dib_influences`, 127.8 → 154.3 M vertices/s), the first DIB job lays
//! out a copy of the vertices in `crate::vertex_order`'s order (sorted by count within
//! windows of 256) and every DIB job, that one included, runs the kernels on it, a chunk a
//! call, each vertex's result stored straight to its place in the caller's output (a
//! scattered `Dest`: the vertex's slot read from the order, its six floats by its own
//! stores, in any of the three layouts). The kernels give every vertex the same
//! bits whatever its block-mates (their tests shift every block and compare), so the output
//! is the ungrouped kernels', bit for bit (tested on every layout).
//!
//! What it costs: the copy (a `Vertex<K>` and a `u32` a vertex, only on rigs that gain)
//! and each vertex's own two stores (four into split arrays) where the packed
//! output takes six whole-register stores for eight vertices; the output is never streamed
//! (the job streams only meshes of 2¹⁸ vertices or more into a packed output). Measured
//! (2026-12-05, a 2-core Intel Xeon with AVX-512F, one core; `cargo run --release -p
//! chasles-skin --example dib_grouping`: best of 20 runs over the characters' clips, the
//! two builds in turn, three rounds of two, M vertices/s), DIB in the rig's order (grouping
//! off, [`super::FastRig::without_dib_grouping`]) → grouped here → on a rig reordered once
//! (`crate::vertex_order`, nothing to put back): the Fox 76–78 → 97.3–100.0 → 99.5–102.8,
//! RiggedFigure 63.6–65.4 → 72.5–74.4 → 73.6–75.7, CesiumMan 66.0–67.8 → 76.3–77.5 →
//! 78.0–79.9 — 2–3 % below the reordered rig by the ranges' middles. Once a vertex of two
//! influences took ScLERP in closed form (`lane::dib`; the same command, two runs): the Fox
//! 86.1–86.5 → 131.3–134.7 → 136.3–139.9, RiggedFigure 49.5–50.8 → 72.3–74.4 → 74.4–76.4,
//! CesiumMan 56.5–57.2 → 79.7–80.3 → 82.4–82.9 (in the rig's order RiggedFigure and
//! CesiumMan lost 13–20 %, their blocks mixing vertices of two with vertices of more). The
//! first grouped path ran the kernels a window of 256 at a time into a stage on the stack
//! and put each vertex back from there:
//! the Fox 88.6–92.8, RiggedFigure 68.3–70.2, CesiumMan 72.9–74.8 in the same runs, 7–10 %
//! below the reordered rig, all of it in the put-back's loop (leaving the put-back out, a
//! wrong output, ran as fast as the reordered rig; the loop was 17 instructions a vertex, and 13
//! once its bounds checks were hoisted still ran behind these direct stores). Earlier
//! still, a `Dest::put` that read each vertex back through a copy on the stack ran slower
//! than the ungrouped kernel. On synthetic meshes whose influence counts are mixed in
//! every block (2 and 4 in turn, or 1–4), the stage's path against ungrouped (best of 5
//! runs, two rounds, M vertices/s, a scratch loop): at 10⁵ vertices 53.3–56.7 against
//! 44.5–46.4 on one thread and 97.7–103.8 against 83.4–86.0 on two; at 10⁶, where the
//! ungrouped output is streamed, 46.3–47.6 against 44.1–44.8 and 96.5–99.7 against
//! 84.1–89.6.

use super::job::for_chunks_unshifted;
use super::{Kernel, Output, Vertex, CHUNK};
use crate::vertex_order::{by_kind, WINDOW};

// Every chunk of the unshifted grid starts at a window's start.
const _: () = assert!(CHUNK.is_multiple_of(WINDOW));

/// A rig's vertices in `crate::vertex_order`'s order: `vertices[i]` is the rig's vertex
/// `order[i]`.
#[derive(Debug, Clone)]
pub(super) struct Groups<const K: usize> {
    vertices: Vec<Vertex<K>>,
    order: Vec<u32>,
}

/// What DIB's kernels spend on `vertices`, block of sixteen by block, in units of about
/// 0.9 ns a vertex: 5 for every block (DLB's start, the transformation, the loads and
/// stores), 4 more where a vertex has two influences (the block's ScLERP), 18 more where
/// one has three or more (the iteration) — from blocks of one, two and four influences
/// alone (`examples/dib_influences`, sixteen lanes, 2026-12-05: 1.49×, 2.68× and 6.95×
/// DQS's 3 ns a vertex). Blocks of three influences now take three logarithms a pass where
/// blocks of four take four (`lane::dib`, `update`), which this model does not see: it
/// charges both alike, so a rig whose only mixing is of threes with fours is not grouped
/// (none of the built-in characters; their grouping is chosen for their ones and twos).
fn cost<const K: usize>(vertices: &[Vertex<K>]) -> usize {
    vertices
        .chunks(16)
        .map(|b| {
            let (two, more) = b
                .iter()
                .map(count)
                .fold((false, false), |(t, m), c| (t || c == 2, m || c >= 3));
            5 + 4 * usize::from(two) + 18 * usize::from(more)
        })
        .sum()
}

/// A vertex's influences of positive weight.
fn count<const K: usize>(v: &Vertex<K>) -> usize {
    v.w.iter().filter(|&&w| w > 0.0).count()
}

impl<const K: usize> Groups<K> {
    /// The grouped copy of `vertices`, where grouping takes a tenth or more off DIB's cost
    /// ([`cost`]; module docs); `None` where it would gain less.
    pub(super) fn of(vertices: &[Vertex<K>]) -> Option<Self> {
        if vertices.len() > u32::MAX as usize {
            return None;
        }
        let order = by_kind(vertices.len(), |v| count(&vertices[v]));
        let grouped: Vec<Vertex<K>> = order.iter().map(|&o| vertices[o as usize]).collect();
        // At least a tenth less (the copy's scattered stores cost 2–3 %).
        let before = cost(vertices);
        if before == 0 || 10 * cost(&grouped) > 9 * before {
            return None;
        }
        // What `run`'s writes rest on: the order moves a vertex only within its window.
        let within = |(i, &o): (usize, &u32)| o as usize / WINDOW == i / WINDOW;
        if !order.iter().enumerate().all(within) {
            return None;
        }
        Some(Groups {
            vertices: grouped,
            order,
        })
    }
}

/// DIB's SIMD kernel `F` on the grouped vertices `g` into `out` (the caller checked the
/// sizes, the joints and that the SIMD kernels run): on the grid that starts at 0, each
/// chunk by one kernel call that writes each vertex straight to the place the rig has it
/// (a scattered `Dest`). `F` must be DIB's kernel (the one `Kernel::GROUPED`): the other
/// kernels' stores have no scattered form and would panic (`by_layout!`).
pub(super) fn run<const K: usize, F: Kernel<K>>(
    g: &Groups<K>,
    joints: &[F::Joint],
    table: &F::Table,
    out: Output<'_>,
    parallel: bool,
) {
    // What lets `F::chunk` take the SIMD kernel (its safety rests on it).
    let simd = super::simd(K);
    debug_assert!(simd, "the grouping is for the SIMD kernels");
    for_chunks_unshifted(out, &g.vertices, parallel, |first, o, v| {
        // SAFETY: the chunk starts at a multiple of CHUNK, so of WINDOW, and ends at one or
        // at the mesh's end; `order` moves a vertex only within its window (checked when
        // `g` was made, `Groups::of`), so it maps this chunk onto itself: every
        // `order[i] − first` is below `o.len()`. `o` is the job's chunk, not scattered.
        let o = unsafe { o.scattered(&g.order[first..first + v.len()], first) };
        F::chunk(o, v, joints, table, simd, false);
    });
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;
    use crate::fast::avx2::dib::tests::{joints, with_counts};
    use crate::fast::dest::Dest;
    use crate::fast::{dib, simd, FastRig, Output, Palette, SkinningJob};
    use crate::synthetic;

    /// Blocks of sixteen that hold a vertex of three influences or more.
    fn iterating<const K: usize>(vertices: &[Vertex<K>]) -> usize {
        vertices
            .chunks(16)
            .filter(|b| b.iter().any(|v| count(v) >= 3))
            .count()
    }

    /// `rig` with DIB's grouping made (`true`) or refused (`false`) before any job.
    fn grouping<const K: usize>(rig: &FastRig<K>, on: bool) -> FastRig<K> {
        let r = FastRig::from_vertices(rig.vertices().to_vec(), rig.centres().to_vec()).unwrap();
        r.dib_groups
            .set(if on { Groups::of(r.vertices()) } else { None })
            .unwrap();
        r
    }

    /// DIB by the job into each layout (packed, interleaved of 8 floats, split), on one
    /// thread and on all: each as the packed output it gives (the interleaved buffer's
    /// other floats are checked untouched).
    fn outputs<const K: usize>(rig: &FastRig<K>, d: &[[f32; 8]]) -> Vec<Vec<[u32; 6]>> {
        let n = rig.vertices().len();
        let palette = Palette::from_joints(
            rig,
            crate::fast::Joints::Dib(d.iter().map(|q| bytemuck::cast(*q)).collect()),
        )
        .unwrap();
        let job = |output: Output<'_>, parallel: bool| {
            SkinningJob {
                rig,
                palette: &palette,
                output,
                parallel,
            }
            .run()
            .unwrap()
        };
        let bits = |o: &[[f32; 6]]| o.iter().map(|o| o.map(f32::to_bits)).collect::<Vec<_>>();
        let mut all = Vec::new();
        for parallel in [false, true] {
            let mut packed = vec![[f32::NAN; 6]; n];
            job(Output::Packed(&mut packed), parallel);
            all.push(bits(&packed));
            let mut data = vec![7.5f32; 8 * n];
            job(
                Output::Interleaved {
                    data: &mut data,
                    stride: 8,
                },
                parallel,
            );
            assert!(data.chunks(8).all(|v| v[6] == 7.5 && v[7] == 7.5));
            let inter: Vec<[f32; 6]> = data
                .chunks(8)
                .map(|v| std::array::from_fn(|c| v[c]))
                .collect();
            all.push(bits(&inter));
            let (mut p, mut nr) = (vec![[f32::NAN; 3]; n], vec![[f32::NAN; 3]; n]);
            job(
                Output::Split {
                    positions: &mut p,
                    normals: &mut nr,
                },
                parallel,
            );
            let split: Vec<[f32; 6]> = p
                .iter()
                .zip(&nr)
                .map(|(p, n)| [p[0], p[1], p[2], n[0], n[1], n[2]])
                .collect();
            all.push(bits(&split));
        }
        all
    }

    /// Grouped and ungrouped, DIB gives every vertex the same bits in every layout, on one
    /// thread and on all: mixed influence counts (1–K in every block, 2 and 4 in turn, runs
    /// of one kind) at meshes of every awkward size (under a block, a window and a window
    /// and its last few, a chunk and its last few, two chunks), at every angle.
    #[test]
    fn grouped_dib_is_the_ungrouped_bit_for_bit() {
        if !simd(4) {
            eprintln!("no AVX2+FMA here: the grouping is not used");
            return;
        }
        fn check<const K: usize>(n: usize, count: fn(usize) -> usize, gains: bool) {
            let rig = with_counts(&synthetic::rig_with::<K>(n, 54, 11), count);
            let (on, off) = (grouping(&rig, true), grouping(&rig, false));
            if n >= 64 {
                assert_eq!(on.dib_groups().is_some(), gains, "n = {n}");
            }
            let every = joints(54);
            let mid = crate::fast::dual_quats8(&synthetic::joints(54, 3));
            for d in [&every, &mid] {
                let (a, b) = (outputs(&on, d), outputs(&off, d));
                for (layout, (a, b)) in a.iter().zip(&b).enumerate() {
                    for v in 0..n {
                        assert_eq!(a[v], b[v], "K = {K}, n = {n}, output {layout}, vertex {v}");
                    }
                }
                // And the free function.
                let dq: Vec<_> = d
                    .iter()
                    .map(|q| chasles::DualQuat::from_array(*q))
                    .collect();
                let (mut x, mut y) = (vec![[0f32; 6]; n], vec![[0f32; 6]; n]);
                dib(&on, &dq, &mut x, false).unwrap();
                dib(&off, &dq, &mut y, false).unwrap();
                assert_eq!(x, y, "K = {K}, n = {n}");
            }
        }
        let mixed: fn(usize) -> usize = |i| 1 + (i * 7919) % 4;
        let turns: fn(usize) -> usize = |i| if i % 2 == 0 { 2 } else { 4 };
        let runs: fn(usize) -> usize = |i| [4, 2, 1][(i / 64) % 3];
        // (2·4096 + 5: a last window merged with the vertices after it in a chunk that does
        // not start at 0.)
        for n in [
            5,
            8,
            61,
            255,
            256,
            263,
            264,
            300,
            4096 + 7,
            2 * 4096 + 5,
            2 * 4096 + 300,
        ] {
            // Runs of 64 of one kind (whole blocks) are grouped already: the grouping is not
            // made.
            for (count, gains) in [(mixed, true), (turns, true), (runs, false)] {
                check::<4>(n, count, gains);
            }
        }
        check::<8>(4096 + 77, mixed, true);
    }

    /// The AVX2 kernel's blocks of eight and the AVX-512 kernel's of sixteen (where the
    /// processor has it) write each vertex of a scattered output to its slot, in every
    /// layout, exactly the floats they store packed, and touch nothing else.
    #[test]
    fn both_kernels_write_a_scattered_output_slot_by_slot() {
        use crate::fast::avx2::dib::dib_with;
        if !simd(4) {
            eprintln!("no AVX2+FMA here: no SIMD kernel to scatter");
            return;
        }
        let n = 300;
        let rig = with_counts(&synthetic::rig(n, 54, 5), |i| 1 + (i * 7919) % 4);
        let (v, d) = (rig.vertices(), joints(54));
        // A permutation of the slots 1000..1000 + n: the kernels' vertex i goes to slot
        // order[i] − 1000.
        let order: Vec<u32> = (0..n as u32)
            .map(|i| 1000 + (i * 7 + 3) % n as u32)
            .collect();
        let sentinel = f32::from_bits(0x7fc0_1234);
        let bits = |x: f32| x.to_bits();
        let mut kernels = vec![false];
        if crate::fast::uses_avx512(4) {
            kernels.push(true);
        }
        for sixteen in kernels {
            let mut want = vec![[sentinel; 6]; n];
            // SAFETY: AVX2 and FMA are present (`simd`), AVX-512F where `sixteen`
            // (`uses_avx512`); the joint indices are below 54; `want` holds n vertices.
            let done = unsafe { dib_with(v, &d, Dest::packed(&mut want), false, sixteen) };
            assert_eq!(done, n / 8 * 8);
            // Each buffer eight vertices longer than its view: a write past the view shows.
            let m = n + 8;
            let (mut packed, mut inter) = (vec![[sentinel; 6]; m], vec![sentinel; 8 * m]);
            let (mut p, mut nr) = (vec![[sentinel; 3]; m], vec![[sentinel; 3]; m]);
            // SAFETY: as above; every order[i] − 1000 is below n, each view's length.
            unsafe {
                for o in [
                    Dest::packed(&mut packed[..n]),
                    Dest::interleaved(&mut inter[..8 * n], 8),
                    Dest::split(&mut p[..n], &mut nr[..n]),
                ] {
                    assert_eq!(
                        dib_with(v, &d, o.scattered(&order, 1000), false, sixteen),
                        done
                    );
                }
            }
            for (i, &slot) in order.iter().enumerate() {
                let s = slot as usize - 1000;
                let want = if i < done { want[i] } else { [sentinel; 6] };
                let split: [f32; 6] =
                    std::array::from_fn(|c| if c < 3 { p[s][c] } else { nr[s][c - 3] });
                for got in [packed[s], std::array::from_fn(|c| inter[8 * s + c]), split] {
                    assert_eq!(
                        got.map(bits),
                        want.map(bits),
                        "sixteen {sixteen}, vertex {i}"
                    );
                }
                assert_eq!(
                    [inter[8 * s + 6], inter[8 * s + 7]].map(bits),
                    [bits(sentinel); 2]
                );
            }
            let untouched = |x: &[f32]| x.iter().all(|x| bits(*x) == bits(sentinel));
            assert!(untouched(packed[n..].as_flattened()) && untouched(&inter[8 * n..]));
            assert!(untouched(p[n..].as_flattened()) && untouched(nr[n..].as_flattened()));
        }
    }

    /// The grid the grouped path runs on starts its chunks at multiples of 4096 (so at
    /// windows' starts) even where the job's own grid would shift them to align a streamed
    /// output: a mesh of 2¹⁸ vertices and more into a packed output at every offset.
    #[test]
    fn the_unshifted_grid_starts_every_chunk_at_a_window() {
        let one = synthetic::rig(8, 4, 1).vertices()[0];
        let n = (1 << 18) + 100;
        let vertices = vec![one; n];
        let mut out = vec![[0f32; 6]; n + 8];
        for offset in 0..8 {
            let firsts = std::sync::Mutex::new(Vec::new());
            let output = Output::Packed(&mut out[offset..offset + n]);
            for_chunks_unshifted(output, &vertices, true, |first, o, v| {
                assert_eq!(o.len(), v.len());
                firsts.lock().unwrap().push((first, v.len()));
            });
            let mut firsts = firsts.into_inner().unwrap();
            firsts.sort_unstable();
            let mut next = 0;
            for (first, len) in firsts {
                assert_eq!(first, next, "offset {offset}: the chunks tile the mesh");
                assert!(
                    first.is_multiple_of(CHUNK),
                    "offset {offset}: chunk at {first}"
                );
                next = first + len;
            }
            assert_eq!(next, n);
        }
    }

    /// The grouping is made where it gains and only there: on the characters (blocks of
    /// sixteen that iterate: the Fox 26 → 5, RiggedFigure 22 → 13, CesiumMan 145 → 77) and
    /// on one and two influences in turn, not on the synthetic mesh, whose vertices all
    /// have four influences, nor where every vertex has as many.
    #[test]
    fn groups_are_made_where_they_gain() {
        for (m, before, after) in crate::vertex_order::tests::ITERATING_BLOCKS {
            let rig = crate::gltf_load::load_slice(m.bytes, m.file).unwrap();
            let fast = FastRig::<4>::new(&rig).unwrap();
            let g = Groups::of(fast.vertices()).expect("the characters gain");
            assert_eq!(iterating(fast.vertices()), before, "{}", rig.name);
            assert_eq!(iterating(&g.vertices), after, "{}", rig.name);
            for (i, &o) in g.order.iter().enumerate() {
                assert_eq!(g.vertices[i], fast.vertices()[o as usize]);
            }
        }
        assert!(Groups::of(synthetic::rig(5000, 54, 7).vertices()).is_none());
        // One and two influences in turn: grouped, so that half the blocks take no ScLERP;
        // two everywhere, or one: nothing to gain.
        let mixed = with_counts(&synthetic::rig(5000, 54, 7), |i| 1 + i % 2);
        assert!(Groups::of(mixed.vertices()).is_some());
        for k in [1, 2] {
            let same = with_counts(&synthetic::rig(5000, 54, 7), |_| k);
            assert!(Groups::of(same.vertices()).is_none());
        }
        assert!(Groups::<4>::of(&[]).is_none());
    }
}
