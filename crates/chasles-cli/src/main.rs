//! The `chasles` command-line tool.
//!
//! * `chasles tour` — the main job: a walk through both papers on built-in data (the
//!   characters included), written as one HTML page.
//! * `chasles convert` — one rotation or rigid motion between representations
//!   (Dam et al. 1998, App. B; Kavan et al. 2006, §3).
//! * `chasles interp` — key-frame interpolation (Dam et al. 1998, chapters 5–7).
//! * `chasles average` — the mean of measured rigid poses, plain (DIB) or robust
//!   (Kavan et al. 2006, §7).
//! * `chasles blend`, `chasles properties` — blending of rigid transformations and the
//!   measured Table 1 (Kavan et al. 2006, §4–5).
//! * `chasles skin` — skinning a glTF or JSON rig with any method, on the CPU or the GPU,
//!   to meshes, pictures and benchmarks (Kavan et al. 2006, §6).
//! * `chasles view` — one self-contained HTML page showing a rig (or the twisted cylinder)
//!   skinned by LBS and DQS in the browser, WebGL2 (Kavan et al. 2006, §6).
//! * `chasles clip blend`, `chasles clip compress` — clips made anew: two blended per joint
//!   by DLB, one compressed to a vertex tolerance (Kavan et al. 2006, §7).
//!
//! Output piped into a program that stops reading (`chasles interp … | head -1`) ends the
//! process quietly, as it does for other Unix tools: SIGPIPE is restored to its default.

#![forbid(unsafe_code)]

mod average;
mod blend;
mod blend_case;
mod blend_pictures;
mod choice;
mod cleanup;
mod clip;
mod convert;
mod device;
mod interp;
mod interp_rigid;
mod json;
mod keyfile;
mod output;
mod picture_args;
mod pictures;
mod properties;
mod report;
mod repr;
mod skin;
mod spring_args;
mod tour;
mod view;

use clap::{Parser, Subcommand};
use repr::Repr;

#[derive(Parser)]
#[command(
    name = "chasles",
    version,
    about = "Rotations and rigid motions: quaternions, dual quaternions, interpolation and blending"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Walk through the papers on built-in data, printing computed numbers.
    Tour {
        /// Random inputs per identity in the closing sweep (1 to 10⁷).
        #[arg(long, default_value_t = 10_000, value_parser = samples_in_range)]
        samples: usize,
        /// Seed of the random inputs.
        #[arg(long, default_value_t = 1998)]
        seed: u64,
        /// Folder for the report (index.html and its pictures).
        #[arg(long, default_value = "report")]
        out: std::path::PathBuf,
    },
    /// Interpolate key frames: LinEuler, LinMat, Lerp, Slerp, Squad, Spring (Dam et al. 1998),
    /// Kochanek–Bartels, Catmull–Rom, Bézier, a C² spline; cameras with a stable horizon.
    ///
    /// Writes one row per frame — index,t,w,x,y,z,velocity,key — to --out (.csv or .json) or
    /// as CSV to stdout, and a summary (curvature energy, velocity range, time) to the
    /// terminal. Every key frame is one of the rows, its index in `key`. Key files: TOML or
    /// JSON with keys as {angle, axis}, {quat = [w,x,y,z]} or {euler, order}, optional time
    /// on every key, and an optional [spring] table of the Spring options below (names with
    /// _ for -); or builtin:NAME with NAME one of table5.1, semicircle, soft, cusp,
    /// pendulum, perturbed, global. LinEuler interpolates keys given as Euler triples as
    /// given (eq. 6.1). The summary prints the Spring options a run used: the presets are
    /// named sets of them. Keys may carry their own tension, continuity and bias for tcb,
    /// or be cameras {yaw, pitch} (radians, with the file's `horizon = "Z"|"Y"` up, z when
    /// it names none); --horizon (or the file's horizon) levels every frame of any method.
    ///
    /// Examples:
    ///   chasles interp --method squad --keys builtin:table5.1 --frames 550 --out squad.csv
    ///   chasles interp --method spring --keys keys.toml --frames 200 --out spring.json
    ///   chasles interp --method slerpsvupti --keys builtin:table5.1 --levels 350 \
    ///       --iterations 500 --frames-dir frames/     (Figure 6.15, as the tour makes it)
    ///   chasles interp --method tcb --tension 0.3 --bias=-0.5 --keys builtin:table5.1
    ///   chasles interp --method c2 --keys camera.toml --horizon Z --out path.csv
    ///   chasles interp --rigid --method squad --keys poses.toml --gif moving.gif
    ///       (keys with a translation, matrix or dq; sclerp, squad or spring; rows gain
    ///       tx,ty,tz)
    #[command(verbatim_doc_comment)]
    Interp {
        /// The method, by its name in the report and App. C.
        #[arg(long, value_enum)]
        method: choice::InterpMethod,
        /// Key file (.toml or .json) or builtin:NAME.
        #[arg(long)]
        keys: String,
        /// Frames in total, keys included (default 200, or the last of --levels).
        #[arg(long)]
        frames: Option<usize>,
        /// The most frames a run may make (a ceiling against runaway sizes; raise it for
        /// longer curves: each frame takes about 64 bytes).
        #[arg(long, default_value_t = 1_000_000)]
        max_frames: usize,
        /// Frames per interval: uniform (or by key times), or by the interval's angle (§6.2).
        #[arg(long, value_enum, default_value_t = TimingArg::Angle)]
        timing: TimingArg,
        /// Output file, .csv or .json (default: CSV on stdout).
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        /// Keep the keys' signs (q vs −q) instead of bringing each into the previous key's hemisphere.
        #[arg(long)]
        keep_signs: bool,
        #[command(flatten)]
        spring: spring_args::SpringArgs,
        #[command(flatten)]
        curve: interp::CurveArgs,
        /// Also write every frame as a numbered PNG of the turned R (frame-0000.png, …) into
        /// this new or empty folder, like the report's program's frame dumps (App. C).
        #[arg(long, value_name = "DIR")]
        frames_dir: Option<std::path::PathBuf>,
        #[command(flatten)]
        pictures: picture_args::Pictures,
        #[command(flatten)]
        rigid: interp_rigid::RigidArgs,
    },
    /// Blend rigid transformations: lin, dec, log, log-iter, qlb, sclerp, dlb, dib (Kavan et al. 2006).
    ///
    /// Input (a file or - for stdin): one JSON case or an array of cases,
    /// {"transforms": [T, ...], "weights": [w, ...]} — optional "center" [x,y,z] (dec, qlb),
    /// "precision" and "max_iterations" (dec, log-iter, dib) — or for sclerp
    /// {"from": T, "to": T, "t": x}. T is {"rotation": [w,x,y,z], "translation": [x,y,z]},
    /// {"matrix": [[...4 rows...]]} (row-major) or {"dq": [8 numbers]}. Weights must be
    /// non-negative with a positive sum; they are scaled to sum to 1. Output: a JSON array,
    /// per case rotation, translation, matrix, dq, rigid (and iterations where the method
    /// iterates, with capped: true when it ran all max_iterations updates).
    #[command(verbatim_doc_comment)]
    Blend {
        /// The blending method.
        #[arg(long, value_enum)]
        method: choice::BlendMethod,
        /// JSON file, or - for stdin.
        #[arg(long)]
        input: String,
        #[command(flatten)]
        pictures: picture_args::Pictures,
    },
    /// Average measured rigid poses: DIB's rigid mean, or a robust mean (Kavan et al. 2006, §7).
    ///
    /// Input (a file or - for stdin): {"poses": [T, ...], "weights": [w, ...]} (weights
    /// optional) or just the array of poses; T is {"rotation": [w,x,y,z], "translation":
    /// [x,y,z]}, {"matrix": [[...4 rows...]]} (row-major), {"dq": [8 numbers]} or any other
    /// object form of convert --jsonl. Output: one JSON object with rotation, translation,
    /// matrix, dq, iterations (and for --robust: scale, weights, distances, outliers).
    /// --robust reweights the poses by their distance to the mean (turn in radians and move
    /// over --length-scale, in quadrature) with Huber's or Tukey's weights, the scale 1.4826
    /// x the median distance unless --scale fixes it; the start is the pose of least median
    /// distance to the others.
    ///
    /// Examples:
    ///   chasles average --input poses.json
    ///   chasles average --input poses.json --robust tukey --out mean.json
    #[command(verbatim_doc_comment)]
    Average(average::AverageArgs),
    /// Measure Kavan et al.'s Table 1 on random inputs, with exact FLOP counts (and --claims).
    Properties {
        /// Random cases per property (1 to 10⁷).
        #[arg(long, default_value_t = 200, value_parser = samples_in_range)]
        samples: usize,
        /// Seed of the random cases.
        #[arg(long, default_value_t = 2006)]
        seed: u64,
        /// md or json.
        #[arg(long, value_enum, default_value_t = FormatArg::Md)]
        format: FormatArg,
        /// Also reproduce the paper's claims: DLB vs ScLERP bounds, Lemmas 2–3, DIB updates, Figure 7.
        #[arg(long)]
        claims: bool,
    },
    /// Skin a rigged mesh (lbs, dqs, dib, log, qlb, sbs), one pose or a whole clip (Kavan et al. 2006, §6).
    ///
    /// Examples:
    ///   chasles skin --rig Fox.glb --anim Run --time 0.4 --method dqs --out fox.obj
    ///   chasles skin --rig CesiumMan.glb --all-frames --fps 24 --method lbs --out frames/
    ///   chasles skin --artifacts      (the candy-wrapper table on a twisted cylinder)
    #[command(verbatim_doc_comment)]
    Skin(skin::SkinArgs),
    /// Write one self-contained HTML page showing a rig skinned by LBS and DQS, live (WebGL2).
    ///
    /// The page embeds the mesh, its skin and every clip sampled into per-frame joint
    /// palettes; JavaScript and shaders inline, no network, no server: open it by
    /// double-click. LBS and DQS side by side or one at a time, a clip scrubber, play/pause,
    /// speed, a heat map of LBS's volume loss, orbit/pan/zoom, the model's credits. The URL
    /// fragment sets the state: #method=lbs|dqs|both&clip=NAME&time=T&heat=1 (and
    /// twist=DEG&bend=DEG for --artifacts).
    ///
    /// Examples:
    ///   chasles view CesiumMan.glb --out cesiumman.html
    ///   chasles view Fox.glb --clip Run --out fox.html
    ///   chasles view --artifacts --out cylinder.html   (the candy wrapper, twist and bend sliders)
    #[command(verbatim_doc_comment)]
    View(view::ViewArgs),
    /// Make clips of a rig: blend two per joint by DLB, or compress one to a vertex tolerance (Kavan et al. 2006, §7).
    #[command(subcommand)]
    Clip(clip::ClipCommand),
    /// Convert one rotation or rigid motion between representations.
    ///
    /// Representations: quat (w x y z), matrix (9 or 16 numbers, row-major), matrix3,
    /// matrix4, euler:ORDER (three angles in radians; lower-case order = extrinsic/fixed axes,
    /// e.g. euler:xyz is Dam et al.'s R = Rz(γ)Ry(β)Rx(α); upper-case = intrinsic, e.g.
    /// euler:ZYX), axis-angle (ax ay az angle), rotvec (axis·angle), rt (rotation then
    /// translation: w x y z tx ty tz), dq (unit dual quaternion: w x y z we xe ye ze),
    /// screw (ax ay az px py pz angle translation: axis direction, a point on it, the turn and
    /// the slide). Quaternions print as [w, x, y, z].
    ///
    /// Examples:
    ///   chasles convert --from euler:xyz --to quat 0.1 0.2 0.3
    ///   chasles convert --from rt --to dq -- 1 0 0 0 -1 2 3
    ///   echo '{"quat": [0, 1, 0, 0]}' | chasles convert --jsonl --to matrix
    #[command(verbatim_doc_comment)]
    Convert {
        /// Input representation (needed for numbers and bare JSON arrays).
        #[arg(long, value_parser = parse_repr)]
        from: Option<Repr>,
        /// Output representation.
        #[arg(long, value_parser = parse_repr)]
        to: Repr,
        /// Read one JSON value per line from stdin, write one JSON result per line.
        #[arg(long)]
        jsonl: bool,
        /// Print numbers with this many decimals, 0 to 17 (default: shortest exact form).
        #[arg(long, value_parser = clap::value_parser!(u8).range(0..=17))]
        precision: Option<u8>,
        /// The numbers (negative ones are fine, or put them after `--`).
        #[arg(allow_negative_numbers = true, num_args = 0..)]
        values: Vec<String>,
    },
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum FormatArg {
    Md,
    Json,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum TimingArg {
    Uniform,
    Angle,
}

fn parse_repr(s: &str) -> Result<Repr, String> {
    s.parse().map_err(|e: anyhow::Error| e.to_string())
}

fn main() {
    // Rust ignores SIGPIPE, which turns a closed pipe into a panic in println!.
    sigpipe::reset();
    cleanup::install();
    device::quiet_vulkan_loader();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => e.exit(), // --help, --version
        Err(e) => {
            // One line naming the problem (and the choices, for a bad value); clap's usage
            // hint would make it three.
            let text = e.render().to_string();
            let mut line = text
                .lines()
                .next()
                .unwrap_or("error: bad arguments")
                .to_string();
            if let Some(choices) = text
                .lines()
                .find(|l| l.trim_start().starts_with("[possible values"))
            {
                line = format!("{line} {}", choices.trim());
            }
            eprintln!("{line}");
            std::process::exit(2);
        }
    };
    // A panic is a bug of ours: one line naming it and the command, and its own exit code
    // (70, EX_SOFTWARE), never a backtrace in the user's face nor exit 101.
    std::panic::set_hook(Box::new(|info| {
        let args: Vec<String> = std::env::args().skip(1).collect();
        let at = info
            .location()
            .map_or(String::new(), |l| format!(" at {}:{}", l.file(), l.line()));
        let what = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_default();
        eprintln!(
            "internal error{at}: {what} (chasles {}; please report it with this input)",
            args.join(" ")
        );
    }));
    let result =
        std::panic::catch_unwind(|| run(cli)).unwrap_or_else(|_| std::process::exit(INTERNAL));
    match result {
        Ok(code) => std::process::exit(code),
        Err(e) => {
            if cleanup::stopping() {
                // Stopped: the handler's exit 130 and message, not this error.
                cleanup::await_exit();
            }
            eprintln!("error: {e:#}");
            std::process::exit(2);
        }
    }
}

/// A count of random samples: 1 to 10⁷ (a ceiling: 10⁷ identities take minutes already).
fn samples_in_range(s: &str) -> Result<usize, String> {
    let n: usize = s
        .parse()
        .map_err(|_| format!("'{s}' is not a whole number"))?;
    if (1..=10_000_000).contains(&n) {
        Ok(n)
    } else {
        Err(format!("{n} is not in 1..=10000000"))
    }
}

/// The exit code of an internal error (a panic): 70, EX_SOFTWARE of sysexits.h.
const INTERNAL: i32 = 70;

/// Runs the command; returns the exit code.
fn run(cli: Cli) -> anyhow::Result<i32> {
    match cli.command {
        Command::Tour { samples, seed, out } => {
            tour::run(tour::TourArgs { samples, seed, out }).map(|_| 0)
        }
        Command::Skin(args) => skin::run(args).map(|_| 0),
        Command::View(args) => view::run(args).map(|_| 0),
        Command::Average(args) => average::run(args).map(|_| 0),
        Command::Clip(cmd) => clip::run(cmd).map(|_| 0),
        Command::Blend {
            method,
            input,
            pictures,
        } => blend::run(method.0, &input, &pictures).map(|_| 0),
        Command::Properties {
            samples,
            seed,
            format,
            claims,
        } => properties::run(
            samples,
            seed,
            match format {
                FormatArg::Md => properties::Format::Markdown,
                FormatArg::Json => properties::Format::Json,
            },
            claims,
        )
        .map(|_| 0),
        Command::Interp {
            method,
            keys,
            frames,
            max_frames,
            timing,
            out,
            keep_signs,
            spring,
            curve,
            frames_dir,
            pictures,
            rigid,
        } => interp::run(interp::InterpArgs {
            method,
            keys,
            frames,
            max_frames,
            timing: match timing {
                TimingArg::Uniform => chasles::interp::Timing::Uniform,
                TimingArg::Angle => chasles::interp::Timing::Angle,
            },
            out,
            keep_signs,
            spring,
            curve,
            frames_dir,
            pictures,
            rigid,
        })
        .map(|_| 0),
        Command::Convert {
            from,
            to,
            jsonl,
            precision,
            values,
        } => convert::run(convert::ConvertArgs {
            from,
            to,
            values,
            jsonl,
            precision: precision.map(usize::from),
        }),
    }
}
