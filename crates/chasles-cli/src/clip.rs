//! `chasles clip`: clips of a rig made anew (Kavan et al. 2006, §7) — `blend` two clips per
//! joint by DLB ("motion blending"), `compress` one to a vertex tolerance ("motion analysis
//! and compression"). Each writes a `.glb` of the rig with the made clip (and, with
//! `--keep-clips`, the rig's own), loaded back and checked before it is written whole
//! (temporary file and rename): `chasles skin --rig OUT --anim NAME` and `chasles view OUT`
//! play it like any clip.

use crate::output::{extension, Pending};
use anyhow::{bail, Context, Result};
use chasles_skin::clip_blend::{self, BlendOptions};
use chasles_skin::clip_compress::{self, CompressOptions, Rotation};
use chasles_skin::gltf_write::rig_glb;
use chasles_skin::{gltf_load, Rig};
use std::path::{Path, PathBuf};

/// The `chasles clip` commands.
#[derive(Debug, clap::Subcommand)]
pub enum ClipCommand {
    /// Blend two clips of one skeleton per joint by DLB of the joints' local transforms
    /// (shortest path), optionally time-warped by normalized phase (--sync).
    ///
    /// Writes the rig with the blended clip as .glb (LINEAR keys at every frame); play it with
    /// `chasles skin --rig OUT --anim NAME` or `chasles view OUT`.
    ///
    /// Examples:
    ///   chasles clip blend --rig Fox.glb --clips Walk,Run --weight 0.5 --sync --out trot.glb
    ///   chasles skin --rig trot.glb --anim "Walk+Run 0.5" --all-frames --out frames/
    #[command(verbatim_doc_comment)]
    Blend(BlendArgs),
    /// Remove key frames per joint while every vertex of the skinned mesh stays within
    /// --tolerance of the original clip at its own sampling (greedy selection).
    ///
    /// Rotations are reconstructed by Slerp (glTF LINEAR) or Squad (its keys and tangents as
    /// glTF CUBICSPLINE); the written file is loaded back and its worst vertex error
    /// measured before it is written; the bound is checked on it.
    ///
    /// Examples:
    ///   chasles clip compress --rig CesiumMan.glb --clip 0 --tolerance 0.005 --out small.glb
    ///   chasles clip compress --rig Fox.glb --clip Run --tolerance 0.5 --rotation slerp
    #[command(verbatim_doc_comment)]
    Compress(CompressArgs),
}

/// Options of `chasles clip blend`.
#[derive(Debug, clap::Args)]
pub struct BlendArgs {
    /// The rig: .gltf, .glb or .json.
    #[arg(long)]
    pub rig: PathBuf,
    /// The two clips, by name or index: A,B.
    #[arg(long, value_delimiter = ',', value_name = "A,B", required = true)]
    pub clips: Vec<String>,
    /// The weight of B, in [0, 1] (A gets 1 − W).
    #[arg(long, value_name = "W", allow_negative_numbers = true)]
    pub weight: f64,
    /// Align the clips by normalized phase: the blend lasts (1 − W)·d_A + W·d_B.
    #[arg(long)]
    pub sync: bool,
    /// Frames per second of the blend (default: the finer key rate of the two clips).
    #[arg(long)]
    pub fps: Option<f64>,
    /// The blended clip's name (default "A+B W").
    #[arg(long)]
    pub name: Option<String>,
    /// Output .glb: the rig with the blended clip.
    #[arg(long)]
    pub out: PathBuf,
    /// Also write the rig's own clips into the output (after the blend).
    #[arg(long)]
    pub keep_clips: bool,
}

/// The reconstruction of rotations, on the command line.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum RotationArg {
    /// Slerp between kept keys (glTF LINEAR).
    Slerp,
    /// Squad's keys and tangents (glTF CUBICSPLINE).
    Squad,
}

/// Options of `chasles clip compress`.
#[derive(Debug, clap::Args)]
pub struct CompressArgs {
    /// The rig: .gltf, .glb or .json.
    #[arg(long)]
    pub rig: PathBuf,
    /// The clip, by name or index.
    #[arg(long)]
    pub clip: String,
    /// The largest distance any vertex may move from the original, in model units.
    #[arg(long, value_name = "D", allow_negative_numbers = true)]
    pub tolerance: f64,
    /// How rotations are rebuilt between kept keys.
    #[arg(long, value_enum, default_value = "squad")]
    pub rotation: RotationArg,
    /// The skinning method the vertices are measured with.
    #[arg(long, value_enum, default_value = "dqs")]
    pub method: crate::choice::SkinMethod,
    /// Output .glb: the rig with the compressed clip (without it: the report only).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Also write the rig's other clips into the output (after the compressed one).
    #[arg(long)]
    pub keep_clips: bool,
}

/// Runs `chasles clip …`.
pub fn run(cmd: ClipCommand) -> Result<()> {
    match cmd {
        ClipCommand::Blend(a) => blend(a),
        ClipCommand::Compress(a) => compress(a),
    }
}

fn check_glb(out: &Path) -> Result<()> {
    if extension(out) != "glb" {
        bail!("--out {} must end in .glb", out.display());
    }
    Ok(())
}

/// The rig's clips other than `except`, for --keep-clips.
fn other_clips(
    rig: &Rig,
    keep: bool,
    except: Option<usize>,
) -> Vec<chasles_skin::animation::Animation> {
    if !keep {
        return Vec::new();
    }
    rig.animations
        .iter()
        .enumerate()
        .filter(|(i, _)| Some(*i) != except)
        .map(|(_, a)| a.clone())
        .collect()
}

fn blend(a: BlendArgs) -> Result<()> {
    check_glb(&a.out)?;
    if a.clips.len() != 2 {
        bail!(
            "--clips takes two clips, A,B (got {}: {})",
            a.clips.len(),
            a.clips.join(",")
        );
    }
    clip_blend::check_weight(a.weight)?;
    let rig = chasles_skin::load(&a.rig)?;
    let (ia, ib) = (rig.clip_index(&a.clips[0])?, rig.clip_index(&a.clips[1])?);
    let name = a
        .name
        .clone()
        .unwrap_or_else(|| format!("{}+{} {}", a.clips[0], a.clips[1], a.weight));
    let opts = BlendOptions {
        weight: a.weight,
        sync: a.sync,
        fps: a.fps,
        name: name.clone(),
    };
    let blended = clip_blend::blend_clips(&rig, ia, ib, &opts)?;
    let mut clips = vec![blended.animation.clone()];
    clips.extend(other_clips(&rig, a.keep_clips, None));
    let comment = format!(
        "{} blended with weight {} by DLB per joint{} (chasles clip blend)",
        a.clips.join(" and "),
        a.weight,
        if a.sync { ", time-warped by phase" } else { "" }
    );
    let bytes = rig_glb(&rig, &clips, &comment)?;
    // Loaded back before it is written: what is written is a rig `chasles skin` reads.
    let back = gltf_load::load_slice(&bytes, &a.out.display().to_string())
        .context("the blended file does not load back (a bug: please report it)")?;
    let mut worst = (0.0f64, 0.0f64);
    for ch in &back.animations[0].channels {
        if ch.path == chasles_skin::animation::Path::Rotation {
            for v in &ch.values {
                let (n, r) = clip_blend::rigidity_defect(chasles::Quat::from_array(*v));
                worst = (worst.0.max(n), worst.1.max(r));
            }
        }
    }
    let mut pending = Pending::default();
    pending.add(&a.out, bytes, None);
    for line in pending.write()? {
        println!("{line}");
    }
    println!(
        "{}: '{name}' = {} blended with {} at weight {}{}: {} frames over {:.4} s at {:.3} fps; rigid per joint (|q| − 1 ≤ {:.1e}, |RᵀR − I| ≤ {:.1e}); wrote {}",
        rig.name,
        a.clips[0],
        a.clips[1],
        a.weight,
        if a.sync { ", time-warped" } else { "" },
        blended.times.len(),
        blended.times.last().copied().unwrap_or(0.0),
        blended.fps,
        worst.0,
        worst.1,
        a.out.display()
    );
    Ok(())
}

fn compress(a: CompressArgs) -> Result<()> {
    if let Some(out) = &a.out {
        check_glb(out)?;
    }
    clip_compress::check_tolerance(a.tolerance)?;
    let rig = chasles_skin::load(&a.rig)?;
    let c = rig.clip_index(&a.clip)?;
    let rotation = match a.rotation {
        RotationArg::Slerp => Rotation::Slerp,
        RotationArg::Squad => Rotation::Squad,
    };
    let method = a.method.0;
    let opts = CompressOptions {
        tolerance: a.tolerance,
        rotation,
        method,
    };
    let comment = format!(
        "clip {} compressed to {} with {} (chasles clip compress)",
        a.clip,
        a.tolerance,
        rotation.name()
    );
    // Written, loaded back and measured before anything is written: the bound holds on the
    // file's own clip.
    let extra = other_clips(&rig, a.keep_clips, Some(c));
    let written = clip_compress::compress_to_glb(&rig, c, &opts, &extra, &comment)?;
    let (done, worst, bytes) = (&written.compressed, written.in_file, written.bytes.clone());
    if worst.distance > a.tolerance {
        bail!(
            "the written clip would move vertex {} by {} at frame {}, past the tolerance {} (a bug: please report it)",
            worst.vertex,
            worst.distance,
            worst.frame,
            a.tolerance
        );
    }
    if let Some(out) = &a.out {
        let mut pending = Pending::default();
        pending.add(out, bytes, None);
        for line in pending.write()? {
            println!("{line}");
        }
    }
    println!(
        "{}: clip {} ({} frames) with {}: kept {} of {} keys ({:.1} %){}; worst vertex error {:.4e} (vertex {}, frame {}) in the written file, {:.4e} in memory, tolerance {} ({} skinning, per-joint budget {:.3} of it){}",
        rig.name,
        if rig.animations[c].name.is_empty() {
            c.to_string()
        } else {
            format!("'{}'", rig.animations[c].name)
        },
        done.frames.len(),
        rotation.name(),
        done.kept_keys,
        done.original_keys,
        100.0 * done.ratio(),
        if done.kept_original {
            " — the original channels (the tolerance could not be met with fewer)"
        } else {
            ""
        },
        worst.distance,
        worst.vertex,
        worst.frame,
        done.worst.distance,
        a.tolerance,
        method.name(),
        done.budget,
        a.out
            .as_ref()
            .map_or(String::new(), |p| format!("; wrote {}", p.display()))
    );
    Ok(())
}
