//! The Spring controls of the report's `quat` program (Dam et al. 1998, §6.3.7 and App. C)
//! on the command line and in key files: the steps of the multi-step scheme (frames and
//! iterations per step, Figures 6.15–6.17), the step rule, the unit penalty c of eq. 6.28,
//! the parameter width of eq. 6.23 (eq. 6.43's 1, eq. 6.24's chord average, or its note's
//! angles), the key-frame weight c_k and the velocity weight c_w (eq. 6.41), and the start
//! curve. The presets (`spring`, `slerpsvupti`, `squadsvupti`, `justdoit`) are named sets
//! of these: [`options`] writes any configuration back as the options that give it, and
//! `chasles interp` prints it in its summary. A key file's `[spring]` table sets the same
//! controls (names with `_`); the command line overrides the file, the file the preset.
//!
//! The solver: `--solver converged` (the default of `--method spring`) minimizes F to a
//! stationary point by Newton's method on the unit quaternions (`chasles::interp::Solver`,
//! §8.2's "more robust numerical solution"), with the start, width and weights as above and
//! a gradient `--tolerance`; `--solver report` (the default of the report's programs
//! `slerpsvupti`, `squadsvupti`, `justdoit`) runs the report's gradient descent, whose
//! levels, iterations, step rule and unit penalty apply to it alone.

use anyhow::{bail, Result};
use chasles::analysis::curvature::Width;
use chasles::interp::{Level, Solver, SpringConfig, Start, StepRule};
use clap::ValueEnum;
use serde::Deserialize;

/// The parameter width `l` of eq. 6.23.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum WidthArg {
    /// `l = 1` (eq. 6.43, the report's program).
    One,
    /// The centred chord average (eq. 6.24).
    Chord,
    /// The centred average of the angles between neighbours (eq. 6.24's note).
    Angle,
}

/// Which minimization runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SolverArg {
    /// Newton's method to a stationary point of F (the default of `spring`).
    Converged,
    /// The report's gradient descent (the default of its programs).
    Report,
}

/// The curve the first step starts from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StartArg {
    /// Slerp (the report's choice).
    Slerp,
    /// Squad.
    Squad,
}

/// A step rule as written: `fixed:E`, `normalized:E` (the report's two), `adaptive:E` or
/// `accelerated:E`, E the step length.
pub fn parse_step(s: &str) -> std::result::Result<StepRule, String> {
    let (rule, e) = s
        .split_once(':')
        .ok_or_else(|| format!("'{s}' is not RULE:LENGTH, e.g. fixed:0.02"))?;
    let e: f64 = e
        .parse()
        .map_err(|_| format!("'{e}' in '{s}' is not a number"))?;
    if !(e > 0.0 && e.is_finite()) {
        return Err(format!(
            "the step length in '{s}' must be positive and finite"
        ));
    }
    match rule {
        "fixed" => Ok(StepRule::Fixed(e)),
        "normalized" => Ok(StepRule::Normalized(e)),
        "adaptive" => Ok(StepRule::Adaptive(e)),
        "accelerated" => Ok(StepRule::Accelerated(e)),
        other => Err(format!(
            "unknown step rule '{other}' (fixed, normalized, adaptive or accelerated)"
        )),
    }
}

/// A step rule written as [`parse_step`] reads it.
fn step_text(s: StepRule) -> String {
    match s {
        StepRule::Fixed(e) => format!("fixed:{e}"),
        StepRule::Normalized(e) => format!("normalized:{e}"),
        StepRule::Adaptive(e) => format!("adaptive:{e}"),
        StepRule::Accelerated(e) => format!("accelerated:{e}"),
    }
}

/// The Spring controls, each unset unless given.
///
/// The same type reads a key file's `[spring]` table (serde, names with `_`; unknown
/// fields are errors), so the command line and the file cannot drift apart.
#[derive(clap::Args, Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringArgs {
    /// Spring methods: frames at each step, coarse to fine, e.g. 22,110,550 (Figures
    /// 6.16–6.17); the last is the total (and --frames, if given, must equal it).
    #[arg(long, value_delimiter = ',', value_name = "N,N,…")]
    pub levels: Option<Vec<usize>>,
    /// Spring methods: gradient-descent iterations at each step, e.g. 200,150,100.
    #[arg(long, value_delimiter = ',', value_name = "N,N,…")]
    pub iterations: Option<Vec<usize>>,
    /// Spring methods: the step rule, fixed:E or normalized:E (the report's), adaptive:E or
    /// accelerated:E.
    #[arg(long, value_parser = parse_step, value_name = "RULE:E")]
    #[serde(default, deserialize_with = "step_field")]
    pub step: Option<StepRule>,
    /// Spring methods: weight c of the unit-length penalty (eq. 6.28).
    #[arg(long, allow_negative_numbers = true, value_name = "C")]
    pub penalty: Option<f64>,
    /// Spring methods: the parameter width l of eq. 6.23.
    #[arg(long, value_enum)]
    pub width: Option<WidthArg>,
    /// Spring methods: weight c_k of the curvature at key frames (§6.3.7).
    #[arg(long, allow_negative_numbers = true, value_name = "C_K")]
    pub key_weight: Option<f64>,
    /// Spring methods: weight c_w of the constant-velocity penalty (eq. 6.41).
    #[arg(long, allow_negative_numbers = true, value_name = "C_W")]
    pub velocity_weight: Option<f64>,
    /// Spring methods: the curve the first step starts from.
    #[arg(long, value_enum)]
    pub start: Option<StartArg>,
    /// Spring methods: converged (Newton to a stationary point; the default of spring) or
    /// report (the report's gradient descent; the default of its programs).
    #[arg(long, value_enum)]
    pub solver: Option<SolverArg>,
    /// Spring methods, converged solver: stop when the projected gradient has fallen to this
    /// share of its start (default 1e-10).
    #[arg(long, value_name = "T")]
    pub tolerance: Option<f64>,
}

/// `step = "fixed:0.02"` in a key file.
fn step_field<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<StepRule>, D::Error> {
    let s = String::deserialize(d)?;
    parse_step(&s).map(Some).map_err(serde::de::Error::custom)
}

impl SpringArgs {
    /// The options given, by their flags (to refuse them for the piecewise methods).
    pub fn given(&self) -> Vec<&'static str> {
        [
            ("--levels", self.levels.is_some()),
            ("--iterations", self.iterations.is_some()),
            ("--step", self.step.is_some()),
            ("--penalty", self.penalty.is_some()),
            ("--width", self.width.is_some()),
            ("--key-weight", self.key_weight.is_some()),
            ("--velocity-weight", self.velocity_weight.is_some()),
            ("--start", self.start.is_some()),
            ("--solver", self.solver.is_some()),
            ("--tolerance", self.tolerance.is_some()),
        ]
        .into_iter()
        .filter_map(|(f, on)| on.then_some(f))
        .collect()
    }

    /// Each control from `self`, else from `other`.
    fn or(self, other: SpringArgs) -> SpringArgs {
        SpringArgs {
            levels: self.levels.or(other.levels),
            iterations: self.iterations.or(other.iterations),
            step: self.step.or(other.step),
            penalty: self.penalty.or(other.penalty),
            width: self.width.or(other.width),
            key_weight: self.key_weight.or(other.key_weight),
            velocity_weight: self.velocity_weight.or(other.velocity_weight),
            start: self.start.or(other.start),
            solver: self.solver.or(other.solver),
            tolerance: self.tolerance.or(other.tolerance),
        }
    }
}

/// The most iterations one step may ask for: far past any convergence (the report's
/// largest run is 900 in all), and small enough that the counts never overflow.
pub const MAX_ITERATIONS: usize = 10_000_000;

/// `preset` with the key file's `[spring]` table and then the command line's options
/// applied (each control from the command line, else the file), for `keys` keys, and the total frame count: `frames` if given, else the last of
/// the levels, else `default_frames`. The solver is the options' `solver`, else
/// `default_solver`; with the converged solver the run is [`SpringConfig::converged`] from
/// the preset's start, and the report's descent controls (levels, iterations, step,
/// penalty) are refused. Errors name the option (`--levels`, or the key file's
/// `spring.levels`): a step of fewer frames than Spring gives a coarse step
/// (`4(keys − 1) + 1`) or more than the total, a total that disagrees with --frames,
/// iterations not one per step or over [`MAX_ITERATIONS`]; the values' ranges are checked
/// by the library's Spring.
pub fn configure(
    mut cfg: SpringConfig,
    default_solver: SolverArg,
    file: Option<&SpringArgs>,
    cli: &SpringArgs,
    frames: Option<usize>,
    default_frames: usize,
    keys: usize,
) -> Result<(SpringConfig, usize)> {
    let given = cli.clone().or(file.cloned().unwrap_or_default());
    if given.solver.unwrap_or(default_solver) == SolverArg::Converged {
        for (flag, on) in [
            ("--levels", given.levels.is_some()),
            ("--iterations", given.iterations.is_some()),
            ("--step", given.step.is_some()),
            ("--penalty", given.penalty.is_some()),
        ] {
            if on {
                bail!("{flag} (or its key-file field) is a control of the report's gradient descent: add --solver report, or leave it out for the converged solver");
            }
        }
        cfg = cfg.into_converged(given.tolerance);
    } else {
        cfg.solver = Solver::Report;
        if given.tolerance.is_some() {
            bail!("--tolerance (or spring.tolerance) is a control of the converged solver, not of --solver report");
        }
    }
    let (levels, iterations) = (given.levels, given.iterations);
    let total = match (&levels, frames) {
        (Some(l), Some(f)) if l.last() != Some(&f) => bail!(
            "--levels (or spring.levels) ends at {} frames but --frames is {f}: the last step is the total",
            l.last().map_or(0, |n| *n)
        ),
        (Some(l), _) => *l.last().ok_or_else(|| {
            anyhow::anyhow!("--levels (or spring.levels) needs at least one frame count")
        })?,
        (None, Some(f)) => f,
        (None, None) => default_frames,
    };
    if let Some(l) = &levels {
        let floor = (4 * keys.saturating_sub(1) + 1).min(total);
        if let Some(bad) = l[..l.len() - 1].iter().find(|n| **n < floor || **n > total) {
            bail!(
                "--levels (or spring.levels): every step before the last needs {floor} to {total} frames for {keys} keys (about four per interval), got {bad}"
            );
        }
        let its: Vec<usize> = match &iterations {
            Some(i) => i.clone(),
            None if cfg.levels.len() == l.len() => {
                cfg.levels.iter().map(|x| x.iterations).collect()
            }
            None => bail!(
                "--levels gives {} steps: give --iterations for each (the preset has {})",
                l.len(),
                cfg.levels.len()
            ),
        };
        if its.len() != l.len() {
            bail!(
                "--iterations (or spring.iterations) gives {} counts for {} steps of --levels",
                its.len(),
                l.len()
            );
        }
        cfg.levels = l
            .iter()
            .zip(its)
            .map(|(n, iterations)| Level {
                fraction: *n as f64 / total as f64,
                iterations,
            })
            .collect();
    } else if let Some(its) = iterations {
        if its.len() != cfg.levels.len() {
            bail!(
                "--iterations (or spring.iterations) gives {} counts but there are {} steps (set them with --levels)",
                its.len(),
                cfg.levels.len()
            );
        }
        for (l, n) in cfg.levels.iter_mut().zip(its) {
            l.iterations = n;
        }
    }
    if let Some(n) = cfg
        .levels
        .iter()
        .map(|l| l.iterations)
        .find(|n| *n > MAX_ITERATIONS)
    {
        bail!("--iterations (or spring.iterations): at most {MAX_ITERATIONS} a step, got {n}");
    }
    if let Some(s) = given.step {
        cfg.step = s;
    }
    if let Some(c) = given.penalty {
        cfg.unit_penalty = c;
    }
    if let Some(w) = given.width {
        cfg.width = match w {
            WidthArg::One => Width::Unit,
            WidthArg::Chord => Width::Centered,
            WidthArg::Angle => Width::Angle,
        };
    }
    if let Some(c) = given.key_weight {
        cfg.key_weight = c;
    }
    if let Some(c) = given.velocity_weight {
        cfg.velocity_penalty = c;
    }
    if let Some(s) = given.start {
        cfg.start = match s {
            StartArg::Slerp => Start::Slerp,
            StartArg::Squad => Start::Squad,
        };
    }
    Ok((cfg, total))
}

/// `cfg` for `frames` frames through `keys` keys written as the options that give it, e.g.
/// `--solver report --start slerp --levels 22,110,550 --iterations 200,150,100 --step
/// accelerated:0.05 --penalty 1 --width one --key-weight 1.3 --velocity-weight 0` (the
/// levels as the frames each step really has, [`SpringConfig::level_frames`]), or
/// `--solver converged --start slerp --width one --key-weight 1 --velocity-weight 0
/// --tolerance 1e-10`.
pub fn options(cfg: &SpringConfig, frames: usize, keys: usize) -> String {
    let start = match cfg.start {
        Start::Slerp => "slerp",
        Start::Squad => "squad",
    };
    let width = match cfg.width {
        Width::Unit => "one",
        Width::Centered => "chord",
        Width::Angle => "angle",
    };
    if let Solver::Converged { tolerance, .. } = cfg.solver {
        return format!(
            "--solver converged --start {start} --width {width} --key-weight {} --velocity-weight {} --tolerance {tolerance:e}",
            cfg.key_weight, cfg.velocity_penalty
        );
    }
    let levels: Vec<String> = cfg
        .level_frames(frames, keys)
        .iter()
        .map(usize::to_string)
        .collect();
    let iterations: Vec<String> = cfg
        .levels
        .iter()
        .map(|l| l.iterations.to_string())
        .collect();
    format!(
        "--solver report --start {start} --levels {} --iterations {} --step {} --penalty {} --width {width} --key-weight {} --velocity-weight {}",
        levels.join(","),
        iterations.join(","),
        step_text(cfg.step),
        cfg.unit_penalty,
        cfg.key_weight,
        cfg.velocity_penalty
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        spring: SpringArgs,
    }

    fn args(a: &[&str]) -> SpringArgs {
        Cli::try_parse_from(std::iter::once("x").chain(a.iter().copied()))
            .unwrap()
            .spring
    }

    /// Each preset is the set of options [`options`] writes, and those options, given to
    /// any preset, give it back.
    #[test]
    fn the_presets_are_named_sets_of_the_options() {
        for preset in [
            SpringConfig::spring(),
            SpringConfig::slerpsvupti(),
            SpringConfig::squadsvupti(),
            SpringConfig::justdoit(),
        ] {
            let text = options(&preset, 550, 6);
            let given = args(&text.split(' ').collect::<Vec<_>>());
            assert_eq!(given.given().len(), 9, "{text}");
            let (cfg, total) = configure(
                SpringConfig::squadsvupti(),
                SolverArg::Report,
                None,
                &given,
                None,
                200,
                6,
            )
            .unwrap();
            assert_eq!(total, 550);
            assert_eq!(cfg.start, preset.start, "{text}");
            assert_eq!(cfg.step, preset.step);
            assert_eq!(cfg.width, preset.width);
            assert_eq!(cfg.key_weight, preset.key_weight);
            assert_eq!(cfg.unit_penalty, preset.unit_penalty);
            assert_eq!(cfg.velocity_penalty, preset.velocity_penalty);
            assert_eq!(cfg.levels.len(), preset.levels.len());
            for (a, b) in cfg.levels.iter().zip(&preset.levels) {
                assert_eq!(a.iterations, b.iterations);
                assert!((a.fraction - b.fraction).abs() < 1e-12, "{text}");
            }
        }
        // The steps as Spring runs them: at 200 frames for six keys the first has 21, not 8;
        // and what is printed reads back.
        let text = options(&SpringConfig::justdoit(), 200, 6);
        assert!(text.contains("--levels 21,40,200"), "{text}");
        let given = args(&text.split(' ').collect::<Vec<_>>());
        assert!(configure(
            SpringConfig::justdoit(),
            SolverArg::Report,
            None,
            &given,
            None,
            200,
            6
        )
        .is_ok());
        assert_eq!(
            options(&SpringConfig::justdoit(), 550, 6),
            "--solver report --start slerp --levels 22,110,550 --iterations 200,150,100 --step adaptive:0.02 --penalty 1 --width one --key-weight 1 --velocity-weight 0"
        );
        // The converged solver likewise, and its options refuse the descent's controls.
        let mut c = SpringConfig::converged();
        c.start = Start::Squad;
        c.key_weight = 1.5;
        c.width = Width::Angle;
        let text = options(&c, 550, 6);
        assert_eq!(
            text,
            "--solver converged --start squad --width angle --key-weight 1.5 --velocity-weight 0 --tolerance 1e-10"
        );
        let given = args(&text.split(' ').collect::<Vec<_>>());
        let (cfg, _) = configure(
            SpringConfig::spring(),
            SolverArg::Report,
            None,
            &given,
            None,
            550,
            6,
        )
        .unwrap();
        assert_eq!(cfg, c);
        let (cfg, _) = configure(
            SpringConfig::spring(),
            SolverArg::Converged,
            None,
            &args(&[]),
            None,
            550,
            6,
        )
        .unwrap();
        assert_eq!(cfg, SpringConfig::converged());
        for flag in [
            &["--levels", "22,550"][..],
            &["--step", "fixed:0.1"],
            &["--penalty", "2"],
            &["--iterations", "3"],
        ] {
            let e = configure(
                SpringConfig::spring(),
                SolverArg::Converged,
                None,
                &args(flag),
                None,
                550,
                6,
            )
            .unwrap_err()
            .to_string();
            assert!(
                e.contains("control of the report's gradient descent"),
                "{e}"
            );
        }
        let e = configure(
            SpringConfig::justdoit(),
            SolverArg::Report,
            None,
            &args(&["--tolerance", "1e-8"]),
            None,
            550,
            6,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("control of the converged solver"), "{e}");
    }

    #[test]
    fn the_command_line_overrides_the_file_and_the_file_the_preset() {
        let file: SpringArgs = toml::from_str(
            "levels = [20, 100]\niterations = [5, 6]\nstep = \"fixed:0.01\"\nkey_weight = 1.2\nwidth = \"angle\"\nstart = \"squad\"",
        )
        .unwrap();
        let cli = args(&["--key-weight", "4", "--step", "normalized:0.5"]);
        let (cfg, total) = configure(
            SpringConfig::spring(),
            SolverArg::Report,
            Some(&file),
            &cli,
            None,
            200,
            3,
        )
        .unwrap();
        assert_eq!(total, 100);
        assert_eq!(cfg.levels.len(), 2);
        assert_eq!((cfg.levels[0].fraction, cfg.levels[0].iterations), (0.2, 5));
        assert_eq!(cfg.key_weight, 4.0);
        assert_eq!(cfg.step, StepRule::Normalized(0.5));
        assert_eq!(cfg.width, Width::Angle);
        assert_eq!(cfg.start, Start::Squad);
        // Nothing given: the preset, at --frames or the default.
        let (cfg, total) = configure(
            SpringConfig::justdoit(),
            SolverArg::Report,
            None,
            &args(&[]),
            Some(300),
            200,
            6,
        )
        .unwrap();
        assert_eq!((cfg, total), (SpringConfig::justdoit(), 300));
    }

    #[test]
    fn bad_controls_name_the_option() {
        let err = |a: &[&str], frames| {
            configure(
                SpringConfig::justdoit(),
                SolverArg::Report,
                None,
                &args(a),
                frames,
                200,
                6,
            )
            .unwrap_err()
            .to_string()
        };
        assert!(err(&["--levels", "22,110,550"], Some(200)).contains("--frames is 200"));
        assert!(err(&["--levels", "22,0,550"], None).contains("21 to 550"));
        assert!(err(&["--levels", "5,550"], None).contains("got 5"));
        assert!(err(&["--iterations", "1,20000000,1"], None).contains("at most 10000000"));
        assert!(err(&["--levels", "600,550"], None).contains("got 600"));
        assert!(err(&["--levels", "22,550"], None).contains("give --iterations"));
        assert!(
            err(&["--levels", "22,550", "--iterations", "1,2,3"], None).contains("3 counts for 2")
        );
        assert!(err(&["--iterations", "1,2"], None).contains("2 counts but there are 3"));
        for bad in ["fixed", "fixed:x", "fixed:-1", "slow:0.1", "fixed:inf"] {
            assert!(parse_step(bad).is_err(), "{bad}");
        }
        let bad: Result<SpringArgs, _> = toml::from_str("step = \"up:1\"");
        assert!(bad.unwrap_err().to_string().contains("unknown step rule"));
        let bad: Result<SpringArgs, _> = toml::from_str("widht = \"one\"");
        assert!(bad.unwrap_err().to_string().contains("widht"));
    }
}
