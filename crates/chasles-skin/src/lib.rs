//! # chasles-skin — skeletal skinning with every rigid blend
//!
//! The case study of Kavan et al. 2006, §6, on real rigged meshes: a [`rig::Rig`] (mesh,
//! node hierarchy, skin, per-vertex influences, animations; built and checked once by
//! [`Rig::new`]) loaded from glTF 2.0 ([`gltf_load`], from a file or bytes) or a plain JSON
//! format ([`json_rig`]), posed ([`pose`]: clips sampled by the glTF rules), and deformed by
//! linear blend skinning, dual quaternion skinning, DIB, Log, decomposed QLB and SBS:
//!
//! * [`skinning`] — the reference path, each method as the papers write it;
//! * [`fast`] — the fast path: a rig laid out once ([`fast::FastRig`], 4 or 8 influences),
//!   a per-method [`fast::Palette`] of `#[repr(C)]` joint types for each pose, and one
//!   [`fast::SkinningJob`] into the caller's buffers (packed, interleaved, split), AVX2+FMA
//!   kernels chosen at run time with a portable fallback, all cores (DIB's on a copy of
//!   the vertices grouped by influence count where that gains; [`vertex_order`] gives
//!   that order to apply to an asset once);
//! * `gpu` (feature `gpu`) — WGSL compute shaders for LBS, DQS and DIB through wgpu, taking
//!   the same palette and output; their per-vertex math ([`shader`]) is shared with the
//!   browser viewer's vertex shaders.
//!
//! The candy-wrapper artifact is measured on a twisted cylinder built in code
//! ([`cylinder`]), linear blending's volume loss by [`volume`]; deformed meshes are written
//! whole or not at all as OBJ, PLY, glTF or JSON ([`writers`]).
//!
//! Beyond the paper (its §7): clips blended per joint by DLB ([`clip_blend`], "motion
//! blending") and compressed to a vertex tolerance ([`clip_compress`], "motion analysis and
//! compression"), written back as glTF with the rig ([`gltf_write`]). Every error is a
//! [`SkinError`] variant naming the file, item or field.

#![warn(missing_docs)]

pub mod animation;
pub mod bounded;
pub mod clip_blend;
pub mod clip_compress;
pub mod cloth;
pub mod cylinder;
pub mod error;
pub mod fast;
mod gltf_check;
pub mod gltf_load;
pub mod gltf_write;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod json_rig;
pub mod peers;
pub mod pose;
pub mod reach;
pub mod rig;
pub mod rotation_centre;
pub mod shader;
pub mod skinning;
pub mod synthetic;
pub mod vertex_order;
pub mod volume;
pub mod writers;

pub use error::{ChannelProblem, Result, SkinError};

/// Loads a rig from `.gltf`, `.glb` or `.json` (by extension).
pub fn load(path: &std::path::Path) -> Result<Rig> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("gltf") | Some("glb") => gltf_load::load(path),
        Some("json") => {
            let text = bounded::read_text(path, bounded::MAX_MODEL_BYTES)?;
            let mut rig = json_rig::parse_rig(&text, &path.display().to_string())?;
            rig.name = gltf_load::file_name(path);
            Ok(rig)
        }
        _ => Err(SkinError::UnknownFormat {
            path: path.display().to_string(),
        }),
    }
}
pub use pose::{joint_transforms, JointTransforms, Pose};
pub use rig::{Influences, Mesh, Node, Rig, Trs};
pub use skinning::{skin, skin_joints, Method, Skinned};
