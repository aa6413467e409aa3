//! `chasles interp`: interpolate key frames with any of the report's methods (Dam et al.
//! 1998, chapters 5–7) and write one row per frame.

use crate::choice::InterpMethod;
use crate::keyfile;
use crate::output::{extension, num, write_atomic};
use crate::picture_args::Pictures;
use anyhow::{bail, Context, Result};
use chasles::analysis::curvature::{curvature_energy, Width};
use chasles::analysis::velocity::velocity_chord;
use chasles::interp::{
    interpolate, spring, Frame, Hemisphere, KeyFrames, Method, SpringConfig, Timing,
};
use chasles::{EulerOrder, Quat};
use indicatif::{ProgressBar, ProgressStyle};
use serde_json::json;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

/// Options of `chasles interp`.
pub struct InterpArgs {
    /// The method.
    pub method: InterpMethod,
    /// Key file or `builtin:NAME`.
    pub keys: String,
    /// Frames in total.
    pub frames: usize,
    /// Frame distribution.
    pub timing: Timing,
    /// Output file (.csv or .json); stdout CSV when absent.
    pub out: Option<PathBuf>,
    /// Keep the keys' signs instead of chaining hemispheres.
    pub keep_signs: bool,
    /// Override of the Spring key-frame weight c_k.
    pub key_weight: Option<f64>,
    /// Override of the Spring constant-velocity weight c_w.
    pub velocity_weight: Option<f64>,
    /// The pictures asked for (`--plot` SVG or PNG).
    pub pictures: Pictures,
}

enum Plan {
    Piecewise(Method),
    Spring(SpringConfig),
}

fn plan(method: InterpMethod) -> Plan {
    match method {
        InterpMethod::LinEuler => Plan::Piecewise(Method::LinEuler(EulerOrder::DAM)),
        InterpMethod::LinMat => Plan::Piecewise(Method::LinMat),
        InterpMethod::Lerp => Plan::Piecewise(Method::Nlerp),
        InterpMethod::Slerp => Plan::Piecewise(Method::Slerp),
        InterpMethod::Squad => Plan::Piecewise(Method::Squad),
        InterpMethod::Spring => Plan::Spring(SpringConfig::spring()),
        InterpMethod::SlerpSvupti => Plan::Spring(SpringConfig::slerpsvupti()),
        InterpMethod::SquadSvupti => Plan::Spring(SpringConfig::squadsvupti()),
        InterpMethod::JustDoIt => Plan::Spring(SpringConfig::justdoit()),
    }
}

/// The result of a run, ready to write.
pub struct Run {
    /// The frames.
    pub frames: Vec<Frame<f64>>,
    /// Eq. 5.1 per frame.
    pub velocity: Vec<f64>,
    /// Summary lines.
    pub summary: String,
}

/// Computes the curve and its summary.
pub fn compute(args: &InterpArgs) -> Result<Run> {
    let plan = plan(args.method);
    let keys = keyfile::load(&args.keys)?;
    let hemisphere = if args.keep_signs {
        Hemisphere::AsGiven
    } else {
        Hemisphere::Chain
    };
    let kf = KeyFrames::new(&keys.quats, keys.times.as_deref(), hemisphere)
        .with_context(|| keys.source.clone())?;
    let started = Instant::now();
    let mut extra = String::new();
    let frames = match plan {
        Plan::Piecewise(m) => interpolate(m, &kf, args.frames, args.timing)?,
        Plan::Spring(mut cfg) => {
            if let Some(c) = args.key_weight {
                cfg.key_weight = c;
            }
            if let Some(c) = args.velocity_weight {
                cfg.velocity_penalty = c;
            }
            let total: usize = cfg.levels.iter().map(|l| l.iterations).sum();
            let bar = ProgressBar::new(total as u64);
            bar.set_style(
                ProgressStyle::with_template(
                    "{prefix} [{bar:30}] {pos}/{len} iterations  F = {msg}",
                )
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            bar.set_prefix(args.method.name());
            let mut done_before = 0usize;
            let mut level_seen = 0usize;
            let mut level_iters = 0usize;
            let r = spring(&kf, args.frames, args.timing, &cfg, &mut |p| {
                if p.level != level_seen {
                    done_before += level_iters;
                    level_seen = p.level;
                }
                level_iters = p.iterations;
                bar.set_position((done_before + p.iteration) as u64);
                bar.set_message(format!(
                    "{:.4e} (level {}/{})",
                    p.energy,
                    p.level + 1,
                    p.levels
                ));
            })?;
            bar.finish_and_clear();
            let last = r.history.last().map_or(0.0, |h| h.energy);
            let iters = r.history.iter().filter(|h| h.iteration > 0).count();
            let _ = writeln!(
                extra,
                "spring            {iters} iterations over {} levels, final F {last:.4e}",
                cfg.levels.len()
            );
            r.frames
        }
    };
    let elapsed = started.elapsed();
    let q: Vec<Quat<f64>> = frames.iter().map(|f| f.q).collect();
    let velocity = velocity_chord(&q);
    let inner = if velocity.len() > 2 {
        &velocity[1..velocity.len() - 1]
    } else {
        &velocity[..]
    };
    let (vmin, vmax) = inner
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), v| (a.min(*v), b.max(*v)));
    let mut summary = String::new();
    let _ = writeln!(
        summary,
        "{} through {} ({} keys): {} frames, timing {}",
        args.method.name(),
        keys.source,
        kf.len(),
        frames.len(),
        match args.timing {
            Timing::Uniform => "uniform",
            Timing::Angle => "angle",
        }
    );
    let _ = writeln!(
        summary,
        "curvature energy  {:.4e}  (eq. 6.23 with l = 1)",
        curvature_energy(&q, Width::Unit)
    );
    let _ = writeln!(
        summary,
        "velocity          min {vmin:.6}  max {vmax:.6}  (eq. 5.1, first and last frame left out)"
    );
    summary.push_str(&extra);
    let _ = write!(
        summary,
        "time              {:.3} ms",
        elapsed.as_secs_f64() * 1e3
    );
    Ok(Run {
        frames,
        velocity,
        summary,
    })
}

/// CSV with the header `index,t,w,x,y,z,velocity,key` (key: the key index, or empty).
pub fn to_csv(run: &Run) -> String {
    let mut s = String::from("index,t,w,x,y,z,velocity,key\n");
    for (i, (f, v)) in run.frames.iter().zip(&run.velocity).enumerate() {
        let key = f.key.map_or(String::new(), |k| k.to_string());
        let cols = [f.t, f.q.w, f.q.x, f.q.y, f.q.z, *v].map(num);
        let _ = writeln!(s, "{i},{},{key}", cols.join(","));
    }
    s
}

/// A JSON array of objects with the CSV's names (key: index or null).
pub fn to_json(run: &Run) -> String {
    let rows: Vec<_> = run
        .frames
        .iter()
        .zip(&run.velocity)
        .enumerate()
        .map(|(i, (f, v))| {
            json!({"index": i, "t": f.t, "w": f.q.w, "x": f.q.x, "y": f.q.y, "z": f.q.z, "velocity": v, "key": f.key})
        })
        .collect();
    serde_json::to_string_pretty(&rows).unwrap_or_else(|_| "[]".into())
}

/// Runs the command.
pub fn run(args: InterpArgs) -> Result<()> {
    if let Some(out) = &args.out {
        let ext = extension(out);
        if ext != "csv" && ext != "json" {
            bail!("--out must end in .csv or .json, got {}", out.display());
        }
    }
    args.pictures.check(&["svg", "png"])?;
    let run = compute(&args)?;
    if let Some(p) = &args.pictures.plot {
        let keys = chasles_viz::graph::key_indices(&run.frames);
        let title = format!(
            "{} through {}: angular velocity (Dam et al. eq. 5.1)",
            args.method.name(),
            args.keys
        );
        if extension(p) == "png" {
            let img = chasles_viz::graph::velocity_png(&run.velocity, &keys, 900, 420);
            write_atomic(p, &img.png())?;
        } else {
            let svg = chasles_viz::graph::velocity_svg(&run.velocity, &keys, &title);
            write_atomic(p, svg.as_bytes())?;
        }
        eprintln!("wrote {}", p.display());
    }
    if let Some(p) = &args.pictures.sphere {
        let img = chasles_viz::sphere::render_frames(&run.frames, 600);
        write_atomic(p, &img.png())?;
        eprintln!("wrote {}", p.display());
    }
    // The frames as rotations: a non-unit frame (raw Lerp) is shown by its rotation.
    let turned: Vec<Quat<f64>> = run
        .frames
        .iter()
        .map(|f| f.q.normalize().unwrap_or(Quat::identity()))
        .collect();
    if let Some(p) = &args.pictures.gif {
        let frames = chasles_viz::letter::animate(&turned, 240);
        write_atomic(p, &chasles_viz::gif(&frames, 4)?)?;
        eprintln!("wrote {} ({} frames)", p.display(), frames.len());
    }
    if let Some(p) = &args.pictures.render {
        write_atomic(p, &chasles_viz::letter::strip(&turned, 8, 180).png())?;
        eprintln!("wrote {}", p.display());
    }
    match &args.out {
        Some(out) => {
            let text = if extension(out) == "json" {
                to_json(&run)
            } else {
                to_csv(&run)
            };
            write_atomic(out, text.as_bytes())?;
            println!("{}\nwrote             {}", run.summary, out.display());
        }
        None => {
            print!("{}", to_csv(&run));
            eprintln!("{}", run.summary);
        }
    }
    Ok(())
}
