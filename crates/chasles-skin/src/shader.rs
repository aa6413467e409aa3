//! The skinning math of the GPU as WGSL source, written once (Kavan et al. 2006, §6): LBS's
//! blend of the joints' rows and its cofactor normals, DQS's blend with the antipodality
//! fix against the heaviest influence, and the rigid motion of a vertex by a unit dual
//! quaternion. The compute shaders of `gpu` put it before their entry points; the viewer
//! (`chasles-view`) puts it before its vertex shaders and translates the whole to GLSL ES
//! 3.00 for WebGL2 — so the browser skins with the very functions the compute shaders run.
//!
//! It declares the structs `Rows` (an [`crate::fast::Affine3x4`]), `Dq` (a
//! [`crate::fast::UnitDualQuat`]) and `Moved` (a position and a normal), and the functions
//! `lbs_blend(Rows, Rows, Rows, Rows, vec4<f32>) -> Rows`, `lbs_move(Rows, p, n) -> Moved`,
//! `dqs_blend(Dq, Dq, Dq, Dq, vec4<f32>) -> Dq` and `rigid_move(Dq, p, n) -> Moved` (with
//! the helpers `lbs_add`, `dqs_add`, `unit_or` and `rotate`), for four influences a vertex,
//! heaviest first, the weights in a `vec4`.

/// The WGSL source of the shared skinning functions (no bindings, no entry points).
pub const SKINNING_WGSL: &str = include_str!("gpu/skinning.wgsl");
