//! The skinning job: one call for every method — a rig laid out once ([`FastRig`]), a
//! [`Palette`] for the pose, and buffers the caller owns ([`Output`]) — in the manner of
//! ozz-animation's `SkinningJob`. Nothing is allocated while it runs: the kernels write
//! straight into a packed output (position then normal, 6 floats a vertex: their own
//! layout), and into an interleaved vertex buffer or split arrays by their own stores, each
//! vertex's six floats and no other ([`super::dest`]). Kavan et al. 2006, §6.
//!
//! The mesh is cut into chunks of about [`CHUNK`] vertices ([`Grid`]), which rayon hands
//! to its threads as they ask for work (`rayon::iter::split`, halving at chunk boundaries).
//! What the chunking costs, measured on a 2-core Intel Xeon (2026-12-04, scratch loop of
//! interleaved rounds, medians, DQS and LBS beside the fast paths' loads and stores alone):
//! - The grid starts where a streamed output starts a 64-byte line. When every chunk started
//!   at a multiple of [`CHUNK`], each one's output began misaligned by the same amount as
//!   the mesh's (a heap buffer of this size is 16 bytes past a page) and started with a
//!   block of ordinary stores over lines then streamed: at 10⁶ vertices one thread ran
//!   DQS at 250 and 263 M vertices/s where the shifted grid ran 258 and 268.5, the loads
//!   and stores alone 381–383 against 387–389 (two runs of 16 rounds).
//! - Chunks of 1024 vertices ran 5–10 % slower out of the cache than 4096; 16 384, 32 768,
//!   65 536 or one chunk a thread ran as fast as 4096 once the grid was shifted.
//! - What rayon costs a parallel job depends on the calling thread (DQS, medians of 15
//!   rounds of 2000 poses, two runs). From a thread of rayon's pool (inside
//!   `ThreadPool::install`), a pose took 23 µs at 8200 vertices (one thread 29.4, an ideal
//!   half 14.7), 68 at 32 768 (115) and 190 at 10⁵ (353): 8–11 µs beyond its share. From
//!   any other thread, which hands the job to the pool and sleeps until it ends: 31, 76–82
//!   and 232–237 µs, 16–55 beyond; at 8200 vertices no faster than one thread.
//!
//! On 16 cores (a lent Intel Xeon of family 6 model 207, one NUMA node, no SMT, 300 MiB
//! of L3; `scripts/scaling.sh`, 2026-12-04) the curve is the README's "Scaling with
//! cores". Out of the cache (10⁷ vertices) DQS on 16 threads with these chunks ran at
//! 0.87–0.90 of the loads and stores alone on 16 threads (1.31–1.34× a 16-thread
//! memcpy): bound by the memory's bandwidth. Chunks of 1024, 4096 and 16 384 vertices
//! (binaries run in turn, twice, at 8 and 16 threads): at 10⁷ on 16 threads 1024 was 7–9 %
//! slower and 16 384 no faster than 4096; elsewhere the three were within one binary's
//! run-to-run change. A pose there takes ~5 ms, against rayon's tens of µs.

use super::dest::Dest;
use super::palette::{Joints, Palette};
use super::qlb::{sbs_into, QlbKernel};
use super::{
    aligned_from, dib::DibKernel, log::LogKernel, run_with, DqsKernel, FastRig, LbsKernel, Vertex,
    CHUNK, STREAM_VERTICES,
};
use crate::error::{same_count, Result, SkinError};
use bytemuck::cast_slice;
use rayon::iter::ParallelIterator;

/// Where a job writes each vertex's skinned position and normal.
#[derive(Debug)]
pub enum Output<'a> {
    /// `[px, py, pz, nx, ny, nz]` per vertex, back to back: the kernels' own layout, written
    /// with no copy.
    Packed(&'a mut [[f32; 6]]),
    /// One interleaved vertex buffer of `stride` floats a vertex (at least 6): the position
    /// in the vertex's first three floats, the normal in the next three; the rest of each
    /// vertex (texture coordinates, …) is left as it is. `data.len()` is the vertex count
    /// times `stride`. A stride of 6 is [`Output::Packed`].
    Interleaved {
        /// The buffer.
        data: &'a mut [f32],
        /// Floats per vertex.
        stride: usize,
    },
    /// Positions and normals in two arrays of one entry per vertex.
    Split {
        /// Positions.
        positions: &'a mut [[f32; 3]],
        /// Normals.
        normals: &'a mut [[f32; 3]],
    },
}

impl<'a> From<&'a mut [[f32; 6]]> for Output<'a> {
    fn from(o: &'a mut [[f32; 6]]) -> Self {
        Output::Packed(o)
    }
}

impl Output<'_> {
    /// How many vertices it holds, or what is wrong with its shape.
    pub fn vertices(&self) -> Result<usize> {
        match self {
            Output::Packed(o) => Ok(o.len()),
            Output::Interleaved { data, stride } => {
                if *stride < 6 || data.len() % stride != 0 {
                    Err(SkinError::Stride {
                        stride: *stride,
                        floats: data.len(),
                    })
                } else {
                    Ok(data.len() / stride)
                }
            }
            Output::Split { positions, normals } => {
                same_count("the output", "normals", positions.len(), normals.len())?;
                Ok(positions.len())
            }
        }
    }
}

impl<'a> Output<'a> {
    /// The output split at vertex `mid` (at most its vertex count).
    fn split_at(self, mid: usize) -> (Output<'a>, Output<'a>) {
        match self {
            Output::Packed(o) => {
                let (a, b) = o.split_at_mut(mid);
                (Output::Packed(a), Output::Packed(b))
            }
            Output::Interleaved { data, stride } => {
                let (a, b) = data.split_at_mut(mid * stride);
                (
                    Output::Interleaved { data: a, stride },
                    Output::Interleaved { data: b, stride },
                )
            }
            Output::Split { positions, normals } => {
                let ((p, q), (n, m)) = (positions.split_at_mut(mid), normals.split_at_mut(mid));
                (
                    Output::Split {
                        positions: p,
                        normals: n,
                    },
                    Output::Split {
                        positions: q,
                        normals: m,
                    },
                )
            }
        }
    }

    /// The kernels' view of it.
    fn dest(self) -> Dest<'a> {
        match self {
            Output::Packed(o) => Dest::packed(o),
            Output::Interleaved { data, stride } => Dest::interleaved(data, stride),
            Output::Split { positions, normals } => Dest::split(positions, normals),
        }
    }

    /// Where the grid of chunks starts ([`Grid`]) for a mesh of `n` vertices: for a packed
    /// output that will be streamed ([`STREAM_VERTICES`] or more; an interleaved one of
    /// stride 6 is packed), the first vertex whose output starts a 64-byte line (one of the
    /// first eight, where the output is 8-byte aligned: then a 32-byte aligned one is among
    /// the first four, [`super::simd_start`]'s), so that only the first chunk starts with an
    /// overlapping block of ordinary stores and no line is streamed by two chunks; else 0
    /// (an output that is never streamed).
    fn shift(&self, n: usize) -> usize {
        let addr = match self {
            Output::Packed(o) => o.as_ptr() as usize,
            Output::Interleaved { data, stride: 6 } => data.as_ptr() as usize,
            _ => return 0,
        };
        if n < STREAM_VERTICES {
            return 0;
        }
        aligned_from(addr, 64).unwrap_or(0)
    }
}

/// The chunks of a mesh of `n` vertices (`n > 0`) whose grid starts at `shift` (< 8): chunk
/// `c` is `start(c)..start(c + 1)` for `c < count`. The first ends at `shift + CHUNK` and
/// the others are [`CHUNK`] long, so that every chunk but the first starts `shift`
/// vertices past a multiple of [`CHUNK`] (`24 CHUNK` bytes are whole 64-byte lines): where
/// `shift` is the first vertex of a streamed output to start a line ([`Output::shift`]),
/// every later chunk's output does too and streams from its first vertex (one overlapping
/// block of ordinary stores per mesh instead of one per chunk: at 10⁶ vertices one thread
/// skinned 2–3 % faster for it, the module docs' figures). A last chunk of 1–7
/// vertices joins the one before: every chunk of a mesh of eight or more has eight or more,
/// so each vertex goes through the SIMD kernel, whose numbers do not depend on the chunking.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Grid {
    n: usize,
    /// The first chunk's end.
    head: usize,
    /// How many chunks.
    count: usize,
}

impl Grid {
    fn new(n: usize, shift: usize) -> Grid {
        let head = (shift + CHUNK).min(n);
        let (whole, left) = ((n - head) / CHUNK, (n - head) % CHUNK);
        // A last chunk of 1–7 vertices joins the one before.
        let count = 1 + whole + usize::from(left >= 8);
        let head = if whole == 0 && left < 8 { n } else { head };
        Grid { n, head, count }
    }

    /// Where chunk `c` (at most `count`) starts; `start(count)` is `n`.
    fn start(&self, c: usize) -> usize {
        match c {
            0 => 0,
            c if c >= self.count => self.n,
            c => self.head + (c - 1) * CHUNK,
        }
    }
}

/// Chunks `from..to` of a [`Grid`]: their part of the output and of the vertices.
struct Piece<'a, const K: usize> {
    from: usize,
    to: usize,
    out: Output<'a>,
    vertices: &'a [Vertex<K>],
}

impl<const K: usize> Piece<'_, K> {
    /// The piece in two at the middle chunk, or itself where it has one chunk.
    fn halve(self, grid: &Grid) -> (Self, Option<Self>) {
        if self.to - self.from < 2 {
            return (self, None);
        }
        let mid = (self.from + self.to) / 2;
        let at = grid.start(mid) - grid.start(self.from);
        let (a, b) = self.out.split_at(at);
        let (v, w) = self.vertices.split_at(at);
        let first = Piece {
            from: self.from,
            to: mid,
            out: a,
            vertices: v,
        };
        let second = Piece {
            from: mid,
            to: self.to,
            out: b,
            vertices: w,
        };
        (first, Some(second))
    }
}

/// `chunk(first, out, vertices)` over the chunks of a [`Grid`] into `out` (`first`: the
/// index of the chunk's first vertex; `out`: the chunk's part of the caller's buffers, in
/// their layout, which the kernels write straight into), in order on the caller's thread,
/// or on all threads when `parallel` (rayon halves the chunks as its threads ask for work).
/// `out` holds as many vertices as `vertices` (checked by the caller).
pub(super) fn for_chunks<const K: usize>(
    out: Output<'_>,
    vertices: &[Vertex<K>],
    parallel: bool,
    chunk: impl Fn(usize, Dest<'_>, &[Vertex<K>]) + Sync,
) {
    let shift = out.shift(vertices.len());
    chunks_from(shift, out, vertices, parallel, chunk);
}

/// [`for_chunks`] on the grid that starts at 0 (never streamed): every chunk but the last
/// is [`CHUNK`] long and starts at a multiple of it (so of any of its divisors: the windows
/// of `crate::vertex_order`, which `super::grouped`'s order keeps each vertex within).
pub(super) fn for_chunks_unshifted<const K: usize>(
    out: Output<'_>,
    vertices: &[Vertex<K>],
    parallel: bool,
    chunk: impl Fn(usize, Dest<'_>, &[Vertex<K>]) + Sync,
) {
    chunks_from(0, out, vertices, parallel, chunk);
}

/// [`for_chunks`] on the grid that starts at `shift`.
fn chunks_from<const K: usize>(
    shift: usize,
    out: Output<'_>,
    vertices: &[Vertex<K>],
    parallel: bool,
    chunk: impl Fn(usize, Dest<'_>, &[Vertex<K>]) + Sync,
) {
    let n = vertices.len();
    if n == 0 {
        return;
    }
    let grid = Grid::new(n, shift);
    let each = |p: Piece<'_, K>| {
        let (mut out, mut vertices) = (p.out, p.vertices);
        for c in p.from..p.to {
            let len = grid.start(c + 1) - grid.start(c);
            let (o, rest) = out.split_at(len);
            let (v, more) = vertices.split_at(len);
            chunk(grid.start(c), o.dest(), v);
            (out, vertices) = (rest, more);
        }
    };
    let all = Piece {
        from: 0,
        to: grid.count,
        out,
        vertices,
    };
    if parallel {
        rayon::iter::split(all, |p| p.halve(&grid)).for_each(each);
    } else {
        each(all);
    }
}

/// One pose skinned into the caller's buffers: `rig` (laid out once), `palette` (made for
/// this pose, any method, for this rig: a palette is checked against the rig's joint and
/// cluster counts, not against which rig made it), `output`; on all threads when `parallel`.
/// On one thread it allocates nothing; on all, only what rayon's scheduler does (the rig's
/// caches aside, each made once by the first job that needs it, or ahead by its call: SBS's
/// clusters, [`FastRig::clusters`], and DIB's grouped vertices, [`FastRig::groups_dib`]).
/// A parallel
/// job called from a thread outside rayon's pool (a program's main thread) waits while the
/// pool takes it up, which on a 2-core machine cost 16–55 µs a pose more than from inside
/// (`rayon::ThreadPool::install` around a frame's work; the module docs' figures).
///
/// A clip frame after frame into an interleaved vertex buffer of 8 floats a vertex
/// (position, normal, uv):
///
/// ```
/// use chasles_skin::fast::{FastRig, Output, Palette, SkinningJob};
/// use chasles_skin::{gltf_load, pose::skinning_matrices, Method, Pose};
///
/// let m = chasles_models::FOX;
/// let rig = gltf_load::load_slice(m.bytes, m.file)?; // or gltf_load::load(path)
/// let fast = FastRig::<4>::new(&rig)?; // laid out once
/// let mut palette = Palette::new(Method::Dqs);
/// let mut vertices = vec![0f32; rig.mesh.positions.len() * 8];
/// for frame in 0..24 {
///     let pose = Pose::animated(&rig, 2, frame as f32 / 24.0)?;
///     palette.update(&fast, &skinning_matrices(&rig, &pose)?, true)?; // in place
///     SkinningJob {
///         rig: &fast,
///         palette: &palette,
///         output: Output::Interleaved { data: &mut vertices, stride: 8 },
///         parallel: true,
///     }
///     .run()?; // no allocation
/// }
/// assert!(vertices.iter().all(|x| x.is_finite()));
/// # Ok::<(), chasles_skin::SkinError>(())
/// ```
#[derive(Debug)]
pub struct SkinningJob<'a, const K: usize> {
    /// The rig.
    pub rig: &'a FastRig<K>,
    /// The pose's joint data for the method to run.
    pub palette: &'a Palette,
    /// Where the skinned vertices go.
    pub output: Output<'a>,
    /// All threads (rayon) or the caller's.
    pub parallel: bool,
}

impl<const K: usize> SkinningJob<'_, K> {
    /// Runs the job: an error, before anything is written, if the palette or the output
    /// does not fit the rig. Output is not checked for finiteness (the caller's buffers may
    /// be mapped GPU memory); [`super::Skinner`] checks it.
    pub fn run(self) -> Result<()> {
        let SkinningJob {
            rig,
            palette,
            output,
            parallel,
        } = self;
        // run_with and sbs_into check the palette and the output before writing.
        let antipodes = palette.antipodes();
        match palette.data() {
            Joints::Lbs(a) => run_with::<K, LbsKernel>(rig, cast_slice(a), &(), output, parallel),
            Joints::Dqs(d) => {
                run_with::<K, DqsKernel>(rig, cast_slice(d), antipodes, output, parallel)
            }
            Joints::Dib(d) => run_with::<K, DibKernel>(rig, cast_slice(d), &(), output, parallel),
            Joints::Log(t) => run_with::<K, LogKernel>(rig, cast_slice(t), &(), output, parallel),
            Joints::Qlb(j) => {
                run_with::<K, QlbKernel>(rig, cast_slice(j), antipodes, output, parallel)
            }
            Joints::Sbs { joints, centres } => sbs_into(
                rig,
                rig.clusters(),
                cast_slice(joints),
                antipodes,
                cast_slice(centres),
                output,
                parallel,
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every grid covers its mesh in order with no gap; every chunk of a mesh of eight or
    /// more has eight or more; the chunks after the first are `CHUNK` long (the last up to
    /// `CHUNK + 7`, or shorter where the mesh ends) and start `shift` past a multiple of
    /// `CHUNK`.
    #[test]
    fn the_grid_covers_the_mesh_in_chunks_of_eight_or_more() {
        let sizes = (1..=3 * CHUNK + 16).chain([STREAM_VERTICES + 13]);
        for n in sizes {
            for shift in 0..8 {
                let g = Grid::new(n, shift);
                let starts: Vec<usize> = (0..=g.count).map(|c| g.start(c)).collect();
                assert_eq!((starts[0], starts[g.count]), (0, n), "n {n} shift {shift}");
                for c in 0..g.count {
                    let len = starts[c + 1] - starts[c];
                    assert!(len >= 8.min(n), "n {n} shift {shift}: chunk {c} of {len}");
                    if c > 0 {
                        assert_eq!(starts[c] % CHUNK, shift, "n {n} shift {shift} chunk {c}");
                    }
                    if c > 0 && c + 1 < g.count {
                        assert_eq!(len, CHUNK, "n {n} shift {shift} chunk {c}");
                    }
                    let most = CHUNK + 7 + if c == 0 { shift } else { 0 };
                    assert!(len <= most, "n {n} shift {shift} chunk {c} of {len}");
                }
            }
        }
        // The grids the kernels used before a shift: chunks of CHUNK from 0.
        assert_eq!(Grid::new(3 * CHUNK + 100, 0).count, 4);
        assert_eq!(Grid::new(3 * CHUNK + 7, 0).count, 3);
        assert_eq!(
            Grid::new(CHUNK + 7, 0),
            Grid {
                n: CHUNK + 7,
                head: CHUNK + 7,
                count: 1
            }
        );
    }

    /// A streamed packed output at any of its eight offsets from a line gets a grid whose
    /// chunks after the first start a 64-byte line (so they stream from their first vertex,
    /// and no line is streamed by two chunks), and an interleaved output of stride 6 the
    /// same grid; outputs that are not streamed keep the grid from 0.
    #[test]
    fn a_streamed_output_starts_every_later_chunk_on_a_line() {
        let n = STREAM_VERTICES + 13;
        let mut buffer = vec![[0f32; 6]; n + 8];
        for offset in 0..8 {
            let o = &mut buffer[offset..offset + n];
            let addr = o.as_ptr() as usize;
            let out = Output::Packed(o);
            let g = Grid::new(n, out.shift(n));
            for c in 1..g.count {
                assert_eq!(
                    (addr + 24 * g.start(c)) % 64,
                    0,
                    "offset {offset}, chunk {c}"
                );
            }
            assert_eq!(
                out.shift(STREAM_VERTICES - 1),
                0,
                "a small mesh is not streamed"
            );
            let shift = out.shift(n);
            let o = &mut buffer[offset..offset + n];
            let six = Output::Interleaved {
                data: bytemuck::cast_slice_mut(o),
                stride: 6,
            };
            assert_eq!(six.shift(n), shift, "stride 6 is packed");
        }
        let mut inter = vec![0f32; n * 7];
        let out = Output::Interleaved {
            data: &mut inter,
            stride: 7,
        };
        assert_eq!(out.shift(n), 0, "an interleaved output is not streamed");
    }
}
