//! # chasles-skin — skeletal skinning with every rigid blend
//!
//! The case study of Kavan et al. 2006, §6, on real rigged meshes: a [`rig::Rig`] (mesh,
//! node hierarchy, skin, per-vertex influences, animations) loaded from glTF 2.0
//! ([`gltf_load`]), posed ([`pose`]), and deformed by [`skinning`] with linear blend
//! skinning, dual quaternion skinning and the other blends of `chasles::blend`. The
//! candy-wrapper artifact is measured on a twisted cylinder built in code ([`cylinder`]).
//! Deformed meshes are written as OBJ or PLY ([`writers`]).

#![warn(missing_docs)]

pub mod animation;
pub mod cylinder;
pub mod error;
pub mod fast;
pub mod gltf_load;
pub mod pose;
pub mod rig;
pub mod skinning;
pub mod synthetic;
pub mod writers;

pub use error::{Result, SkinError};
pub use pose::{joint_transforms, JointTransforms, Pose};
pub use rig::{Influences, Mesh, Node, Rig, Trs};
pub use skinning::{skin, skin_joints, Method, Skinned};
