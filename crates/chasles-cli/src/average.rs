//! `chasles average`: the mean of measured rigid poses (Kavan et al. 2006, §7: averaging
//! measured positions and orientations), plain ([`chasles::blend::average::mean`], DIB's
//! fixed point) or robust ([`chasles::blend::average::robust_mean`], Huber or Tukey).
//!
//! Input (a file or `-` for stdin): `{"poses": [T, …], "weights"?: [w, …]}` or just the
//! array of poses; a pose T is any object form of `chasles convert --jsonl`
//! ([`crate::repr::MotionFields`]): `{"rotation": [w,x,y,z], "translation": [x,y,z]}`,
//! `{"matrix": …}`, `{"dq": [8 numbers]}`, …. Errors name the path of the bad field
//! (`poses[3].rotation`). Output: one JSON object — `rotation`, `translation`, `matrix`,
//! `dq`, `method`, `iterations`, `capped`, and for the robust means `scale`, `weights` (the
//! final ones, summing to 1), `distances` (each pose's to the mean) and `outliers` (the
//! poses whose weight fell to 0) — on stdout or, written whole or not at all, to `--out`.

use crate::json::{from_json, FieldError};
use crate::output::{extension, Pending};
use crate::repr::MotionObject;
use anyhow::{anyhow, bail, Context, Result};
use chasles::blend::average::{mean, robust_mean, Loss, Robust, Scale};
use chasles::blend::Options;
use chasles::DualQuat;
use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
use serde::de::{Deserializer, MapAccess, SeqAccess, Visitor};
use serde::Deserialize;
use serde_json::json;
use std::fmt;
use std::path::PathBuf;

/// The robust loss on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum RobustArg {
    /// Huber: outliers count linearly, not quadratically.
    Huber,
    /// Tukey's biweight: outliers past c·s are ignored.
    Tukey,
}

/// Options of `chasles average`.
#[derive(clap::Args, Clone, Debug)]
pub struct AverageArgs {
    /// JSON file, or - for stdin.
    #[arg(long)]
    pub input: String,
    /// A robust mean that ignores outliers (iteratively reweighted DIB).
    #[arg(long, value_enum)]
    pub robust: Option<RobustArg>,
    /// The robust loss's tuning constant c (default 1.345 for huber, 4.685 for tukey).
    #[arg(long, allow_negative_numbers = true)]
    pub tuning: Option<f64>,
    /// A fixed scale s for the robust weights (default: 1.4826 × the median distance,
    /// re-estimated at every step).
    #[arg(long, allow_negative_numbers = true)]
    pub scale: Option<f64>,
    /// The length that weighs as much as one radian in the robust distance (default 1).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub length_scale: f64,
    /// Stop when an update is smaller than this.
    #[arg(long, allow_negative_numbers = true)]
    pub precision: Option<f64>,
    /// At most this many updates (up to 10000; default 50, robust 200).
    #[arg(long)]
    pub max_iterations: Option<usize>,
    /// Write the JSON here (.json) instead of stdout.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// The input as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Doc {
    /// The poses.
    poses: Vec<MotionObject>,
    /// One weight per pose.
    #[serde(default)]
    weights: Option<Vec<f64>>,
}

/// The input: a [`Doc`] or just its array of poses (the path into either kept).
struct Input(Doc);

impl<'de> Deserialize<'de> for Input {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        /// An object or an array of poses.
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Input;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("an object {\"poses\": [...], \"weights\": [...]} or an array of poses")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Input, A::Error> {
                let poses = Vec::deserialize(SeqAccessDeserializer::new(seq))?;
                Ok(Input(Doc {
                    poses,
                    weights: None,
                }))
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Input, A::Error> {
                Doc::deserialize(MapAccessDeserializer::new(map)).map(Input)
            }
        }
        d.deserialize_any(V)
    }
}

/// Poses read, with their weights if given.
type Read = (Vec<DualQuat<f64>>, Option<Vec<f64>>);

/// The poses and weights of `text`, remarks (normalization) in `notes`; errors name the
/// field.
pub fn read(text: &str, notes: &mut Vec<String>) -> Result<Read> {
    let Input(doc) = from_json(text).map_err(|e: FieldError| {
        // A bare array of poses: its `[i]` is `poses[i]`.
        if e.path.starts_with('[') {
            anyhow!(e.within("poses"))
        } else {
            anyhow!(e)
        }
    })?;
    let mut poses = Vec::with_capacity(doc.poses.len());
    for (i, p) in doc.poses.into_iter().enumerate() {
        let at = format!("poses[{i}]");
        let m = p.0.motion().map_err(|e| anyhow!(e.within(&at)))?;
        notes.extend(m.notes.iter().map(|n| format!("{at}: {n}")));
        poses.push(m.dq);
    }
    if poses.is_empty() {
        bail!("poses: nothing to average (no poses)");
    }
    Ok((poses, doc.weights))
}

/// The mean of `text` as the output object.
pub fn compute(
    args: &AverageArgs,
    text: &str,
    notes: &mut Vec<String>,
) -> Result<serde_json::Value> {
    let (poses, weights) = read(text, notes)?;
    let mut opt = Options::default();
    if let Some(p) = args.precision {
        if !(p > 0.0 && p.is_finite()) {
            bail!("--precision must be positive and finite, got {p}");
        }
        opt.precision = p;
    }
    if let Some(n) = args.max_iterations {
        if n > 10_000 {
            bail!("--max-iterations must be at most 10000 (a cap, not a goal), got {n}");
        }
    }
    let robust = args.robust.map(|r| match r {
        RobustArg::Huber => Loss::Huber,
        RobustArg::Tukey => Loss::Tukey,
    });
    if robust.is_none() {
        for (flag, given) in [
            ("--tuning", args.tuning.is_some()),
            ("--scale", args.scale.is_some()),
            ("--length-scale", args.length_scale != 1.0),
        ] {
            if given {
                bail!("{flag} applies to the robust means: add --robust huber|tukey");
            }
        }
    }
    let w = weights.as_deref();
    let (a, method) = match robust {
        None => {
            opt.max_iterations = args.max_iterations.unwrap_or(opt.max_iterations);
            (mean(&poses, w, &opt)?, "dib")
        }
        Some(loss) => {
            let mut r = Robust::new(loss);
            r.options.precision = opt.precision;
            r.options.max_iterations = args.max_iterations.unwrap_or(r.options.max_iterations);
            r.tuning = args.tuning;
            r.length_scale = args.length_scale;
            if let Some(s) = args.scale {
                r.scale = Scale::Fixed(s);
            }
            opt.max_iterations = r.options.max_iterations;
            (robust_mean(&poses, w, &r)?, loss.name())
        }
    };
    if !a.pose.is_finite() {
        bail!("the mean is not finite: the poses are beyond the range of f64");
    }
    let m = a.pose.to_matrix4();
    let mut o = json!({
        "method": method,
        "poses": poses.len(),
        "rotation": a.pose.real.to_array(),
        "translation": a.pose.translation().to_array(),
        "matrix": m.m,
        "dq": a.pose.to_array(),
        "iterations": a.iterations,
        "capped": a.capped,
    });
    if let Some(s) = a.scale {
        o["scale"] = json!(s);
        o["weights"] = json!(a.weights);
        o["distances"] = json!(a.distances);
        let out: Vec<usize> = (0..a.weights.len())
            .filter(|i| a.weights[*i] == 0.0)
            .collect();
        o["outliers"] = json!(out);
    }
    if a.capped {
        notes.push(format!(
            "{method} ran all max_iterations = {} updates; its stopping rule (precision {:e}) had not stopped it",
            opt.max_iterations, opt.precision
        ));
    }
    if let Some(at) = crate::repr::first_non_finite(&o, "") {
        bail!("the mean's {at} is not a finite number: the input is beyond the range of f64");
    }
    Ok(o)
}

/// Runs `chasles average`.
pub fn run(args: AverageArgs) -> Result<()> {
    if let Some(out) = &args.out {
        if extension(out) != "json" {
            bail!("--out must end in .json, got {}", out.display());
        }
    }
    use chasles_skin::bounded::{read_capped, read_text, MAX_TEXT_BYTES};
    let text = if args.input == "-" {
        let bytes = read_capped(std::io::stdin().lock(), MAX_TEXT_BYTES, "stdin")?;
        String::from_utf8(bytes).context("stdin is not UTF-8 text")?
    } else {
        read_text(std::path::Path::new(&args.input), MAX_TEXT_BYTES)
            .with_context(|| format!("cannot read {}", args.input))?
    };
    let mut notes = Vec::new();
    let o = compute(&args, &text, &mut notes).with_context(|| args.input.clone())?;
    let json = serde_json::to_string_pretty(&o)?;
    for n in &notes {
        eprintln!("note: {n}");
    }
    match &args.out {
        Some(p) => {
            let mut files = Pending::default();
            files.add(p, json.into_bytes(), Some(String::new()));
            for line in files.write()? {
                eprintln!("{line}");
            }
        }
        None => println!("{json}"),
    }
    Ok(())
}
