//! Spring's controls as `chasles interp` takes them (Dam et al. 1998, §6.3.7 and App. C):
//! the keywords of `chasles.spring` and `chasles.interpolate` turned into a
//! `chasles::interp::SpringConfig` by the rules of the CLI's `spring_args::configure`
//! (the same checks, the same messages, with the keyword names): the converged solver
//! (§8.2, `chasles::interp::Solver::Converged`) by default for `spring`, the report's
//! gradient descent (App. C) for its presets, `solver=` choosing either.

use crate::arrays::value_error;
use chasles::analysis::curvature::Width;
use chasles::interp::{Level, Solver, SpringConfig, Start, StepRule};
use pyo3::prelude::*;

/// Spring's controls as `chasles interp` takes them (`--levels`, `--iterations`, `--step`,
/// `--penalty`, `--width`, `--key-weight`, `--velocity-weight`, `--start`, `--solver`,
/// `--tolerance`), each unset unless given.
#[derive(Debug, Clone, Default)]
pub struct SpringOptions {
    /// Frames at each step, coarse to fine; the last is the total.
    pub levels: Option<Vec<usize>>,
    /// Gradient-descent iterations at each step.
    pub iterations: Option<Vec<usize>>,
    /// `fixed:E`, `normalized:E`, `adaptive:E` or `accelerated:E`.
    pub step: Option<String>,
    /// c of the unit penalty (eq. 6.28).
    pub penalty: Option<f64>,
    /// `one`, `chord` or `angle` (eq. 6.23–6.24).
    pub width: Option<String>,
    /// c_k, the curvature weight at key frames.
    pub key_weight: Option<f64>,
    /// c_w, the constant-velocity weight (eq. 6.41).
    pub velocity_weight: Option<f64>,
    /// `slerp` or `squad`.
    pub start: Option<String>,
    /// `converged` or `report`.
    pub solver: Option<String>,
    /// The converged solver's gradient tolerance.
    pub tolerance: Option<f64>,
}

impl SpringOptions {
    /// The controls given, by their keyword names.
    pub fn given(&self) -> Vec<&'static str> {
        [
            ("levels", self.levels.is_some()),
            ("iterations", self.iterations.is_some()),
            ("step", self.step.is_some()),
            ("penalty", self.penalty.is_some()),
            ("width", self.width.is_some()),
            ("key_weight", self.key_weight.is_some()),
            ("velocity_weight", self.velocity_weight.is_some()),
            ("start", self.start.is_some()),
            ("solver", self.solver.is_some()),
            ("tolerance", self.tolerance.is_some()),
        ]
        .into_iter()
        .filter_map(|(n, on)| on.then_some(n))
        .collect()
    }
}

/// The most iterations one Spring step may ask for (as `chasles interp`).
const MAX_ITERATIONS: usize = 10_000_000;

/// A step rule written `RULE:LENGTH` (the CLI's `--step`).
fn step_rule(s: &str) -> PyResult<StepRule> {
    let bad = |why: String| value_error(format!("step: {why}"));
    let (rule, e) = s
        .split_once(':')
        .ok_or_else(|| bad(format!("'{s}' is not RULE:LENGTH, e.g. fixed:0.02")))?;
    let e: f64 = e
        .parse()
        .map_err(|_| bad(format!("'{e}' in '{s}' is not a number")))?;
    if !(e > 0.0 && e.is_finite()) {
        return Err(bad(format!(
            "the step length in '{s}' must be positive and finite"
        )));
    }
    match rule {
        "fixed" => Ok(StepRule::Fixed(e)),
        "normalized" => Ok(StepRule::Normalized(e)),
        "adaptive" => Ok(StepRule::Adaptive(e)),
        "accelerated" => Ok(StepRule::Accelerated(e)),
        other => Err(bad(format!(
            "unknown step rule '{other}' (fixed, normalized, adaptive or accelerated)"
        ))),
    }
}

/// `preset` with the options applied, and the total frame count (`frames`, else the last
/// of `levels`, else 200), by the rules of `chasles interp` (its `spring_args::configure`):
/// the solver is `o.solver`, else the converged one when `converged_by_default` (the
/// method `spring`) and the report's otherwise; the converged solver starts from
/// [`SpringConfig::converged`] with the preset's start and refuses the descent's controls
/// (`levels`, `iterations`, `step`, `penalty`), the report's refuses `tolerance`.
pub fn spring_config(
    mut cfg: SpringConfig,
    converged_by_default: bool,
    o: &SpringOptions,
    frames: Option<usize>,
    keys: usize,
) -> PyResult<(SpringConfig, usize)> {
    let converged = match o.solver.as_deref() {
        None => converged_by_default,
        Some("converged") => true,
        Some("report") => false,
        Some(other) => {
            return Err(value_error(format!(
                "solver: unknown solver '{other}' (converged or report)"
            )))
        }
    };
    if converged {
        for (name, on) in [
            ("levels", o.levels.is_some()),
            ("iterations", o.iterations.is_some()),
            ("step", o.step.is_some()),
            ("penalty", o.penalty.is_some()),
        ] {
            if on {
                return Err(value_error(format!(
                    "{name} is a control of the report's gradient descent: add solver=\"report\", or leave it out for the converged solver"
                )));
            }
        }
        cfg = cfg.into_converged(o.tolerance);
    } else {
        cfg.solver = Solver::Report;
        if o.tolerance.is_some() {
            return Err(value_error(
                "tolerance is a control of the converged solver, not of solver=\"report\"",
            ));
        }
    }
    let total = match (&o.levels, frames) {
        (Some(l), Some(f)) if l.last() != Some(&f) => {
            return Err(value_error(format!(
                "levels ends at {} frames but frames is {f}: the last step is the total",
                l.last().map_or(0, |n| *n)
            )))
        }
        (Some(l), _) => *l
            .last()
            .ok_or_else(|| value_error("levels needs at least one frame count"))?,
        (None, Some(f)) => f,
        (None, None) => DEFAULT_FRAMES,
    };
    if let Some(l) = &o.levels {
        let floor = (4 * keys.saturating_sub(1) + 1).min(total);
        if let Some(bad) = l[..l.len() - 1].iter().find(|n| **n < floor || **n > total) {
            return Err(value_error(format!(
                "levels: every step before the last needs {floor} to {total} frames for {keys} keys (about four per interval), got {bad}"
            )));
        }
        let its: Vec<usize> = match &o.iterations {
            Some(i) => i.clone(),
            None if cfg.levels.len() == l.len() => {
                cfg.levels.iter().map(|x| x.iterations).collect()
            }
            None => {
                return Err(value_error(format!(
                    "levels gives {} steps: give iterations for each (the preset has {})",
                    l.len(),
                    cfg.levels.len()
                )))
            }
        };
        if its.len() != l.len() {
            return Err(value_error(format!(
                "iterations gives {} counts for {} steps of levels",
                its.len(),
                l.len()
            )));
        }
        cfg.levels = l
            .iter()
            .zip(its)
            .map(|(n, iterations)| Level {
                fraction: *n as f64 / total as f64,
                iterations,
            })
            .collect();
    } else if let Some(its) = &o.iterations {
        if its.len() != cfg.levels.len() {
            return Err(value_error(format!(
                "iterations gives {} counts but there are {} steps (set them with levels)",
                its.len(),
                cfg.levels.len()
            )));
        }
        for (l, n) in cfg.levels.iter_mut().zip(its) {
            l.iterations = *n;
        }
    }
    if let Some(n) = cfg
        .levels
        .iter()
        .map(|l| l.iterations)
        .find(|n| *n > MAX_ITERATIONS)
    {
        return Err(value_error(format!(
            "iterations: at most {MAX_ITERATIONS} a step, got {n}"
        )));
    }
    if let Some(s) = &o.step {
        cfg.step = step_rule(s)?;
    }
    if let Some(c) = o.penalty {
        cfg.unit_penalty = c;
    }
    if let Some(w) = &o.width {
        cfg.width = match w.as_str() {
            "one" => Width::Unit,
            "chord" => Width::Centered,
            "angle" => Width::Angle,
            other => {
                return Err(value_error(format!(
                    "width: unknown width '{other}' (one, chord or angle)"
                )))
            }
        };
    }
    if let Some(c) = o.key_weight {
        cfg.key_weight = c;
    }
    if let Some(c) = o.velocity_weight {
        cfg.velocity_penalty = c;
    }
    if let Some(s) = &o.start {
        cfg.start = match s.as_str() {
            "slerp" => Start::Slerp,
            "squad" => Start::Squad,
            other => {
                return Err(value_error(format!(
                    "start: unknown start curve '{other}' (slerp or squad)"
                )))
            }
        };
    }
    Ok((cfg, total))
}

/// Frames when neither `frames` nor `levels` says (as `chasles interp`).
pub const DEFAULT_FRAMES: usize = 200;
