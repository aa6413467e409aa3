//! The skinning job: one call for every method — a rig laid out once ([`FastRig`]), a
//! [`Palette`] for the pose, and buffers the caller owns ([`Output`]) — in the manner of
//! ozz-animation's `SkinningJob`. Nothing is allocated while it runs: the kernels write
//! straight into a packed output (position then normal, 6 floats a vertex: their own
//! layout), and into an interleaved vertex buffer or split arrays by their own stores, each
//! vertex's six floats and no other ([`super::dest`]). Kavan et al. 2006, §6.

use super::dest::Dest;
use super::palette::{Joints, Palette};
use super::qlb::{sbs_into, QlbKernel};
use super::{
    dib::DibKernel, log::LogKernel, run_with, DqsKernel, FastRig, LbsKernel, Vertex, CHUNK,
};
use crate::error::{same_count, Result, SkinError};
use bytemuck::cast_slice;
use rayon::prelude::*;

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

/// `chunk(first, out, vertices)` over chunks of [`CHUNK`] vertices into `out` (`first`: the
/// index of the chunk's first vertex; `out`: the chunk's part of the caller's buffers, in
/// their layout, which the kernels write straight into), on all threads when `parallel`.
/// `out` holds as many vertices as `vertices` (checked by the caller).
pub(super) fn for_chunks<const K: usize>(
    out: Output<'_>,
    vertices: &[Vertex<K>],
    parallel: bool,
    chunk: impl Fn(usize, Dest<'_>, &[Vertex<K>]) + Sync,
) {
    if vertices.is_empty() {
        return; // and no chunk size to compute from a stride
    }
    match out {
        Output::Packed(o) => {
            let each = |(c, (o, v))| chunk(c * CHUNK, Dest::packed(o), v);
            if parallel {
                o.par_chunks_mut(CHUNK)
                    .zip(vertices.par_chunks(CHUNK))
                    .enumerate()
                    .for_each(each);
            } else {
                o.chunks_mut(CHUNK)
                    .zip(vertices.chunks(CHUNK))
                    .enumerate()
                    .for_each(each);
            }
        }
        Output::Interleaved { data, stride } => {
            let each = |(c, (d, v))| chunk(c * CHUNK, Dest::interleaved(d, stride), v);
            if parallel {
                data.par_chunks_mut(CHUNK * stride)
                    .zip(vertices.par_chunks(CHUNK))
                    .enumerate()
                    .for_each(each);
            } else {
                data.chunks_mut(CHUNK * stride)
                    .zip(vertices.chunks(CHUNK))
                    .enumerate()
                    .for_each(each);
            }
        }
        Output::Split { positions, normals } => {
            let each = |(c, ((p, n), v))| chunk(c * CHUNK, Dest::split(p, n), v);
            if parallel {
                positions
                    .par_chunks_mut(CHUNK)
                    .zip(normals.par_chunks_mut(CHUNK))
                    .zip(vertices.par_chunks(CHUNK))
                    .enumerate()
                    .for_each(each);
            } else {
                positions
                    .chunks_mut(CHUNK)
                    .zip(normals.chunks_mut(CHUNK))
                    .zip(vertices.chunks(CHUNK))
                    .enumerate()
                    .for_each(each);
            }
        }
    }
}

/// One pose skinned into the caller's buffers: `rig` (laid out once), `palette` (made for
/// this pose, any method, for this rig: a palette is checked against the rig's joint and
/// cluster counts, not against which rig made it), `output`; on all threads when `parallel`.
/// On one thread it allocates nothing; on all, only what rayon's scheduler does.
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
        let signs = palette.signs();
        match palette.data() {
            Joints::Lbs(a) => run_with::<K, LbsKernel>(rig, cast_slice(a), &(), output, parallel),
            Joints::Dqs(d) => run_with::<K, DqsKernel>(rig, cast_slice(d), signs, output, parallel),
            Joints::Dib(d) => run_with::<K, DibKernel>(rig, cast_slice(d), &(), output, parallel),
            Joints::Log(t) => run_with::<K, LogKernel>(rig, cast_slice(t), &(), output, parallel),
            Joints::Qlb(j) => run_with::<K, QlbKernel>(rig, cast_slice(j), signs, output, parallel),
            Joints::Sbs { joints, centres } => sbs_into(
                rig,
                rig.clusters(),
                cast_slice(joints),
                signs,
                cast_slice(centres),
                output,
                parallel,
            ),
        }
    }
}
