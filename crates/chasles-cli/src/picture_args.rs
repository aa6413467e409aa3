//! The picture options that `chasles interp`, `chasles blend` and `chasles skin` share:
//! one clap `Args` struct, flattened into each command.

use crate::output::check_extension;
use std::path::PathBuf;

/// The most frames a `--gif` draws, whatever else allows: each frame is a picture held in
/// memory until the file is written.
pub const MAX_GIF_FRAMES: usize = 2_000;

/// `--plot`, `--render`, `--gif`, `--sphere`: what each draws depends on the command.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct Pictures {
    /// Also write a line plot, SVG — interp: the angular velocity (§5.2; PNG too); blend:
    /// every method's rotation along the path of weights; skin: LBS's smallest local volume
    /// over the clip (with --artifacts: middle radius against twist).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Also draw, PNG — interp: the R at eight evenly spread frames; blend: the inputs and
    /// every method's blend as letters R; skin: the pose skinned by every method side by
    /// side (with --artifacts: the cylinder twisted 180°).
    #[arg(long)]
    pub render: Option<PathBuf>,
    /// Also animate, GIF — interp: the R turned by every frame (§5.1); blend: the blend
    /// along the path of weights; skin: LBS beside DQS through the clip at --fps (with
    /// --artifacts: the twist sweep).
    #[arg(long)]
    pub gif: Option<PathBuf>,
    /// Also plot on the unit sphere (§5.3), PNG — interp: the curve; blend: the method's
    /// rotations along the path; skin: the clip's most-turning joint.
    #[arg(long)]
    pub sphere: Option<PathBuf>,
}

impl Pictures {
    /// Checks every path's extension before any work: `--plot` takes one of `plot`,
    /// `--render` and `--sphere` PNG, `--gif` GIF.
    pub fn check(&self, plot: &[&str]) -> anyhow::Result<()> {
        check_extension("--plot", self.plot.as_deref(), plot)?;
        check_extension("--render", self.render.as_deref(), &["png"])?;
        check_extension("--gif", self.gif.as_deref(), &["gif"])?;
        check_extension("--sphere", self.sphere.as_deref(), &["png"])
    }

    /// Whether any picture was asked for.
    pub fn any(&self) -> bool {
        self.plot.is_some() || self.render.is_some() || self.gif.is_some() || self.sphere.is_some()
    }
}
