//! *Spring*: Spherical Interpolation using Numerical Gradient descent (Dam et al. 1998,
//! §6.3.7 and App. C).
//!
//! The frames `q_1 … q_N` (keys fixed) minimize
//! `F = Σ_i c_i l_i ‖κ̃_i‖² + c_g Σ_i g(q_i)² + c_w Σ_i w(q_i)²` (eq. 6.28, 6.41) where
//! * `l_i ‖κ̃_i‖²` is the discrete curvature term (eq. 6.23–6.26; see
//!   [`crate::analysis::curvature`]), with `l = 1` by default (eq. 6.43);
//! * `c_i = c_k` when frame i is a key frame, else 1 — the key-frame weighting of §6.3.7
//!   ("each key frame can simply ask its neighbours to be more considerate"): the report
//!   scales the gradient terms `2κ̃(q_{i±1})·∂κ̃(q_{i±1})/∂q_i` of a key neighbour by c_k,
//!   which is exactly the gradient of this weighted energy;
//! * `g(q) = q·q − 1` keeps the frames near unit length (eq. 6.27);
//! * `w(q_i) = ‖q_{i−1} − q_i‖ − ‖q_i − q_{i+1}‖` penalizes uneven speed (eq. 6.40). The
//!   report's eq. 6.42 for its derivative has a sign slip (it adds both unit vectors, as
//!   for l); the gradient here is the derivative of eq. 6.40 itself, checked against finite
//!   differences in the tests.
//!
//! Gradient descent `q ← q − e ∇F` with a [`StepRule`]: a fixed step, the normalized step
//! `e ∇F/‖∇F‖` (both from the report), or an adaptive step that halves on an energy
//! increase and grows by 20 % on success (so F never rises). The gradient is zero at the
//! key frames. It stops at the iteration count, or earlier on a small relative energy
//! change or gradient norm.
//!
//! Multi-step minimization ("few frames first, then refine"): each level starts from the
//! previous level's curve resampled (by Slerp between its frames) to more frames; the
//! first level starts from Slerp or Squad. The presets are the report's programs:
//! [`SpringConfig::slerpsvupti`], [`SpringConfig::squadsvupti`], [`SpringConfig::justdoit`]
//! (three levels, 22 → 110 → 550 frames with 200/150/100 iterations on Table 5.1, Figures
//! 6.16–6.17) and [`SpringConfig::spring`] (the same with key weight c_k = 1.3, Figure
//! 6.20). The result is normalized to unit quaternions at the end; the report regards
//! normalizing *during* the descent as cheating, and so do we.
//!
//! Past 500 lines because the energy, its analytic gradient and the descent that uses them
//! are one algorithm whose parts must change together (a term added to F needs its
//! gradient beside it); the configuration and presets are a quarter of it.

use super::slerp::slerp;
use super::timing::{self, Timing};
use super::{interpolate, Frame, KeyFrames, Method};
use crate::analysis::curvature::{term_gradient, Width};
use crate::{Error, Quat, Real, Result};

/// The curve the first level starts from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Start {
    /// Slerp between the keys (the report's choice: "more fair").
    Slerp,
    /// Squad through the keys.
    Squad,
}

/// How far each descent step goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StepRule {
    /// `q ← q − e ∇F`.
    Fixed(f64),
    /// `q ← q − e ∇F / ‖∇F‖`.
    Normalized(f64),
    /// `q ← q − e ∇F` with e halved until F decreases and grown by 20 % after a success.
    Adaptive(f64),
    /// Nesterov's accelerated gradient with adaptive restart (O'Donoghue & Candès 2015):
    /// the step is taken from an extrapolated point, e is halved until the step satisfies
    /// the Armijo condition there, and the momentum is dropped whenever F rises. Same
    /// minimum, far fewer iterations on this stiff (fourth-difference) energy.
    Accelerated(f64),
}

impl StepRule {
    fn length(self) -> f64 {
        match self {
            StepRule::Fixed(e)
            | StepRule::Normalized(e)
            | StepRule::Adaptive(e)
            | StepRule::Accelerated(e) => e,
        }
    }
}

/// Which minimization runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Solver {
    /// The report's gradient descent (App. C): the [`SpringConfig::levels`], the
    /// [`SpringConfig::step`] rule and the unit penalty c_g; frames normalized at the end.
    Report,
    /// Gauss–Newton on the unit quaternions to a stationary point of F (keys fixed): until
    /// the projected gradient is `tolerance` times its start, or no step lowers F (the
    /// rounding of f64), at most `max_iterations` steps. Needs no step length, penalty or
    /// levels (§8.2's "more robust numerical solution"; `spring_converged`).
    Converged {
        /// The projected gradient's fall that ends the solve (1e-10 by default).
        tolerance: f64,
        /// The most Gauss–Newton steps.
        max_iterations: usize,
    },
}

/// Why a Spring run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stopped {
    /// The report's solver ran its levels (to their iteration counts or thresholds).
    LevelsDone,
    /// The converged solver reached its gradient tolerance.
    Converged,
    /// The converged solver found no step that lowers F: a stationary point as far as f64
    /// can tell.
    Rounding,
    /// The converged solver ran all its iterations.
    MaxIterations,
}

/// One level of the multi-step scheme. A level never has fewer than `4(K − 1) + 1` frames
/// for K keys (about four per interval), nor more than the final count.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Level {
    /// Frames at this level as a fraction of the final count (the last level: 1).
    pub fraction: f64,
    /// Gradient-descent iterations at this level.
    pub iterations: usize,
}

/// Everything Spring can be told. Build from a preset and adjust fields.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringConfig {
    /// Start curve of the first level.
    pub start: Start,
    /// The levels, coarse to fine.
    pub levels: Vec<Level>,
    /// Step rule.
    pub step: StepRule,
    /// `c_k`: weight of the curvature at key frames (1 = none).
    pub key_weight: f64,
    /// `c_g`: weight of the unit-length penalty (eq. 6.28).
    pub unit_penalty: f64,
    /// `c_w`: weight of the constant-velocity penalty (eq. 6.41); 0 = off.
    pub velocity_penalty: f64,
    /// The parameter width `l` of the curvature term.
    pub width: Width,
    /// Stop a level when `|ΔF| / F` falls below this (0 = never).
    pub min_energy_change: f64,
    /// Stop a level when `‖∇F‖` falls below this (0 = never).
    pub min_gradient_norm: f64,
    /// The report's descent or the converged solver.
    pub solver: Solver,
}

impl SpringConfig {
    fn base(start: Start, levels: Vec<Level>, key_weight: f64) -> Self {
        Self {
            start,
            levels,
            step: StepRule::Adaptive(0.02),
            key_weight,
            unit_penalty: 1.0,
            velocity_penalty: 0.0,
            width: Width::Unit,
            min_energy_change: 0.0,
            min_gradient_norm: 0.0,
            solver: Solver::Report,
        }
    }
    /// Spring solved to its optimum ([`Solver::Converged`], gradient tolerance 1e-10, at
    /// most 200 steps) from Slerp: the energy of eq. 6.23 on unit frames, keys fixed, c_k = 1,
    /// no velocity penalty, width 1 — the minimum the report's descent approaches.
    pub fn converged() -> Self {
        let mut c = Self::base(
            Start::Slerp,
            vec![Level {
                fraction: 1.0,
                iterations: 0,
            }],
            1.0,
        );
        c.solver = Solver::Converged {
            tolerance: 1e-10,
            max_iterations: 200,
        };
        c
    }
    /// This preset's start curve solved by the converged solver ([`SpringConfig::converged`]),
    /// with `tolerance` in place of 1e-10 when given: what `--solver converged` makes of any
    /// preset (the command line's and Python's Spring options share it).
    pub fn into_converged(self, tolerance: Option<f64>) -> Self {
        let mut c = Self::converged();
        c.start = self.start;
        if let (Some(t), Solver::Converged { tolerance, .. }) = (tolerance, &mut c.solver) {
            *tolerance = t;
        }
        c
    }
    /// App. C `slerpsvupti`: one level, Slerp start, 500 iterations (Figure 6.15).
    pub fn slerpsvupti() -> Self {
        Self::base(
            Start::Slerp,
            vec![Level {
                fraction: 1.0,
                iterations: 500,
            }],
            1.0,
        )
    }
    /// App. C `squadsvupti`: one level, Squad start, 500 iterations.
    pub fn squadsvupti() -> Self {
        Self::base(
            Start::Squad,
            vec![Level {
                fraction: 1.0,
                iterations: 500,
            }],
            1.0,
        )
    }
    /// App. C `justdoit`: three levels from Slerp, 22/550 → 110/550 → all frames with
    /// 200, 150 and 100 iterations (Figures 6.16–6.17).
    pub fn justdoit() -> Self {
        Self::base(Start::Slerp, Self::report_levels(), 1.0)
    }
    /// *Spring* as the report concludes §6.3.7: `justdoit` with the key-frame curvature
    /// weighted by c_k = 1.3 (Figure 6.20) — and, beyond the report, the accelerated step
    /// rule, which reaches in the same 450 iterations an energy plain descent needs several
    /// times as many for.
    pub fn spring() -> Self {
        let mut c = Self::base(Start::Slerp, Self::report_levels(), 1.3);
        c.step = StepRule::Accelerated(0.05);
        c
    }
    fn report_levels() -> Vec<Level> {
        vec![
            Level {
                fraction: 22.0 / 550.0,
                iterations: 200,
            },
            Level {
                fraction: 110.0 / 550.0,
                iterations: 150,
            },
            Level {
                fraction: 1.0,
                iterations: 100,
            },
        ]
    }
    /// The frames of each level for `frames` frames through `keys` keys: the last level
    /// all of them, the others their fraction of them, rounded, but never fewer than
    /// `4(keys − 1) + 1` (about four frames per interval, the report's 22 for its six keys:
    /// fewer leave the coarse levels nothing to smooth) nor more than `frames`.
    pub fn level_frames(&self, frames: usize, keys: usize) -> Vec<usize> {
        let floor = (4 * keys.saturating_sub(1) + 1).min(frames);
        let last = self.levels.len().saturating_sub(1);
        self.levels
            .iter()
            .enumerate()
            .map(|(i, l)| {
                if i == last {
                    frames
                } else {
                    ((l.fraction * frames as f64).round() as usize).clamp(floor, frames)
                }
            })
            .collect()
    }
    fn validate(&self) -> Result<()> {
        let bad = |what, rule, value| Err(Error::BadParameter { what, rule, value });
        if let Solver::Converged {
            tolerance,
            max_iterations,
        } = self.solver
        {
            if !(0.0..1.0).contains(&tolerance) {
                return bad("the converged Spring's tolerance", "in [0, 1[", tolerance);
            }
            if max_iterations > 100_000 {
                return bad(
                    "the converged Spring's iterations",
                    "at most 100000",
                    max_iterations as f64,
                );
            }
        }
        if self.levels.is_empty() {
            return bad("the number of Spring levels", "at least 1", 0.0);
        }
        for l in &self.levels {
            if !(l.fraction > 0.0 && l.fraction <= 1.0) {
                return bad("a Spring level's frame fraction", "in ]0, 1]", l.fraction);
            }
        }
        let step = self.step.length();
        if !(step > 0.0 && step.is_finite()) {
            return bad("the Spring step length", "positive and finite", step);
        }
        for (what, v) in [
            ("the key weight c_k", self.key_weight),
            ("the unit penalty c_g", self.unit_penalty),
            ("the velocity penalty c_w", self.velocity_penalty),
            ("the energy-change threshold", self.min_energy_change),
            ("the gradient-norm threshold", self.min_gradient_norm),
        ] {
            if !(v >= 0.0 && v.is_finite()) {
                return bad(what, "non-negative and finite", v);
            }
        }
        Ok(())
    }
}

/// One entry of the energy history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyRecord {
    /// Level (0 = coarsest).
    pub level: usize,
    /// Iteration within the level (0 = the start, before any step).
    pub iteration: usize,
    /// Frames at this level.
    pub frames: usize,
    /// F, the minimized energy.
    pub energy: f64,
    /// ‖∇F‖.
    pub gradient_norm: f64,
}

/// What [`spring`] returns.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringResult<T> {
    /// The final frames (normalized), keys flagged.
    pub frames: Vec<Frame<T>>,
    /// F and ‖∇F‖ at the start of each level and after every iteration (the converged
    /// solver: one level, ‖∇F‖ projected onto the tangent spaces).
    pub history: Vec<EnergyRecord>,
    /// Why it ended.
    pub stopped: Stopped,
}

/// Progress report for long runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Current level.
    pub level: usize,
    /// Number of levels.
    pub levels: usize,
    /// Iterations done in this level.
    pub iteration: usize,
    /// Iterations of this level.
    pub iterations: usize,
    /// Current energy F.
    pub energy: f64,
}

/// The energy F of eq. 6.28/6.41 (see the module docs) and its gradient, zero at keys.
pub fn energy_and_gradient<T: Real>(
    q: &[Quat<T>],
    is_key: &[bool],
    cfg: &SpringConfig,
) -> (T, Vec<Quat<T>>) {
    let n = q.len();
    let mut grad = vec![Quat::zero(); n];
    let mut f = T::ZERO;
    let ck = T::from_f64(cfg.key_weight);
    let cg = T::from_f64(cfg.unit_penalty);
    let cw = T::from_f64(cfg.velocity_penalty);
    for j in 1..n.saturating_sub(1) {
        let (t, g) = term_gradient(q[j - 1], q[j], q[j + 1], cfg.width);
        let c = if is_key[j] { ck } else { T::ONE };
        f += c * t;
        for (k, gk) in g.iter().enumerate() {
            grad[j - 1 + k] += *gk * c;
        }
        if cfg.velocity_penalty > 0.0 {
            let (d1, d2) = (q[j] - q[j - 1], q[j] - q[j + 1]);
            let (n1, n2) = (d1.norm(), d2.norm());
            let w = n1 - n2;
            f += cw * w * w;
            let e1 = if n1 > T::ZERO { d1 / n1 } else { Quat::zero() };
            let e2 = if n2 > T::ZERO { d2 / n2 } else { Quat::zero() };
            let s = cw * T::TWO * w;
            grad[j - 1] += -e1 * s;
            grad[j] += (e1 - e2) * s;
            grad[j + 1] += e2 * s;
        }
    }
    for (qi, gi) in q.iter().zip(grad.iter_mut()) {
        let g = qi.dot(*qi) - T::ONE;
        f += cg * g * g;
        *gi += *qi * (cg * T::from_i32(4) * g);
    }
    for (gi, key) in grad.iter_mut().zip(is_key) {
        if *key {
            *gi = Quat::zero();
        }
    }
    (f, grad)
}

/// What one descent step proposes.
enum Step<T> {
    /// Take this point, with its energy and gradient.
    Accept(Vec<Quat<T>>, T, Vec<Quat<T>>),
    /// Momentum dropped: try again from the current point.
    Restart,
    /// No step lowers F any more: converged to rounding.
    Stop,
}

/// Nesterov's `t_{k+1} = (1 + √(1 + 4t²))/2`.
fn y_t_next<T: Real>(t: T) -> T {
    (T::ONE + (T::ONE + T::from_i32(4) * t * t).sqrt()) * T::HALF
}

/// Fixed, normalized or adaptive step from q (see [`StepRule`]).
fn plain_step<T: Real>(
    q: &[Quat<T>],
    f: T,
    g: &[Quat<T>],
    gn: T,
    e: &mut T,
    is_key: &[bool],
    cfg: &SpringConfig,
) -> Step<T> {
    let scale = match cfg.step {
        StepRule::Normalized(_) => *e / gn,
        _ => *e,
    };
    let mut trial: Vec<Quat<T>> = q.iter().zip(g).map(|(a, b)| *a - *b * scale).collect();
    let (mut f2, mut g2) = energy_and_gradient(&trial, is_key, cfg);
    if let StepRule::Adaptive(_) = cfg.step {
        let mut tries = 0;
        while !decreased(f2, f) && tries < 40 {
            *e *= T::HALF;
            trial = q.iter().zip(g).map(|(a, b)| *a - *b * *e).collect();
            (f2, g2) = energy_and_gradient(&trial, is_key, cfg);
            tries += 1;
        }
        if !decreased(f2, f) {
            return Step::Stop;
        }
        *e *= T::from_f64(1.2);
    }
    Step::Accept(trial, f2, g2)
}

/// One accelerated step: from the extrapolated point y (q itself after a restart), with
/// the Armijo condition at y; a rise of F drops the momentum.
fn accelerated_step<T: Real>(
    q: &[Quat<T>],
    f: T,
    g: &[Quat<T>],
    momentum: &mut Option<(Vec<Quat<T>>, T)>,
    e: &mut T,
    is_key: &[bool],
    cfg: &SpringConfig,
) -> Step<T> {
    let (y, t) = momentum.take().unwrap_or_else(|| (q.to_vec(), T::ONE));
    let (fy, gy) = if t == T::ONE {
        (f, g.to_vec())
    } else {
        energy_and_gradient(&y, is_key, cfg)
    };
    let gy2 = gy.iter().fold(T::ZERO, |a, v| a + v.dot(*v));
    if gy2 == T::ZERO {
        return Step::Stop;
    }
    let mut tries = 0;
    loop {
        let x_new: Vec<Quat<T>> = y.iter().zip(&gy).map(|(a, b)| *a - *b * *e).collect();
        let (f_new, g_new) = energy_and_gradient(&x_new, is_key, cfg);
        if f_new <= fy - T::HALF * *e * gy2 || tries >= 40 {
            if !decreased(f_new, f) {
                // Restart without momentum; if that was already a plain step, stop.
                return if t == T::ONE {
                    Step::Stop
                } else {
                    Step::Restart
                };
            }
            *momentum = Some((y, t));
            return Step::Accept(x_new, f_new, g_new);
        }
        *e *= T::HALF;
        tries += 1;
    }
}

/// `new < old`, false when either is NaN (so a NaN energy is never accepted).
fn decreased<T: Real>(new: T, old: T) -> bool {
    new < old
}

fn norm_of<T: Real>(g: &[Quat<T>]) -> T {
    g.iter().fold(T::ZERO, |a, v| a + v.dot(*v)).sqrt()
}

/// Runs Spring through the keys: `frames` frames shared by `timing`, minimized as
/// configured. `progress` is called after every iteration. Errors: fewer frames than keys,
/// bad configuration values.
///
/// The descent itself always runs in f64, whatever T: in f32 the rounding of the second
/// differences (relative 1e-4 at a few hundred frames) is larger than the energy decrease
/// per step, and the descent stalls. The frames are converted back to T at the end.
pub fn spring<T: Real>(
    keys: &KeyFrames<T>,
    frames: usize,
    timing: Timing,
    cfg: &SpringConfig,
    progress: &mut dyn FnMut(&Progress),
) -> Result<SpringResult<T>> {
    let q64: Vec<Quat<f64>> = keys.quats().iter().map(|q| q.cast()).collect();
    let t64: Option<Vec<f64>> = keys.times().map(|t| t.iter().map(|v| v.to_f64()).collect());
    let mut keys64 = KeyFrames::new(&q64, t64.as_deref(), super::Hemisphere::AsGiven)?;
    if let Some(v) = keys.velocities() {
        let v64: Vec<Option<crate::Vec3<f64>>> = v.iter().map(|w| w.map(|w| w.cast())).collect();
        keys64 = keys64.with_velocities(&v64)?;
    }
    let r = spring_f64(&keys64, frames, timing, cfg, progress)?;
    Ok(SpringResult {
        frames: r
            .frames
            .into_iter()
            .map(|f| Frame {
                q: f.q.cast(),
                t: T::from_f64(f.t),
                key: f.key,
            })
            .collect(),
        history: r.history,
        stopped: r.stopped,
    })
}

fn spring_f64(
    keys: &KeyFrames<f64>,
    frames: usize,
    timing: Timing,
    cfg: &SpringConfig,
    progress: &mut dyn FnMut(&Progress),
) -> Result<SpringResult<f64>> {
    type T = f64;
    cfg.validate()?;
    let k = keys.len();
    if frames < k {
        return Err(Error::TooFewFrames { frames, keys: k });
    }
    if let (Solver::Report, Some(v)) = (cfg.solver, keys.velocities()) {
        return Err(Error::KeyVelocity {
            index: v.iter().position(Option::is_some).unwrap_or(0),
            why: "only the converged Spring solver honours key velocities (Solver::Converged)",
        });
    }
    if let Solver::Converged {
        tolerance,
        max_iterations,
    } = cfg.solver
    {
        return super::spring_converged::spring_converged(
            keys,
            frames,
            timing,
            cfg,
            tolerance,
            max_iterations,
            progress,
        );
    }
    let mut history = Vec::new();
    let mut current: Vec<Frame<T>> = Vec::new();
    let sizes = cfg.level_frames(frames, k);
    let levels = cfg.levels.len();
    for (li, (level, &n)) in cfg.levels.iter().zip(&sizes).enumerate() {
        current = if li == 0 {
            let m = match cfg.start {
                Start::Slerp => Method::Slerp,
                Start::Squad => Method::Squad,
            };
            interpolate(m, keys, n, timing)?
        } else {
            resample(keys, &current, n, timing)?
        };
        let is_key: Vec<bool> = current.iter().map(|f| f.key.is_some()).collect();
        let mut q: Vec<Quat<T>> = current.iter().map(|f| f.q).collect();
        let (mut f, mut g) = energy_and_gradient(&q, &is_key, cfg);
        let mut gn = norm_of(&g);
        let record = |iteration, f: T, gn: T| EnergyRecord {
            level: li,
            iteration,
            frames: n,
            energy: f.to_f64(),
            gradient_norm: gn.to_f64(),
        };
        history.push(record(0, f, gn));
        let mut e = T::from_f64(cfg.step.length());
        // Nesterov state: the next extrapolated point y and its t (after a step, the point
        // the step started from until the loop replaces it).
        let mut momentum: Option<(Vec<Quat<T>>, T)> = None;
        for it in 1..=level.iterations {
            if gn == T::ZERO || gn.to_f64() < cfg.min_gradient_norm {
                break;
            }
            let step = match cfg.step {
                StepRule::Accelerated(_) => {
                    accelerated_step(&q, f, &g, &mut momentum, &mut e, &is_key, cfg)
                }
                _ => plain_step(&q, f, &g, gn, &mut e, &is_key, cfg),
            };
            let (q_new, f_new, g_new) = match step {
                Step::Stop => break,
                Step::Restart => continue,
                Step::Accept(q_new, f_new, g_new) => (q_new, f_new, g_new),
            };
            let change = ((f - f_new).abs() / f.abs().max(T::from_f64(f64::MIN_POSITIVE))).to_f64();
            if let Some((_, t)) = momentum.take() {
                // Extrapolate from the accepted point: y = x_new + β (x_new − x).
                let beta = (t - T::ONE) / y_t_next(t);
                let y_new = q_new
                    .iter()
                    .zip(&q)
                    .map(|(a, b)| *a + (*a - *b) * beta)
                    .collect();
                momentum = Some((y_new, y_t_next(t)));
            }
            q = q_new;
            f = f_new;
            g = g_new;
            gn = norm_of(&g);
            history.push(record(it, f, gn));
            progress(&Progress {
                level: li,
                levels,
                iteration: it,
                iterations: level.iterations,
                energy: f.to_f64(),
            });
            if change < cfg.min_energy_change {
                break;
            }
        }
        for (fr, qi) in current.iter_mut().zip(q) {
            fr.q = qi;
        }
    }
    for fr in current.iter_mut() {
        fr.q = fr.q.normalize()?;
    }
    Ok(SpringResult {
        frames: current,
        history,
        stopped: Stopped::LevelsDone,
    })
}

/// The previous level's curve at `n` frames: within each key interval, new frames at
/// equal fractions, each by Slerp between the two (normalized) old frames around it.
pub(super) fn resample<T: Real>(
    keys: &KeyFrames<T>,
    old: &[Frame<T>],
    n: usize,
    timing: Timing,
) -> Result<Vec<Frame<T>>> {
    let counts = timing::distribute(keys, n, timing)?;
    let grid = timing::samples::<T>(&counts);
    // Old frames per interval, keys at both ends.
    let key_pos: Vec<usize> = old
        .iter()
        .enumerate()
        .filter_map(|(i, f)| f.key.map(|_| i))
        .collect();
    grid.iter()
        .map(|s| {
            let (a, b) = (key_pos[s.interval], key_pos[s.interval + 1]);
            let q = match s.key {
                Some(k) => keys.quats()[k],
                None => {
                    let x = s.h.to_f64() * (b - a) as f64;
                    let m = (x.floor() as usize).min(b - a - 1);
                    let frac = T::from_f64(x - m as f64);
                    let p0 = old[a + m].q.normalize()?;
                    let p1 = old[a + m + 1].q.normalize()?;
                    slerp(p0, p1, frac)
                }
            };
            Ok(Frame {
                q,
                t: keys.parameter(s.interval, s.h),
                key: s.key,
            })
        })
        .collect()
}
