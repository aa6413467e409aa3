//! The skinning job on the GPU: the CPU's [`Palette`] uploaded as it is and the skinned
//! vertices read back into the caller's [`Output`] (any layout), as
//! [`crate::fast::SkinningJob`] does on the CPU (Kavan et al. 2006, §6).

use super::{GpuError, GpuSkinner};
use crate::fast::{Output, Palette};
use rayon::prelude::*;

impl GpuSkinner {
    /// The skinning job on the GPU, as on the CPU ([`crate::fast::SkinningJob`]): the
    /// palette's joints uploaded as they are (an [`crate::fast::Affine3x4`] or a
    /// [`crate::fast::UnitDualQuat`] a joint: LBS, DQS and DIB have shaders), the shader run,
    /// and the skinned vertices read back into the caller's `output` (any layout). An error,
    /// before anything is uploaded, if the palette or the output does not fit the rig; a
    /// non-finite position or normal is [`GpuError::NonFinite`].
    pub fn run(&self, palette: &Palette, output: Output<'_>) -> Result<(), GpuError> {
        let n = output.vertices()?;
        let vertices: usize = self.chunks.iter().map(|c| c.vertices).sum();
        crate::error::same_count("the GPU rig", "output vertices", vertices, n)?;
        let pipeline = self.upload_joints(palette.data())?;
        self.submit(pipeline);
        self.read_output(output)
    }

    /// Brings the last dispatch's vertices back into `output` (checked to hold them all),
    /// chunk by chunk, copied out on all cores.
    fn read_output(&self, mut output: Output<'_>) -> Result<(), GpuError> {
        let put = |o: &mut [f32], v: &[f32; 8]| {
            o[..3].copy_from_slice(&v[..3]);
            o[3..6].copy_from_slice(&v[4..7]);
        };
        self.read_chunks(|first, skinned| {
            let range = first..first + skinned.len();
            match &mut output {
                Output::Packed(o) => o[range]
                    .par_iter_mut()
                    .zip(skinned)
                    .for_each(|(o, v)| put(o, v)),
                Output::Interleaved { data, stride } => data
                    [range.start * *stride..range.end * *stride]
                    .par_chunks_mut(*stride)
                    .zip(skinned)
                    .for_each(|(o, v)| put(o, v)),
                Output::Split { positions, normals } => positions[range.clone()]
                    .par_iter_mut()
                    .zip(&mut normals[range])
                    .zip(skinned)
                    .for_each(|((p, n), v)| {
                        *p = [v[0], v[1], v[2]];
                        *n = [v[4], v[5], v[6]];
                    }),
            }
        })
    }
}
