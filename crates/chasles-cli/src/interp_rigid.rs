//! `chasles interp --rigid`: key frames that turn and move (Kavan et al. 2006, §7's
//! "spatial keyframing"; `chasles::interp::rigid`), by piecewise ScLERP (`--method sclerp`,
//! or `slerp`), the dual-quaternion Squad (`squad`) or Spring on rigid motions (`spring`,
//! `--energy split|screw`, `--length-scale`). Keys: any key of the key file, with a
//! `translation` or as a whole `matrix` or `dq` (keys without one stay at the origin).
//! Rows: `index,t,w,x,y,z,tx,ty,tz,velocity,key` (velocity: eq. 5.1 on the rotations). The
//! frames are shared among the intervals uniformly, or in proportion to the key times.
//! Pictures: `--gif` the R moved along the curve, `--render` the keys, the path of the top
//! of the R's stem and the R at eight frames.

use crate::choice::InterpMethod;
use crate::interp::{frames_csv, frames_json, InterpArgs};
use crate::keyfile;
use crate::output::{extension, Pending};
use crate::picture_args::MAX_GIF_FRAMES;
use anyhow::{bail, Context, Result};
use chasles::analysis::velocity::velocity_chord;
use chasles::interp::rigid_spring::rigid_energy;
use chasles::interp::{
    rigid_spring, RigidEnergy, RigidFrame, RigidKeys, RigidMethod, RigidSpringConfig,
};
use chasles::{DualQuat, Quat};
use std::fmt::Write as _;
use std::time::Instant;

/// The rigid options of `chasles interp`.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct RigidArgs {
    /// Interpolate rigid motions (keys with a translation, matrix or dq): --method sclerp
    /// (or slerp: piecewise ScLERP), squad (the dual-quaternion Squad) or spring; frames are
    /// shared uniformly, or by key times (--timing does not apply).
    #[arg(long)]
    pub rigid: bool,
    /// --rigid --method spring: the energy — split (the rotations' Spring energy plus the
    /// translations' second differences, the default) or screw (the dual-quaternion curve's
    /// own, which turns the body along a bent path).
    #[arg(long, value_enum)]
    pub energy: Option<EnergyArg>,
    /// --rigid --method spring: the length that weighs as much as one radian (default 1).
    #[arg(long, allow_negative_numbers = true)]
    pub length_scale: Option<f64>,
}

/// The rigid Spring's energy on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum EnergyArg {
    /// The rotations' Spring energy plus the translations' second differences.
    Split,
    /// The dual-quaternion curve's own curvature energy.
    Screw,
}

impl RigidArgs {
    /// The first rigid-only flag given without `--rigid`.
    pub fn stray(&self) -> Option<&'static str> {
        if self.rigid {
            None
        } else if self.energy.is_some() {
            Some("--energy")
        } else if self.length_scale.is_some() {
            Some("--length-scale")
        } else {
            None
        }
    }
}

/// A rigid run: frames, the rotations' velocity, the summary.
pub struct RigidRun {
    /// The frames.
    pub frames: Vec<RigidFrame<f64>>,
    /// Eq. 5.1 per frame, of the rotations.
    pub velocity: Vec<f64>,
    /// Summary lines.
    pub summary: String,
}

/// Flags of the rotation curves that a rigid run does not take.
fn refuse_others(args: &InterpArgs) -> Result<()> {
    let flags = [
        ("--horizon", args.curve.horizon.is_some()),
        ("--tension", args.curve.tension.is_some()),
        ("--continuity", args.curve.continuity.is_some()),
        ("--bias", args.curve.bias.is_some()),
        ("--keep-signs", args.keep_signs),
        ("--frames-dir", args.frames_dir.is_some()),
        ("--plot", args.pictures.plot.is_some()),
        ("--sphere", args.pictures.sphere.is_some()),
    ];
    if let Some((flag, _)) = flags.iter().find(|f| f.1) {
        bail!("{flag} does not apply to --rigid curves (they take --gif and --render)");
    }
    if let Some(flag) = args.spring.given().first() {
        bail!("{flag} is a control of the rotations' Spring: --rigid --method spring takes --energy and --length-scale");
    }
    Ok(())
}

/// Computes the rigid curve.
pub fn compute(args: &InterpArgs) -> Result<RigidRun> {
    refuse_others(args)?;
    let method = match args.method {
        InterpMethod::Slerp => RigidMethod::ScLerp,
        InterpMethod::Squad => RigidMethod::Squad,
        InterpMethod::Spring => {
            let mut cfg = RigidSpringConfig::default();
            if let Some(e) = args.rigid.energy {
                cfg.energy = match e {
                    EnergyArg::Split => RigidEnergy::Split,
                    EnergyArg::Screw => RigidEnergy::Screw,
                };
            }
            if let Some(l) = args.rigid.length_scale {
                if !(l > 0.0 && l.is_finite()) {
                    bail!("--length-scale must be positive and finite, got {l}");
                }
                cfg.length_scale = l;
            }
            RigidMethod::Spring(cfg)
        }
        other => bail!(
            "--rigid interpolates with sclerp (slerp), squad or spring, not {}",
            other.name()
        ),
    };
    if !matches!(method, RigidMethod::Spring(_)) {
        for (flag, given) in [
            ("--energy", args.rigid.energy.is_some()),
            ("--length-scale", args.rigid.length_scale.is_some()),
        ] {
            if given {
                bail!("{flag} applies to --rigid --method spring");
            }
        }
    }
    let n = args.frames.unwrap_or(200);
    if n > args.max_frames {
        bail!(
            "--frames {n} is more than --max-frames {} (raise it to make longer curves)",
            args.max_frames
        );
    }
    let keys = keyfile::load(&args.keys)?;
    if keys.velocities.is_some() {
        bail!(
            "{}: key velocities are for the rotation curves, not --rigid",
            keys.source
        );
    }
    let poses: Vec<DualQuat<f64>> = match &keys.poses {
        Some(p) => p.clone(),
        None => keys
            .quats
            .iter()
            .map(|q| DualQuat::from_rotation(*q))
            .collect(),
    };
    let rk = RigidKeys::new(&poses, keys.times.as_deref()).with_context(|| keys.source.clone())?;
    let started = Instant::now();
    let mut extra = String::new();
    let frames = match &method {
        RigidMethod::Spring(cfg) => {
            let r = rigid_spring(&rk, n, cfg)?;
            let _ = writeln!(
                extra,
                "spring            {} energy, length scale {}: F {:.6e} (start) -> {:.6e}, {} steps, gradient {:.1e} of the start's",
                match cfg.energy {
                    RigidEnergy::Split => "split",
                    RigidEnergy::Screw => "screw",
                },
                cfg.length_scale,
                r.energy.0,
                r.energy.1,
                r.iterations,
                r.gradient_ratio
            );
            r.frames
        }
        m => chasles::interp::interpolate_rigid(m, &rk, n)?,
    };
    let elapsed = started.elapsed();
    let q: Vec<Quat<f64>> = frames.iter().map(|f| f.dq.real).collect();
    let velocity = velocity_chord(&q);
    let d: Vec<DualQuat<f64>> = frames.iter().map(|f| f.dq).collect();
    let path: f64 = d
        .windows(2)
        .map(|w| (w[1].translation() - w[0].translation()).norm())
        .sum();
    let mut summary = String::new();
    let name = match method {
        RigidMethod::ScLerp => "sclerp",
        RigidMethod::Squad => "squad",
        RigidMethod::Spring(_) => "spring",
    };
    let _ = writeln!(
        summary,
        "{name} (rigid) through {} ({} keys): {} frames, timing uniform{}",
        keys.source,
        rk.len(),
        frames.len(),
        if rk.times().is_some() {
            " (by key times)"
        } else {
            ""
        }
    );
    let _ = writeln!(
        summary,
        "screw energy      {:.4e}  (the dual-quaternion curve's curvature, length scale 1)",
        rigid_energy(&d, 1.0)
    );
    let _ = writeln!(summary, "path length       {path:.6}  (of the origin)");
    summary.push_str(&extra);
    let _ = write!(
        summary,
        "time              {:.3} ms",
        elapsed.as_secs_f64() * 1e3
    );
    Ok(RigidRun {
        frames,
        velocity,
        summary,
    })
}

/// CSV with the header `index,t,w,x,y,z,tx,ty,tz,velocity,key`.
pub fn to_csv(run: &RigidRun) -> String {
    frames_csv(COLUMNS, rows(run))
}

/// A JSON array of objects with the CSV's names.
pub fn to_json(run: &RigidRun) -> String {
    frames_json(COLUMNS, rows(run))
}

/// The columns of a frame between its index and its key.
const COLUMNS: [&str; 9] = ["t", "w", "x", "y", "z", "tx", "ty", "tz", "velocity"];

/// Each frame's numbers under [`COLUMNS`] (its rotation and translation), and its key.
fn rows(run: &RigidRun) -> impl Iterator<Item = ([f64; 9], Option<usize>)> + '_ {
    run.frames.iter().zip(&run.velocity).map(|(f, v)| {
        let (q, t) = (f.dq.real, f.dq.translation());
        ([f.t, q.w, q.x, q.y, q.z, t.x, t.y, t.z, *v], f.key)
    })
}

/// Runs `chasles interp --rigid` (the paths' extensions already checked).
pub fn run(args: &InterpArgs) -> Result<()> {
    let run = compute(args)?;
    if let Some(i) = run.frames.iter().position(|f| !f.dq.is_finite()) {
        bail!("frame {i} is {:?}, not finite", run.frames[i].dq.to_array());
    }
    if args.pictures.gif.is_some() && run.frames.len() > MAX_GIF_FRAMES {
        bail!(
            "--gif draws every frame: at most {MAX_GIF_FRAMES}, and this run has {} (ask for fewer --frames)",
            run.frames.len()
        );
    }
    let d: Vec<DualQuat<f64>> = run.frames.iter().map(|f| f.dq).collect();
    let keys: Vec<DualQuat<f64>> = run
        .frames
        .iter()
        .filter(|f| f.key.is_some())
        .map(|f| f.dq)
        .collect();
    let mut files = Pending::default();
    if let Some(p) = &args.pictures.gif {
        let frames = chasles_viz::rigid::animate(&keys, &d, 320);
        let n = frames.len();
        files.add(
            p,
            chasles_viz::gif(&frames, 4)?,
            Some(format!("{n} frames")),
        );
    }
    if let Some(p) = &args.pictures.render {
        let png = chasles_viz::rigid::path(&keys, &d, 8, (640, 480), "").png();
        files.add(p, png, Some(String::new()));
    }
    if let Some(out) = &args.out {
        let text = if extension(out) == "json" {
            to_json(&run)
        } else {
            to_csv(&run)
        };
        files.add(out, text.into_bytes(), None);
    }
    for line in files.write()? {
        eprintln!("{line}");
    }
    match &args.out {
        Some(out) => println!("{}\nwrote             {}", run.summary, out.display()),
        None => {
            print!("{}", to_csv(&run));
            eprintln!("{}", run.summary);
        }
    }
    Ok(())
}
