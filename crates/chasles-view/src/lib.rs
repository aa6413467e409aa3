//! # chasles-view — LBS against DQS in the browser, on your own character
//!
//! Kavan, Collins, Žára & O'Sullivan 2006, §6, compare linear blend skinning with dual
//! quaternion skinning on real characters: LBS's blended matrices shrink the skin where the
//! joints turn apart — the "candy wrapper" of a twisted joint (Figure 6(a)), lost volume at
//! bent elbows and knees (Figure 1) — where DQS, blending only rigid motions, keeps it
//! (Figure 6(b)) at about the same cost a vertex on the GPU (Figure 5). Technical artists
//! choose between them by looking, so this crate writes one self-contained HTML page that
//! shows a rig skinned both ways, live:
//!
//! * the mesh, its four influences a vertex (heaviest first) and the clip sampled into
//!   per-frame joint palettes — [`chasles_skin::fast::Palette`]s, `Affine3x4` rows for LBS
//!   and `UnitDualQuat`s for DQS, made from [`chasles_skin::pose::skinning_matrices`] —
//!   embedded as base64 in the page ([`scene`], [`page`]);
//! * skinning in WebGL2 vertex shaders whose math is the GPU compute shaders' own: the
//!   functions of [`chasles_skin::shader::SKINNING_WGSL`] (DQS with the antipodality fix
//!   against the heaviest influence) with the viewer's entry points, translated to GLSL ES
//!   3.00 by naga when the page is written ([`shader`]) — no third copy of the math;
//! * LBS and DQS side by side under one camera or one at a time, a clip scrubber with
//!   play, pause and speed, twist and bend sliders for the twisted cylinder
//!   ([`chasles_skin::cylinder`]), a heat map of LBS's local volume loss (the det of the
//!   blended 3×3 per vertex, as [`chasles_skin::volume`] measures it), orbit, pan and zoom,
//!   and the model's credits; the URL fragment sets the state
//!   (`#method=lbs|dqs|both&clip=NAME&time=T&heat=1`, `twist=DEG&bend=DEG` for the cylinder;
//!   also `speed=S`, `checker=0|1`, `play=0|1`, and `ui=0`, the canvas alone, for pictures).
//!
//! The page loads nothing — no URL, no server, no network — and exposes what the tests read
//! (`window.__chasles`, and `#debug=readback` / `#debug=bench` write a JSON report into the
//! page): the frame shown and the skinned positions read back by transform feedback.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod page;
pub mod scene;
pub mod shader;
pub mod synthetic;

use chasles_skin::{Rig, SkinError};
pub use scene::Scene;

/// Why a page cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    /// The rig cannot be posed or laid out (more than four influences a vertex, a bad clip).
    #[error(transparent)]
    Skin(#[from] SkinError),
    /// A clip asked for by a name the rig does not have.
    #[error("{rig}: no clip '{clip}'; there are: {}", if known.is_empty() { "none".to_string() } else { known.join(", ") })]
    UnknownClip {
        /// The rig.
        rig: String,
        /// The name asked for.
        clip: String,
        /// The rig's clips, by name (or index when unnamed).
        known: Vec<String>,
    },
    /// A clip whose palettes would not fit in a page.
    #[error(
        "clip '{clip}' takes {frames} frames, more than the {limit} a page holds (lower --fps)"
    )]
    TooLong {
        /// The clip.
        clip: String,
        /// Frames it would take.
        frames: u64,
        /// The most frames a page holds for this rig.
        limit: usize,
    },
    /// A frame rate outside 1–240.
    #[error("--fps {0} is not between 1 and 240")]
    Fps(f32),
    /// naga refused the viewer's shaders (a bug of ours, whatever the input).
    #[error("the viewer's shaders: {0}")]
    Shader(String),
    /// The page could not be assembled.
    #[error("the page: {0}")]
    Page(String),
}

/// A page made, with what it holds.
#[derive(Debug, Clone, PartialEq)]
pub struct Page {
    /// The HTML, whole.
    pub html: String,
    /// Vertices of the mesh.
    pub vertices: usize,
    /// Joints of the skin.
    pub joints: usize,
    /// Frames (or poses) embedded, all clips together.
    pub frames: usize,
}

impl Page {
    fn of(scene: &Scene) -> Result<Page, ViewError> {
        let frames = match &scene.grid {
            Some(g) => g.twist.len() * g.bend.len(),
            None => scene.clips.iter().map(|c| c.times.len()).sum(),
        };
        Ok(Page {
            html: page::html(scene, &shader::glsl()?)?,
            vertices: scene.buffers.positions.len() / 3,
            joints: scene.joints,
            frames,
        })
    }
}

/// Frames a second a clip is sampled at unless told otherwise.
pub const DEFAULT_FPS: f32 = 30.0;

/// The page for `rig`: every clip sampled at `fps`, `clip` (a name or an index) shown
/// first, `credit` (the model's licence and attribution) shown under it.
pub fn character(rig: &Rig, clip: Option<&str>, fps: f32, credit: &str) -> Result<Page, ViewError> {
    Page::of(&Scene::character(rig, clip, fps, credit)?)
}

/// Degrees between the cylinder's poses on the twist and bend sliders.
pub const CYLINDER_STEP: f32 = 5.0;

/// The page for the twisted two-bone cylinder (the candy wrapper): twist 0°–360° and
/// bend 0°–180° every [`CYLINDER_STEP`] degrees, shown at 180° of twist.
pub fn cylinder() -> Result<Page, ViewError> {
    Page::of(&Scene::cylinder(CYLINDER_STEP)?)
}
