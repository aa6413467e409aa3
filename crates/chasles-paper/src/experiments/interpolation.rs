//! Dam et al. 1998, chapters 5–6 on Table 5.1's six keys: LinEuler, LinMat, Lerp, Slerp,
//! Squad and Spring through 550 frames shared by interval angle (§6.2), compared by
//! curvature energy (eq. 6.23) and by the angular speed inside each interval (§5.2,
//! eq. 5.1, the chord estimate the report plots), with the velocity graphs (§5.2), sphere
//! plots (§5.3) and the direct visualisation (§5.1); and Proposition 30: Squad is C¹ at
//! the keys. The figures themselves, with their captions' parameters, are in
//! [`super::dam_figures`].

use super::Figures;
use crate::claim::Paper::Dam1998;
use crate::error::Result;
use crate::section::Section;
use crate::table::{Cell, Number, Table};
use chasles::analysis::curvature::{curvature_energy, Width};
use chasles::analysis::velocity::velocity_chord;
use chasles::interp::slerp::slerp;
use chasles::interp::{
    examples, interpolate, spring, Frame, Hemisphere, KeyFrames, Method, SpringConfig, Squad,
    Timing,
};
use chasles::{EulerOrder, Quat};

/// One method's run: its name, frames and velocity.
struct Run {
    name: &'static str,
    frames: Vec<Frame<f64>>,
    velocity: Vec<f64>,
}

/// The largest max/min ratio of the speed `v` inside one interval between keys (frames
/// next to a key left out): 1 for constant speed. The worst interval, not the whole curve,
/// because whole frame counts per interval make the step differ slightly from one interval
/// to the next even for a constant-speed method.
pub fn speed_ratio_within_intervals(frames: &[Frame<f64>], v: &[f64]) -> f64 {
    let mut per_interval: Vec<(f64, f64)> = Vec::new();
    let mut interval = 0;
    for (w, s) in frames.windows(3).zip(&v[1..]) {
        if w[1].key.is_some() {
            interval += 1;
        }
        if w.iter().any(|f| f.key.is_some()) {
            continue;
        }
        if per_interval.len() <= interval {
            per_interval.resize(interval + 1, (f64::MAX, 0.0));
        }
        let r = &mut per_interval[interval];
        *r = (r.0.min(*s), r.1.max(*s));
    }
    per_interval
        .iter()
        .filter(|r| r.1 > 0.0)
        .map(|r| r.1 / r.0)
        .fold(1.0f64, f64::max)
}

/// Curvature energy (eq. 6.23) of the frames' rotations.
pub fn energy(f: &[Frame<f64>]) -> f64 {
    curvature_energy(&f.iter().map(|x| x.q).collect::<Vec<_>>(), Width::Unit)
}

/// The frames of one method (`None`: Spring, §6.3.7) through `keys`.
pub fn frames_of(
    method: Option<Method>,
    keys: &KeyFrames<f64>,
    n: usize,
) -> chasles::Result<Vec<Frame<f64>>> {
    match method {
        Some(m) => interpolate(m, keys, n, Timing::Angle),
        None => Ok(spring(keys, n, Timing::Angle, &SpringConfig::spring(), &mut |_| {})?.frames),
    }
}

/// Table 5.1's keys, brought into one hemisphere chain.
fn table_5_1_keys() -> chasles::Result<KeyFrames<f64>> {
    KeyFrames::new(
        &examples::table_5_1().keys::<f64>(),
        None,
        Hemisphere::Chain,
    )
}

/// The six methods through Table 5.1's keys: energies, speed ratios
/// and, with [`Figures::Draw`], every method's velocity graph, four sphere plots and the
/// turning R of Squad.
pub fn six_methods(figures: Figures) -> Section {
    let mut s = Section::new(
        "Dam et al. ch. 5–6: six methods through Table 5.1's keys (550 frames, §6.2 timing)",
    );
    let methods: [(&str, Option<Method>); 6] = [
        ("lineuler", Some(Method::LinEuler(EulerOrder::DAM))),
        ("linmat", Some(Method::LinMat)),
        ("lerp", Some(Method::Nlerp)),
        ("slerp", Some(Method::Slerp)),
        ("squad", Some(Method::Squad)),
        ("spring", None),
    ];
    let measured = (|| -> Result<Vec<Run>> {
        let keys = table_5_1_keys()?;
        let mut t = Table::new(
            "Table 5.1's keys, 550 frames",
            &[
                "method",
                "curvature energy (eq. 6.23)",
                "speed max/min within an interval (worst)",
            ],
        );
        let mut out = Vec::new();
        for (name, m) in methods {
            let frames = frames_of(m, &keys, 550)?;
            let v = velocity_chord(&frames.iter().map(|f| f.q).collect::<Vec<_>>());
            let ratio = speed_ratio_within_intervals(&frames, &v);
            t.row(vec![
                Cell::text(name),
                Cell::Number(Number::sci(energy(&frames), 4)),
                Cell::Number(Number::fixed(ratio, 3)),
            ]);
            out.push(Run {
                name,
                frames,
                velocity: v,
            });
        }
        s.table(t);
        Ok(out)
    })();
    // The claims these numbers bear on are the figures' own (Figures 5.1, 5.3, 6.1–6.6:
    // `captions`); here the six methods stand side by side on one set of frames.
    if let Err(e) = &measured {
        s.text(format!("the six methods could not be run: {e}"));
    }
    if figures == Figures::Draw {
        if let Ok(rows) = &measured {
            draw(&mut s, rows);
        }
    }
    s
}

/// The velocity graphs and sphere plots of the six methods, and Squad's turning R.
fn draw(s: &mut Section, rows: &[Run]) {
    for Run {
        name,
        frames,
        velocity: v,
        ..
    } in rows
    {
        let keys_at = chasles_viz::graph::key_indices(frames);
        let title = format!("{name}: velocity by eq. 5.1 (chord), Table 5.1 keys");
        s.figure(
            &format!("velocity-{name}.svg"),
            chasles_viz::graph::velocity_svg(v, &keys_at, &title).into_bytes(),
            &format!(
                "§5.2: velocity of {name} by eq. 5.1 (the chord estimate) against the frame index, first and last frame left out; * marks the key frames"
            ),
        );
        if matches!(*name, "lineuler" | "lerp" | "slerp" | "squad") {
            s.figure(
                &format!("sphere-{name}.png"),
                chasles_viz::sphere::render_frames(frames, 420).png(),
                &format!("§5.3: the {name} curve on the unit sphere (z = 0 for all of Table 5.1's keys); first key large, keys medium, frames small; frames inside the sphere show dimmed"),
            );
        }
    }
    let gif = (|| -> Result<Vec<u8>> {
        let squad = interpolate(Method::Squad, &table_5_1_keys()?, 96, Timing::Angle)?;
        let turned: Vec<Quat<f64>> = squad.iter().map(|f| f.q).collect();
        Ok(chasles_viz::gif(
            &chasles_viz::letter::animate(&turned, 240),
            5,
        )?)
    })();
    s.try_figure(
        "letter-squad.gif",
        gif,
        "§5.1, direct visualisation: an extruded R turned by the 96 Squad frames through Table 5.1's keys",
    );
}

/// Proposition 30: the jump of dq/dh at the inner keys, Squad against Slerp.
pub fn squad_continuity() -> Section {
    let mut s = Section::new("Dam et al. Proposition 30: Squad is C¹ at the key frames");
    s.attempt(
        Dam1998,
        "Proposition 30",
        "Squad is C¹ at the key frames (Slerp is not)",
        |s| -> chasles::Result<_> {
            let keys = table_5_1_keys()?;
            let sq = Squad::new(&keys)?;
            let q = keys.quats();
            let jump = |f: &dyn Fn(usize, f64) -> Quat<f64>| {
                (1..q.len() - 1)
                    .map(|k| {
                        let d = 1e-4;
                        let l = (f(k - 1, 1.0) * 3.0 - f(k - 1, 1.0 - d) * 4.0
                            + f(k - 1, 1.0 - 2.0 * d))
                            / (2.0 * d);
                        let r = (f(k, 0.0) * -3.0 + f(k, d) * 4.0 - f(k, 2.0 * d)) / (2.0 * d);
                        (l - r).norm()
                    })
                    .fold(0.0f64, f64::max)
            };
            let (jq, js) = (
                jump(&|i, h| sq.eval(i, h)),
                jump(&|i, h| slerp(q[i], q[i + 1], h)),
            );
            s.text("One-sided derivatives dq/dh at Table 5.1's inner keys, by second-order differences.");
            Ok((
                format!("largest jump of dq/dh at a key: Squad {jq:.1e}, Slerp {js:.2}"),
                jq < 1e-3 && js > 0.1,
            ))
        },
    );
    s
}
