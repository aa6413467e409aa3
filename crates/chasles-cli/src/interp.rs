//! `chasles interp`: interpolate key frames with any of the report's methods (Dam et al.
//! 1998, chapters 5–7) or the curves past it (Kochanek–Bartels, Catmull–Rom, Bézier, the C²
//! spline), optionally as a camera path with a stable horizon, and write one row per frame.

use crate::choice::InterpMethod;
use crate::keyfile;
use crate::output::{check_frames_dir, extension, num, write_frames_dir, Pending};
use crate::picture_args::{Pictures, MAX_GIF_FRAMES};
use crate::spring_args::{configure, options, SolverArg, SpringArgs};
use anyhow::{bail, Context, Result};
use chasles::analysis::curvature::{curvature_energy, Width};
use chasles::analysis::velocity::velocity_chord;
use chasles::interp::horizon::{check_keys, level_frames};
use chasles::interp::tcb::check_parameter;
use chasles::interp::{
    interpolate, spring, Frame, Hemisphere, KeyFrames, Method, Solver, SpringConfig, Stopped, Tcb,
    Timing, Up,
};
use chasles::{EulerOrder, Quat};
use indicatif::{ProgressBar, ProgressStyle};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Options of `chasles interp`.
pub struct InterpArgs {
    /// The method.
    pub method: InterpMethod,
    /// Key file or `builtin:NAME`.
    pub keys: String,
    /// Frames in total (default 200, or the last of `--levels`).
    pub frames: Option<usize>,
    /// The ceiling on frames (`--max-frames`).
    pub max_frames: usize,
    /// Frame distribution.
    pub timing: Timing,
    /// Output file (.csv or .json); stdout CSV when absent.
    pub out: Option<PathBuf>,
    /// Keep the keys' signs instead of chaining hemispheres.
    pub keep_signs: bool,
    /// Spring's controls given on the command line.
    pub spring: SpringArgs,
    /// Kochanek–Bartels' parameters and the horizon.
    pub curve: CurveArgs,
    /// A folder for the frames as numbered PNGs.
    pub frames_dir: Option<PathBuf>,
    /// The pictures asked for (`--plot` SVG or PNG).
    pub pictures: Pictures,
    /// `--rigid` and its options.
    pub rigid: crate::interp_rigid::RigidArgs,
}

/// The world's up axis on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum HorizonArg {
    /// z up (yaw–pitch–roll intrinsic ZYX).
    #[value(name = "Z")]
    Z,
    /// y up (yaw–pitch–roll intrinsic YZX).
    #[value(name = "Y")]
    Y,
}

/// The options of the curves past the report: Kochanek–Bartels' parameters for every key
/// without its own, and a stable horizon.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct CurveArgs {
    /// Kochanek–Bartels tension in [-1, 1] (--method tcb; 1 stops at the keys, -1 doubles
    /// the tangents; a key's own `tension` in the key file wins).
    #[arg(long, allow_negative_numbers = true)]
    pub tension: Option<f64>,
    /// Kochanek–Bartels continuity in [-1, 1] (--method tcb; 0 is C1, -1 a corner).
    #[arg(long, allow_negative_numbers = true)]
    pub continuity: Option<f64>,
    /// Kochanek–Bartels bias in [-1, 1] (--method tcb; 1 follows the incoming chord, -1
    /// the outgoing one).
    #[arg(long, allow_negative_numbers = true)]
    pub bias: Option<f64>,
    /// A camera path with a stable horizon, any method: the keys are cameras looking along
    /// their x axis with this world axis up and no roll (yaw-pitch-roll intrinsic ZYX for Z,
    /// YZX for Y); every frame is turned about its viewing axis so that it does not roll.
    #[arg(long, value_enum, ignore_case = true)]
    pub horizon: Option<HorizonArg>,
}

impl CurveArgs {
    /// `--tension`, `--continuity`, `--bias` checked (each named in its error), 0 where
    /// not given.
    fn tcb(&self) -> Result<Tcb> {
        let mut t = Tcb::CATMULL_ROM;
        for (flag, v, slot) in [
            ("--tension", self.tension, &mut t.tension),
            ("--continuity", self.continuity, &mut t.continuity),
            ("--bias", self.bias, &mut t.bias),
        ] {
            if let Some(v) = v {
                if check_parameter("", v).is_err() {
                    bail!("{flag} must be a finite number in [-1, 1], got {v}");
                }
                *slot = v;
            }
        }
        Ok(t)
    }
    /// The flags given of Kochanek–Bartels'.
    fn tcb_given(&self) -> Option<&'static str> {
        [
            ("--tension", self.tension),
            ("--continuity", self.continuity),
            ("--bias", self.bias),
        ]
        .into_iter()
        .find_map(|(f, v)| v.map(|_| f))
    }
}

/// The up axis of a run: `--horizon`, else the key file's `horizon`; an error when they
/// differ, or when camera keys made with the file's axis (z when it names none) would be
/// levelled about another.
fn up_axis(arg: Option<HorizonArg>, keys: &keyfile::Keys) -> Result<Option<Up>> {
    let arg = arg.map(|h| match h {
        HorizonArg::Z => Up::Z,
        HorizonArg::Y => Up::Y,
    });
    match (arg, keys.horizon) {
        (Some(a), Some(f)) if a != f => bail!(
            "--horizon {} and the key file's horizon = \"{}\" differ ({})",
            a.name(),
            f.name(),
            keys.source
        ),
        (Some(a), None) if keys.cameras && a != Up::Z => bail!(
            "--horizon {}: the yaw/pitch keys of {} are cameras with z up (the file names no horizon); write horizon = \"{}\" in it",
            a.name(),
            keys.source,
            a.name()
        ),
        (a, f) => Ok(a.or(f)),
    }
}

/// Frames when neither `--frames` nor `--levels` says.
const DEFAULT_FRAMES: usize = 200;

enum Plan {
    Piecewise(Method),
    /// A Spring preset and the solver it runs unless told otherwise.
    Spring(SpringConfig, SolverArg),
}

/// What `method` runs; LinEuler in `order` (the keys' own when they were given as Euler
/// triples, else the report's).
fn plan(method: InterpMethod, order: EulerOrder) -> Plan {
    match method {
        InterpMethod::LinEuler => Plan::Piecewise(Method::LinEuler(order)),
        InterpMethod::LinMat => Plan::Piecewise(Method::LinMat),
        InterpMethod::Lerp => Plan::Piecewise(Method::Nlerp),
        InterpMethod::Slerp => Plan::Piecewise(Method::Slerp),
        InterpMethod::Squad => Plan::Piecewise(Method::Squad),
        InterpMethod::Spring => Plan::Spring(SpringConfig::spring(), SolverArg::Converged),
        InterpMethod::SlerpSvupti => Plan::Spring(SpringConfig::slerpsvupti(), SolverArg::Report),
        InterpMethod::SquadSvupti => Plan::Spring(SpringConfig::squadsvupti(), SolverArg::Report),
        InterpMethod::JustDoIt => Plan::Spring(SpringConfig::justdoit(), SolverArg::Report),
        InterpMethod::Tcb => Plan::Piecewise(Method::KochanekBartels(Tcb::CATMULL_ROM)),
        InterpMethod::CatmullRom => Plan::Piecewise(Method::CatmullRom),
        InterpMethod::Bezier => Plan::Piecewise(Method::Bezier),
        InterpMethod::C2 => Plan::Piecewise(Method::C2),
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
    if let Some(n) = args.frames.filter(|n| *n > args.max_frames) {
        bail!(
            "--frames {n} is more than --max-frames {} (raise it to make longer curves)",
            args.max_frames
        );
    }
    if let Some(flag) = args.rigid.stray() {
        bail!("{flag} applies to --rigid curves");
    }
    let keys = keyfile::load(&args.keys)?;
    if keys.poses.is_some() {
        bail!(
            "{}: the keys carry translations (translation, matrix or dq): interpolate them with --rigid",
            keys.source
        );
    }
    let hemisphere = if args.keep_signs {
        Hemisphere::AsGiven
    } else {
        Hemisphere::Chain
    };
    let kf = match &keys.euler {
        Some((order, triples)) => {
            KeyFrames::from_euler(*order, triples, keys.times.as_deref(), hemisphere)
        }
        None => KeyFrames::new(&keys.quats, keys.times.as_deref(), hemisphere),
    }
    .with_context(|| keys.source.clone())?;
    let kf = match &keys.velocities {
        Some(v) => {
            if !matches!(args.method, InterpMethod::Squad | InterpMethod::Spring) {
                bail!(
                    "{}: key velocities are honoured by squad and by spring (the converged solver), not by {}",
                    keys.source,
                    args.method.name()
                );
            }
            kf.with_velocities(v).with_context(|| keys.source.clone())?
        }
        None => kf,
    };
    let started = Instant::now();
    let mut extra = String::new();
    let up = up_axis(args.curve.horizon, &keys)?;
    if let Some(up) = up {
        check_keys(&kf, up).with_context(|| {
            format!(
                "{}: a camera path with a stable horizon ({} up)",
                keys.source,
                up.name()
            )
        })?;
    }
    let mut plan = plan(
        args.method,
        keys.euler.as_ref().map_or(EulerOrder::DAM, |e| e.0),
    );
    let kf = match (&mut plan, &keys.tcb) {
        (Plan::Piecewise(Method::KochanekBartels(p)), per_key) => {
            *p = args.curve.tcb()?;
            let own = per_key.as_ref().map_or(0, |k| {
                k.iter()
                    .filter(|k| k.tension.or(k.continuity).or(k.bias).is_some())
                    .count()
            });
            let _ = writeln!(
                extra,
                "tcb               tension {}, continuity {}, bias {} ({own} keys with their own)",
                p.tension, p.continuity, p.bias
            );
            match per_key {
                Some(k) => kf
                    .with_tcb(k.clone())
                    .with_context(|| keys.source.clone())?,
                None => kf,
            }
        }
        _ => {
            if let Some(flag) = args.curve.tcb_given() {
                bail!(
                    "{flag} is a Kochanek-Bartels control: it applies to tcb, not {}",
                    args.method.name()
                );
            }
            kf
        }
    };
    let mut n = args.frames.unwrap_or(DEFAULT_FRAMES);
    let frames = match plan {
        Plan::Piecewise(m) => {
            if let Some(flag) = args.spring.given().first() {
                bail!(
                    "{flag} is a Spring control: it applies to spring, slerpsvupti, squadsvupti and justdoit, not {}",
                    args.method.name()
                );
            }
            interpolate(m, &kf, n, args.timing)?
        }
        Plan::Spring(preset, solver) => {
            let (cfg, total) = configure(
                preset,
                solver,
                keys.spring.as_ref(),
                &args.spring,
                args.frames,
                DEFAULT_FRAMES,
                kf.len(),
            )
            .with_context(|| keys.source.clone())?;
            if total > args.max_frames {
                bail!(
                    "--levels asks for {total} frames, more than --max-frames {}",
                    args.max_frames
                );
            }
            n = total;
            let _ = writeln!(extra, "spring options    {}", options(&cfg, n, kf.len()));
            // At most MAX_ITERATIONS a step (checked): the sums cannot overflow.
            let total: usize = match cfg.solver {
                Solver::Converged { max_iterations, .. } => max_iterations,
                Solver::Report => cfg.levels.iter().map(|l| l.iterations).sum(),
            };
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
            let r = spring(&kf, n, args.timing, &cfg, &mut |p| {
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
            let _ = match cfg.solver {
                Solver::Converged { .. } => {
                    let (first, end) = (r.history.first(), r.history.last());
                    let fall = match (first, end) {
                        (Some(a), Some(b)) if a.gradient_norm > 0.0 => {
                            b.gradient_norm / a.gradient_norm
                        }
                        _ => 0.0,
                    };
                    writeln!(
                        extra,
                        "spring            converged solver: {iters} Newton steps, final F {last:.6e}, gradient {fall:.1e} of the start's ({})",
                        match r.stopped {
                            Stopped::Converged => "converged",
                            Stopped::Rounding => "stopped at f64's rounding",
                            Stopped::MaxIterations => "iteration cap reached",
                            Stopped::LevelsDone => "levels done",
                        }
                    )
                }
                Solver::Report => writeln!(
                    extra,
                    "spring            {iters} iterations over {} levels, final F {last:.4e}",
                    cfg.levels.len()
                ),
            };
            r.frames
        }
    };
    let mut frames = frames;
    if let Some(up) = up {
        let removed = level_frames(&mut frames, up);
        let _ = writeln!(
            extra,
            "horizon           {} up: every frame turned about its viewing axis to roll 0 (the method's frames rolled up to {:.4}°)",
            up.name(),
            removed.to_degrees()
        );
    }
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
    frames_csv(COLUMNS, rows(run))
}

/// A JSON array of objects with the CSV's names (key: index or null).
pub fn to_json(run: &Run) -> String {
    frames_json(COLUMNS, rows(run))
}

/// The columns of a frame between its index and its key.
const COLUMNS: [&str; 6] = ["t", "w", "x", "y", "z", "velocity"];

/// Each frame's numbers under [`COLUMNS`], and its key.
fn rows(run: &Run) -> impl Iterator<Item = ([f64; 6], Option<usize>)> + '_ {
    let frames = run.frames.iter().zip(&run.velocity);
    frames.map(|(f, v)| ([f.t, f.q.w, f.q.x, f.q.y, f.q.z, *v], f.key))
}

/// Frames as CSV, for `chasles interp` and `interp --rigid` alike: the header
/// `index,<columns>,key`, then a row a frame — its index, its numbers ([`num`]) and its key
/// index (empty where it is no key).
pub(crate) fn frames_csv<const N: usize>(
    columns: [&str; N],
    rows: impl Iterator<Item = ([f64; N], Option<usize>)>,
) -> String {
    let mut s = format!("index,{},key\n", columns.join(","));
    for (i, (cols, key)) in rows.enumerate() {
        let key = key.map_or(String::new(), |k| k.to_string());
        let _ = writeln!(s, "{i},{},{key}", cols.map(num).join(","));
    }
    s
}

/// The rows of [`frames_csv`] as a JSON array of objects with the CSV's names, in its order
/// (key: the key index, or null).
pub(crate) fn frames_json<const N: usize>(
    columns: [&str; N],
    rows: impl Iterator<Item = ([f64; N], Option<usize>)>,
) -> String {
    let rows: Vec<serde_json::Value> = rows
        .enumerate()
        .map(|(i, (cols, key))| {
            let mut o = serde_json::Map::new();
            o.insert("index".into(), i.into());
            for (c, v) in columns.iter().zip(cols) {
                o.insert((*c).into(), v.into());
            }
            o.insert("key".into(), key.into());
            o.into()
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
    if args.rigid.rigid {
        return crate::interp_rigid::run(&args);
    }
    if let Some(dir) = &args.frames_dir {
        check_frames_dir("--frames-dir", dir)?;
    }
    let run = compute(&args)?;
    // Nothing silent: every frame and velocity finite, or the run fails naming the first.
    if let Some(i) = run.frames.iter().position(|f| !f.q.is_finite()) {
        bail!("frame {i} is {:?}, not finite", run.frames[i].q.to_array());
    }
    if let Some(i) = run.velocity.iter().position(|v| !v.is_finite()) {
        bail!(
            "the velocity at frame {i} is {}, not finite",
            run.velocity[i]
        );
    }
    if args.pictures.gif.is_some() && run.frames.len() > MAX_GIF_FRAMES {
        bail!(
            "--gif draws every frame: at most {MAX_GIF_FRAMES}, and this run has {} (ask for fewer --frames)",
            run.frames.len()
        );
    }
    // Every picture made before any is written: a failure leaves none behind.
    let mut files = Pending::default();
    if let Some(p) = &args.pictures.plot {
        let keys = chasles_viz::graph::key_indices(&run.frames);
        let title = format!(
            "{} through {}: angular velocity (Dam et al. eq. 5.1)",
            args.method.name(),
            args.keys
        );
        let bytes = if extension(p) == "png" {
            chasles_viz::graph::velocity_png(&run.velocity, &keys, 900, 420).png()
        } else {
            chasles_viz::graph::velocity_svg(&run.velocity, &keys, &title).into_bytes()
        };
        files.add(p, bytes, Some(String::new()));
    }
    if let Some(p) = &args.pictures.sphere {
        let img = chasles_viz::sphere::render_frames(&run.frames, 600);
        files.add(p, img.png(), Some(String::new()));
    }
    // The frames as rotations: a non-unit frame (raw Lerp) is shown by its rotation.
    let turned: Vec<Quat<f64>> = run
        .frames
        .iter()
        .map(|f| f.q.normalize().unwrap_or(Quat::identity()))
        .collect();
    if let Some(p) = &args.pictures.gif {
        let frames = chasles_viz::letter::animate(&turned, 240);
        let n = frames.len();
        files.add(
            p,
            chasles_viz::gif(&frames, 4)?,
            Some(format!("{n} frames")),
        );
    }
    if let Some(p) = &args.pictures.render {
        let png = chasles_viz::letter::strip(&turned, 8, 180).png();
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
    // The other outputs are written all or none, after the frames are made and before
    // they are moved into place: one failure leaves nothing.
    let mut said = Vec::new();
    match &args.frames_dir {
        Some(dir) => {
            write_frames(dir, &turned, || {
                said = files.write()?;
                Ok(())
            })?;
            eprintln!("wrote {} ({} frames)", dir.display(), turned.len());
        }
        None => said = files.write()?,
    }
    for line in said {
        eprintln!("{line}");
    }
    match &args.out {
        Some(out) => {
            println!("{}\nwrote             {}", run.summary, out.display());
        }
        None => {
            print!("{}", to_csv(&run));
            eprintln!("{}", run.summary);
        }
    }
    Ok(())
}

/// Every frame as `frame-NNNN.png` (the R turned by it, 240 pixels, its number in the
/// corner), written all or nothing into `dir` ([`write_frames_dir`]), `then` before the
/// frames are moved into place.
fn write_frames(dir: &Path, turned: &[Quat<f64>], then: impl FnOnce() -> Result<()>) -> Result<()> {
    let digits = turned.len().saturating_sub(1).to_string().len().max(4);
    write_frames_dir(
        dir,
        turned.len(),
        "frames",
        |i| {
            let png = chasles_viz::letter::draw(turned[i], &i.to_string(), 240).png();
            Ok((format!("frame-{i:0digits$}.png"), png))
        },
        then,
    )
}
