//! Dam et al. 1998's interpolation figures, each with the parameters its caption gives:
//! Figures 5.1–5.3 (Slerp, Squad, LinEuler through Table 5.1), 6.1–6.3 and 6.6 (LinEuler,
//! LinMat, Lerp, Slerp between two keys, 300 frames), 6.7 and 6.8 (Slerp, 750 frames
//! uniform and 550 by angle), 6.11 (Squad), 6.15–6.17 (one step of 350 frames and 500
//! iterations against the multi-step scheme's 22 → 110 → 550 frames and 200/150/100
//! iterations), 6.18–6.19 (a sharp curve, 200 frames, c_k 1 and 1.2), 6.20 (Spring, 550
//! frames, c_k 1.3) and 7.1–7.12 (Squad and Spring on chapter 7's sets; the section and
//! its outcomes by number are [`super::squad_and_spring`]). Every figure is
//! the paper's pair: the curve on the sphere (§5.3) beside its velocity graph (§5.2, eq.
//! 5.1 — the chord estimate the report plots — with the first and last frame left out and
//! the keys starred).
//!
//! What the captions leave open is fixed here and said in each caption: chapter 5's
//! figures share 550 frames equally among the intervals; the two keys of
//! Figures 6.1–6.6 are Table 5.1's first two; the "sharp curve" of 6.18–6.19 is chapter 7's
//! cusp set; "700 iterations distributed over three steps" are split in the report's
//! 200 : 150 : 100 proportion (311, 233, 156; 900 as 400, 300, 200) over its 22/550 and
//! 110/550 fractions of the frames; the step is `justdoit`'s. Frame counts are totals,
//! keys included.

use super::Figures;
use crate::claim::Paper::Dam1998;
use crate::error::Result;
use crate::section::{PaperFigure, Section};
use crate::table::{Cell, Number, Table};
use chasles::analysis::curvature::{curvature_energy, Width};
use chasles::analysis::velocity::velocity_chord;
use chasles::interp::{
    examples, interpolate, spring, Frame, Hemisphere, KeyFrames, Level, Method, SpringConfig,
    Timing,
};
use chasles::EulerOrder;

/// Which keys a figure interpolates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Keys {
    /// Table 5.1's first two keys (Figures 6.1–6.6).
    FirstTwo,
    /// A built-in set by name (`chasles::interp::examples`).
    Set(&'static str),
}

/// How a figure's curve is made.
#[derive(Debug, Clone, PartialEq)]
pub enum Curve {
    /// A piecewise method.
    Piecewise(Method),
    /// Spring's gradient descent with this configuration.
    Spring(SpringConfig),
}

/// One of the report's figures: its number and caption, and what reproduces it.
#[derive(Debug, Clone, PartialEq)]
pub struct Spec {
    /// The figure's number, e.g. `6.15`.
    pub number: &'static str,
    /// Its caption, word for word.
    pub caption: &'static str,
    /// The keys.
    pub keys: Keys,
    /// The curve.
    pub curve: Curve,
    /// Frames in total, keys included.
    pub frames: usize,
    /// How frames are shared among the intervals.
    pub timing: Timing,
}

/// A figure's curve, made.
pub struct Run {
    /// The figure.
    pub spec: Spec,
    /// The frames.
    pub frames: Vec<Frame<f64>>,
    /// Eq. 5.1 per frame.
    pub velocity: Vec<f64>,
    /// Gradient-descent iterations made (0 for a piecewise method).
    pub iterations: usize,
}

/// The report's multi-step Spring (`justdoit`'s step) with `iterations` spread over its
/// three steps in the proportion 200 : 150 : 100, and key weight `c_k`.
fn three_steps(iterations: usize, c_k: f64) -> SpringConfig {
    let mut c = SpringConfig::justdoit();
    let first = iterations * 200 / 450;
    let second = iterations * 150 / 450;
    for (l, n) in c
        .levels
        .iter_mut()
        .zip([first, second, iterations - first - second])
    {
        l.iterations = n;
    }
    c.key_weight = c_k;
    c
}

/// One step of `iterations` from Slerp (`slerpsvupti`).
fn one_step(iterations: usize) -> SpringConfig {
    let mut c = SpringConfig::slerpsvupti();
    c.levels = vec![Level {
        fraction: 1.0,
        iterations,
    }];
    c
}

fn spec(
    number: &'static str,
    caption: &'static str,
    keys: Keys,
    curve: Curve,
    frames: usize,
    timing: Timing,
) -> Spec {
    Spec {
        number,
        caption,
        keys,
        curve,
        frames,
        timing,
    }
}

use Curve::{Piecewise as P, Spring as S};
use Keys::{FirstTwo, Set};
use Timing::{Angle, Uniform};

/// Figures 5.1–5.3: Slerp, Squad and LinEuler through Table 5.1, 550 frames shared equally
/// among the intervals (chapter 5 comes before §6.2's sharing by angle, and Figure 5.1's
/// "piecewise continuous" velocity, constant between keys, is what equal shares give).
pub fn chapter_5() -> Vec<Spec> {
    let t = Set("table5.1");
    vec![
        spec("5.1", "The interpolation curve stays on the surface of the sphere, but it is not differentiable in any key frames; the curve \u{201c}breaks\u{201d} when it passes through the key frames. The angular velocity graph is piecewise continuous and shows that the angular velocity is constant between keys. This method of interpolation is called Slerp and is described in section 6.1.5.", t, P(Method::Slerp), 550, Uniform),
        spec("5.2", "The interpolation curve is now differentiable through all key frames. Compare, for example, the key frame in the middle of the figure with the corresponding key frame in figure 5.1. The angular velocity graph is continuous and assumes local minima at the key frames. This interpolation curve is called Squad, and it is described in section 6.2.1.", t, P(Method::Squad), 550, Uniform),
        spec("5.3", "This interpolation curve dips below the surface of the three-dimensional unit sphere. This means that the interpolated points are not unit quaternions, and thus the points do not lie on the surface of the sphere. The angular velocity graph is piecewise linear. This interpolation curve is called LinEuler, and is described in section 6.1.1", t, P(Method::LinEuler(EulerOrder::DAM)), 550, Uniform),
    ]
}

/// Figures 6.1–6.3, 6.6–6.8, 6.11 and 6.15–6.20.
pub fn chapter_6() -> Vec<Spec> {
    let t = Set("table5.1");
    let mut sharp_12 = SpringConfig::justdoit();
    sharp_12.key_weight = 1.2;
    let first_step = one_step(200);
    let mut spring_13 = SpringConfig::justdoit();
    spring_13.key_weight = 1.3;
    vec![
        spec("6.1", "Interpolation curve and velocity graph for Linear Euler interpolation \u{2014} LinEuler. Between the two key frames are 300 interpolated frames.", FirstTwo, P(Method::LinEuler(EulerOrder::DAM)), 300, Uniform),
        spec("6.2", "Interpolation curve and velocity graph for linear matrix interpolation \u{2014} LinMat. Between the two key frames are 300 interpolated frames.", FirstTwo, P(Method::LinMat), 300, Uniform),
        spec("6.3", "Interpolation curve and velocity graph for linear quaternion interpolation \u{2014} Lerp. Between the two key frames are 300 interpolated frames.", FirstTwo, P(Method::Nlerp), 300, Uniform),
        spec("6.6", "Interpolation curve and velocity graph for spherical linear quaternion interpolation \u{2013} Slerp. Between the two key frames there are 300 interpolated frames.", FirstTwo, P(Method::Slerp), 300, Uniform),
        spec("6.7", "Interpolation curve and angular velocity graph for Slerp. Between the six key frames, 750 interpolated frames have been generated.", t, P(Method::Slerp), 750, Uniform),
        spec("6.8", "Interpolation curve and angular velocity graph for Slerp. Between the six key frames, 550 interpolated frames have been generated. The frames in the subintervals are distributed according to length of the interval.", t, P(Method::Slerp), 550, Angle),
        spec("6.11", "Interpolation curve and angular velocity graph for Squad. Between the six key frames we have interpolated 550 frames. The frames have been distributed according to interval length.", t, P(Method::Squad), 550, Angle),
        spec("6.15", "One-step iteration. The interpolation curve contains 350 frames, and is shown after 500 iterations.", t, S(one_step(500)), 350, Angle),
        spec("6.16", "The multi-step algorithm, first step. In the first step only 22 frames and 200 iterations are used.", t, S(first_step), 22, Angle),
        spec("6.17", "The multi-step algorithm, final result. In the second step, 110 frames are interpolated using 150 iterations. In the third and final step, 550 frames and 100 iterations are used.", t, S(SpringConfig::justdoit()), 550, Angle),
        spec("6.18", "The multi-step algorithm used on a set of key frames with a sharp curve. 200 frames are interpolated.", Set("cusp"), S(SpringConfig::justdoit()), 200, Angle),
        spec("6.19", "The multi-step algorithm with a set of key frames with a sharp curve. 200 frames are interpolated, and the curvature around the key frames are weighted with a factor 1.2", Set("cusp"), S(sharp_12), 200, Angle),
        spec("6.20", "The effect of Spring. 550 frames have been interpolated and curvature is weighted with a factor 1.3", t, S(spring_13), 550, Angle),
    ]
}

/// Figures 7.1–7.12: Squad and Spring on chapter 7's six sets.
pub fn chapter_7() -> Vec<Spec> {
    let sq = || P(Method::Squad);
    vec![
        spec("7.1", "A simple curve with soft rounded corners interpolated with Squad. A total of 550 frames have been used in the interpolation.", Set("semicircle"), sq(), 550, Angle),
        spec("7.2", "A simple curve with soft rounded corners interpolated with Spring. A total of 430 frames and 700 iterations in the steps have been used. No extra weight on the curvature at the key frames has been added (see section 6.3.7 page 73).", Set("semicircle"), S(three_steps(700, 1.0)), 430, Angle),
        spec("7.3", "Interpolation with Squad of a soft curve with an intersection. A total of 550 frames have been used in the interpolation.", Set("soft"), sq(), 550, Angle),
        spec("7.4", "Interpolation with Spring of a soft curve with an intersection. A total of 550 frames and 700 iterations distributed over the interpolation steps. No extra weight is added to the curvature around the key frames (see section 6.3.7 page 73)", Set("soft"), S(three_steps(700, 1.0)), 550, Angle),
        spec("7.5", "A curve with a cusp interpolated with Squad. 200 frames have been used.", Set("cusp"), sq(), 200, Angle),
        spec("7.6", "A curve with a cusp interpolated with Spring. A total of 200 frames and 700 iterations distributed over three steps. The relative weight of the curvature around the key frames is 1.3 (see section 6.3.7 page 73).", Set("cusp"), S(three_steps(700, 1.3)), 200, Angle),
        spec("7.7", "Squad displaying pendulum motion over 250 frames.", Set("pendulum"), sq(), 250, Angle),
        spec("7.8", "Spring displaying pendulum motion over 200 frames and 700 iterations in three steps. The relative weight of the curvature around the key frames is 1.5 (see section 6.3.7 page 73).", Set("pendulum"), S(three_steps(700, 1.5)), 200, Angle),
        spec("7.9", "The perturbed pendulum interpolated by Squad using 250 frames.", Set("perturbed"), sq(), 250, Angle),
        spec("7.10", "The perturbed pendulum interpolated by Spring using 200 frames and 700 iterations in three steps. The relative weight of the curvature around the key frames is 1.5 (see section 6.3.7 page 73)", Set("perturbed"), S(three_steps(700, 1.5)), 200, Angle),
        spec("7.11", "Squad producing pointy curve using 550 frames.", Set("global"), sq(), 550, Angle),
        spec("7.12", "Spring avoiding the pointy curve using 430 frames and 900 iterations. The relative weight of the curvature around the key frames is 4 (see section 6.3.7 page 73).", Set("global"), S(three_steps(900, 4.0)), 430, Angle),
    ]
}

/// The keys of `k`, brought into one hemisphere chain.
pub fn keys_of(k: Keys) -> Result<KeyFrames<f64>> {
    let (name, take) = match k {
        Keys::FirstTwo => ("table5.1", 2),
        Keys::Set(name) => (name, usize::MAX),
    };
    let set = examples::by_name(name).ok_or_else(|| crate::Error::NoKeySet(name.to_string()))?;
    let q: Vec<_> = set.keys::<f64>().into_iter().take(take).collect();
    Ok(KeyFrames::new(&q, None, Hemisphere::Chain)?)
}

/// Makes a figure's curve.
pub fn run(spec: &Spec) -> Result<Run> {
    let keys = keys_of(spec.keys)?;
    let (frames, iterations) = match &spec.curve {
        Curve::Piecewise(m) => (interpolate(*m, &keys, spec.frames, spec.timing)?, 0),
        Curve::Spring(cfg) => {
            let r = spring(&keys, spec.frames, spec.timing, cfg, &mut |_| {})?;
            let n = r.history.iter().filter(|h| h.iteration > 0).count();
            (r.frames, n)
        }
    };
    let velocity = velocity_chord(&frames.iter().map(|f| f.q).collect::<Vec<_>>());
    Ok(Run {
        spec: spec.clone(),
        frames,
        velocity,
        iterations,
    })
}

/// The method's name as the report writes it.
fn method_name(c: &Curve) -> String {
    match c {
        Curve::Piecewise(Method::LinEuler(_)) => "LinEuler".into(),
        Curve::Piecewise(Method::LinMat) => "LinMat".into(),
        Curve::Piecewise(Method::Lerp) => "Lerp (raw)".into(),
        Curve::Piecewise(Method::Nlerp) => "Lerp".into(),
        Curve::Piecewise(Method::Slerp) => "Slerp".into(),
        Curve::Piecewise(Method::Squad) => "Squad".into(),
        Curve::Piecewise(Method::CatmullRom) => "Catmull-Rom".into(),
        Curve::Piecewise(Method::KochanekBartels(_)) => "Kochanek-Bartels".into(),
        Curve::Piecewise(Method::Bezier) => "Bezier".into(),
        Curve::Piecewise(Method::C2) => "C2 spline".into(),
        Curve::Spring(cfg) => {
            let steps: Vec<String> = cfg
                .levels
                .iter()
                .map(|l| l.iterations.to_string())
                .collect();
            format!(
                "Spring ({} step{}, {} iterations, c_k {})",
                cfg.levels.len(),
                if cfg.levels.len() == 1 { "" } else { "s" },
                steps.join("/"),
                cfg.key_weight
            )
        }
    }
}

fn keys_name(k: Keys) -> String {
    match k {
        Keys::FirstTwo => "Table 5.1's first two keys".into(),
        Keys::Set("table5.1") => "Table 5.1's keys".into(),
        Keys::Set(n) => format!("the {n} set"),
    }
}

/// The velocity of the inner frames (the report's graphs leave the first and last out).
pub(crate) fn inner(v: &[f64]) -> &[f64] {
    if v.len() > 2 {
        &v[1..v.len() - 1]
    } else {
        v
    }
}

/// Max/min of the velocity over the inner frames.
pub fn speed_spread(r: &Run) -> f64 {
    let (lo, hi) = inner(&r.velocity)
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), v| (a.min(*v), b.max(*v)));
    hi / lo
}

/// The curvature energy (eq. 6.23, l = 1) of the run's frames.
pub fn energy(r: &Run) -> f64 {
    curvature_energy(
        &r.frames.iter().map(|f| f.q).collect::<Vec<_>>(),
        Width::Unit,
    )
}

/// The pair of pictures, the sphere (§5.3) left and the velocity graph (eq. 5.1) right.
pub fn picture(r: &Run) -> Vec<u8> {
    let keys = chasles_viz::graph::key_indices(&r.frames);
    let sphere = chasles_viz::sphere::render_frames(&r.frames, 400);
    let graph = chasles_viz::graph::velocity_png(&r.velocity, &keys, 600, 400);
    chasles_viz::Image::side_by_side(&[sphere, graph]).png()
}

/// Our caption of a run.
fn caption(r: &Run) -> String {
    let s = &r.spec;
    format!(
        "{} through {}, {} frames ({}){}: curvature energy (eq. 6.23, l = 1) {:.3e}, velocity max/min {:.2}. Left: the curve on the sphere of (w, x, y) (z = 0 at the keys; first key large, keys medium, frames small, frames off the sphere dimmed). Right: velocity by eq. 5.1 (the chord estimate) against the frame, first and last frame left out, * at the keys.",
        method_name(&s.curve),
        keys_name(s.keys),
        s.frames,
        match s.timing {
            Timing::Uniform => "uniform",
            Timing::Angle => "by interval angle, §6.2",
        },
        if r.iterations > 0 {
            format!(", {} iterations made", r.iterations)
        } else {
            String::new()
        },
        energy(r),
        speed_spread(r),
    )
}

/// Runs `specs` into a section titled `title`: a table of every figure's numbers and,
/// with [`Figures::Draw`], every figure beside the paper's caption. A figure whose curve
/// fails is reported by name. Returns the runs too, for claims on them.
pub fn section(title: &str, specs: &[Spec], figures: Figures) -> (Section, Vec<Run>) {
    let mut s = Section::new(title);
    let mut t = Table::new(
        "each figure with its caption's parameters",
        &[
            "figure",
            "method",
            "keys",
            "frames",
            "iterations",
            "curvature energy (eq. 6.23)",
            "velocity max/min",
        ],
    );
    let mut runs = Vec::new();
    for spec in specs {
        match run(spec) {
            Ok(r) => {
                t.row(vec![
                    Cell::text(spec.number),
                    Cell::text(method_name(&spec.curve)),
                    Cell::text(keys_name(spec.keys)),
                    Cell::Number(Number::integer(spec.frames as u64)),
                    Cell::Number(Number::integer(r.iterations as u64)),
                    Cell::Number(Number::sci(energy(&r), 3)),
                    Cell::Number(Number::fixed(speed_spread(&r), 2)),
                ]);
                runs.push(r);
            }
            Err(e) => s.text(format!("Figure {} could not be made: {e}", spec.number)),
        }
    }
    s.table(t);
    if figures == Figures::Draw {
        for r in &runs {
            let file = format!("dam-figure-{}.png", r.spec.number.replace('.', "-"));
            s.paper_figure(
                PaperFigure::new(Dam1998, r.spec.number, r.spec.caption),
                &file,
                Ok::<_, String>(picture(r)),
                &caption(r),
            );
        }
    }
    (s, runs)
}

/// [`section`] of `specs` with `claims` checked on its runs.
pub fn checked_section(
    title: &str,
    specs: &[Spec],
    figures: Figures,
    claims: fn(&mut Section, &[Run]),
) -> Section {
    let (mut s, runs) = section(title, specs, figures);
    claims(&mut s, &runs);
    s
}

/// Figures 5.1–5.3 as a section, with their captions checked.
pub fn chapter_5_section(figures: Figures) -> Section {
    checked_section(
        "Dam et al. ch. 5: Figures 5.1–5.3, the curve on the sphere and its velocity (Table 5.1's keys)",
        &chapter_5(),
        figures,
        super::captions::chapter_5_claims,
    )
}

/// Figures 6.1–6.20 as a section, with their captions checked.
pub fn chapter_6_section(figures: Figures) -> Section {
    checked_section(
        "Dam et al. ch. 6: Figures 6.1–6.20, each method with its caption's frames, steps and weights",
        &chapter_6(),
        figures,
        super::captions::chapter_6_claims,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every figure's parameters are its caption's: frames, iterations and weights.
    #[test]
    fn the_figures_have_their_captions_parameters() {
        let all: Vec<Spec> = [chapter_5(), chapter_6(), chapter_7()].concat();
        let numbers: Vec<&str> = all.iter().map(|s| s.number).collect();
        assert_eq!(
            numbers,
            [
                "5.1", "5.2", "5.3", "6.1", "6.2", "6.3", "6.6", "6.7", "6.8", "6.11", "6.15",
                "6.16", "6.17", "6.18", "6.19", "6.20", "7.1", "7.2", "7.3", "7.4", "7.5", "7.6",
                "7.7", "7.8", "7.9", "7.10", "7.11", "7.12"
            ]
        );
        let by = |n: &str| all.iter().find(|s| s.number == n).unwrap();
        let iters = |n: &str| match &by(n).curve {
            Curve::Spring(c) => (
                c.levels.iter().map(|l| l.iterations).collect::<Vec<_>>(),
                c.key_weight,
            ),
            Curve::Piecewise(_) => (Vec::new(), 0.0),
        };
        for (n, frames, its, ck) in [
            ("6.15", 350, vec![500], 1.0),
            ("6.16", 22, vec![200], 1.0),
            ("6.17", 550, vec![200, 150, 100], 1.0),
            ("6.18", 200, vec![200, 150, 100], 1.0),
            ("6.19", 200, vec![200, 150, 100], 1.2),
            ("6.20", 550, vec![200, 150, 100], 1.3),
            ("7.2", 430, vec![311, 233, 156], 1.0),
            ("7.4", 550, vec![311, 233, 156], 1.0),
            ("7.6", 200, vec![311, 233, 156], 1.3),
            ("7.8", 200, vec![311, 233, 156], 1.5),
            ("7.10", 200, vec![311, 233, 156], 1.5),
            ("7.12", 430, vec![400, 300, 200], 4.0),
        ] {
            assert_eq!(by(n).frames, frames, "{n}");
            assert_eq!(iters(n), (its, ck), "{n}");
        }
        for (n, frames) in [
            ("6.1", 300),
            ("6.7", 750),
            ("6.8", 550),
            ("7.5", 200),
            ("7.7", 250),
            ("7.9", 250),
            ("7.11", 550),
        ] {
            assert_eq!(by(n).frames, frames, "{n}");
        }
        assert_eq!(by("6.7").timing, Timing::Uniform);
        assert_eq!(by("6.8").timing, Timing::Angle);
    }

    /// Slerp between two keys is one great arc at one speed (Figure 6.6), LinEuler's is
    /// not (6.1); Figure 6.7's uniform frames give Slerp a speed that jumps between
    /// intervals, 6.8's by-angle frames nearly none.
    #[test]
    fn the_two_key_and_slerp_figures_show_what_their_captions_say() {
        let ch6 = chapter_6();
        let get = |n: &str| run(ch6.iter().find(|s| s.number == n).unwrap()).unwrap();
        assert!(speed_spread(&get("6.6")) < 1.0 + 1e-9);
        assert!(speed_spread(&get("6.1")) > 1.05);
        let (uniform, by_angle) = (speed_spread(&get("6.7")), speed_spread(&get("6.8")));
        assert!(uniform > 1.3 && by_angle < 1.1, "{uniform} {by_angle}");
    }
}
