//! Past Dam et al. 1998: §8.2's future work, on the report's own examples.
//!
//! * "a more robust numerical solution with a faster convergence": Spring solved to its
//!   optimum by Newton's method on the unit quaternions (`chasles::interp::Solver::Converged`)
//!   against the report's gradient descent, on Table 5.1 at 550 frames (the energy of eq.
//!   6.23 each reaches, and the time).
//! * §7.6's remark: "an algorithm with a better numerical approximation [...] would produce
//!   the same result — without having to fit the parameters of the program to the example":
//!   the converged solver with no key weight (c_k = 1) on the set of Figures 7.11–7.12, by
//!   the geodesic curvature of the curve (largest, and at the centre key) against Squad's
//!   (Figure 7.11) and the report's Spring with c_k = 4 (Figure 7.12). Found against the
//!   report: the minimum of eq. 6.23 (with c_k = 1, and with the c_k = 4 energy of Figure
//!   7.12 too) keeps a geodesic curvature of about 3.1 near the centre key (Squad 3.6);
//!   Figure 7.12's 1.9 belongs to a curve whose own weighted energy is 16 % above that
//!   minimum — the descent stopped short, and the rounding is its artefact.
//! * "the ability to supply the angular velocity at an arbitrary key frame" (generalizing
//!   Barr et al. 1992's angular velocity constraints at the first and last key): Squad
//!   and the converged Spring through Table 5.1 with an angular velocity at a key, the
//!   velocity measured on each curve beside the key.

use super::dam_figures::{energy, picture, run, Curve, Keys, Run, Spec};
use super::squad_and_spring::{curvature_near_key, geodesic};
use super::Figures;
use crate::claim::Paper::Dam1998;
use crate::section::Section;
use crate::table::{Cell, Number, Table};
use chasles::interp::{
    examples, spring, Hemisphere, KeyFrames, Method, SpringConfig, Squad, Timing,
};
use chasles::Vec3;
use std::time::Instant;

/// §8.2's words on the numerical solution.
const FASTER: &str = "Therefore it would be more realistic to establish a more robust numerical solution with a faster convergence.";
/// §7.6's remark.
const SAME_RESULT: &str = "we have no doubt that an algorithm with a better numerical approximation for the constituent expressions (in particular q_i'' in equation 6.26) would produce the same result — without having to fit the parameters of the program to the example.";
/// §8.2's words on key velocities.
const VELOCITY: &str = "An obvious generalization of this would be the ability to supply the angular velocity at an arbitrary key frame.";

/// A figure-like run: `curve` through `keys` at `frames` frames by angle.
fn spec(keys: Keys, curve: Curve, frames: usize) -> Spec {
    Spec {
        number: "§8.2",
        caption: "",
        keys,
        curve,
        frames,
        timing: Timing::Angle,
    }
}

/// Runs `s` and times it.
fn timed(s: &Spec) -> crate::error::Result<(Run, f64)> {
    let start = Instant::now();
    let r = run(s)?;
    Ok((r, start.elapsed().as_secs_f64()))
}

/// The section "beyond the report": the converged solver against the report's descent,
/// §7.6's remark, and key velocities.
pub fn beyond_the_report(figures: Figures) -> Section {
    let mut s = Section::new(
        "Beyond Dam et al. (§8.2): Spring solved to its optimum, §7.6's remark tested, angular velocities at keys",
    );
    s.text("The report's Spring is gradient descent on an energy whose conditioning grows like the fourth power of the frame count; the converged solver (chasles::interp::Solver::Converged) takes Newton steps on the unit quaternions, each solving a band system in time linear in the frames, and stops when the projected gradient has fallen to 1e-10 of its start. `cargo bench -p chasles --bench spring` times it from 550 to 10⁶ frames against the report's descent.");
    s.attempt(Dam1998, "§8.2", FASTER, |s| {
        let t = Keys::Set("table5.1");
        let runs = [
            ("converged (c_k 1)", SpringConfig::converged()),
            ("report: spring preset (c_k 1.3, accelerated)", SpringConfig::spring()),
            ("report: justdoit", SpringConfig::justdoit()),
            ("report: slerpsvupti", SpringConfig::slerpsvupti()),
        ];
        let mut table = Table::new(
            "Table 5.1, 550 frames by angle: the energy of eq. 6.23 (width 1) each solver ends at",
            &["solver", "curvature energy", "above the minimum", "time"],
        );
        let mut made = Vec::new();
        for (name, cfg) in runs {
            let (r, secs) = timed(&spec(t, Curve::Spring(cfg), 550)).map_err(|e| e.to_string())?;
            made.push((name, energy(&r), secs));
        }
        let best = made[0].1;
        for (name, e, secs) in &made {
            table.row(vec![
                Cell::text(*name),
                Cell::Number(Number::sci(*e, 4)),
                Cell::text(format!("{:+.2} %", (e / best - 1.0) * 100.0)),
                Cell::text(format!("{:.1} ms", secs * 1e3)),
            ]);
        }
        s.table(table);
        let (spring_e, spring_t) = (made[1].1, made[1].2);
        Ok::<_, String>((
            format!(
                "converged F = {best:.5e} in {:.1} ms; the report's spring preset stops {:.1} % above it after {:.1} ms",
                made[0].2 * 1e3,
                (spring_e / best - 1.0) * 100.0,
                spring_t * 1e3
            ),
            made.iter().all(|m| m.1 >= best) && made[0].2 < spring_t,
        ))
    });
    s.attempt(Dam1998, "§7.6, Figures 7.11–7.12", SAME_RESULT, |s| {
        let g = Keys::Set("global");
        let (squad, _) = timed(&spec(g, Curve::Piecewise(Method::Squad), 550)).map_err(|e| e.to_string())?;
        let report = super::dam_figures::chapter_7()
            .into_iter()
            .find(|x| x.number == "7.12")
            .ok_or("Figure 7.12's spec is missing")?;
        let (weighted_run, _) = timed(&report).map_err(|e| e.to_string())?;
        let (converged, _) =
            timed(&spec(g, Curve::Spring(SpringConfig::converged()), 430)).map_err(|e| e.to_string())?;
        let mut four = SpringConfig::converged();
        four.key_weight = 4.0;
        let (converged_4, _) =
            timed(&spec(g, Curve::Spring(four.clone()), 430)).map_err(|e| e.to_string())?;
        // The energy Figure 7.12's descent minimizes (c_k = 4), at its curve and at the
        // minimum.
        let weighted = |r: &Run| {
            let q: Vec<_> = r.frames.iter().map(|f| f.q).collect();
            let k: Vec<bool> = r.frames.iter().map(|f| f.key.is_some()).collect();
            chasles::interp::spring::energy_and_gradient(&q, &k, &four).0
        };
        let (fw, f4) = (weighted(&weighted_run), weighted(&converged_4));
        let max = |r: &Run| geodesic(r).into_iter().fold(0.0f64, f64::max);
        let (ks, kw, kc, k4) = (max(&squad), max(&weighted_run), max(&converged), max(&converged_4));
        let (cs, cw, cc, c4) = (
            curvature_near_key(&squad, 2),
            curvature_near_key(&weighted_run, 2),
            curvature_near_key(&converged, 2),
            curvature_near_key(&converged_4, 2),
        );
        if figures == Figures::Draw {
            s.try_figure(
                "beyond-7-12-converged.png",
                Ok::<_, String>(picture(&converged)),
                &format!("The set of Figures 7.11–7.12 (430 frames by angle) by the converged Spring with c_k = 1: largest geodesic curvature {kc:.2}, at the centre key {cc:.2} (Squad, Figure 7.11: {ks:.2} and {cs:.2}; the report's Spring with c_k = 4, Figure 7.12: {kw:.2} and {cw:.2}). Left: the curve on the sphere; right: velocity by eq. 5.1."),
            );
        }
        // "The same result": the converged curve without a key weight as rounded as Figure
        // 7.12's, within a quarter, and rounder than Squad's.
        Ok::<_, String>((
            format!("geodesic curvature, largest and near the centre key: Squad {ks:.2} / {cs:.2}; the report's Spring with c_k = 4 (Figure 7.12) {kw:.2} / {cw:.2}; the minimum of eq. 6.23 with c_k = 1 (converged) {kc:.2} / {cc:.2}, and of the c_k = 4 energy {k4:.2} / {c4:.2}, whose F ({f4:.3e}) is below Figure 7.12's ({fw:.3e}): Figure 7.12 is rounder than the minimum of its own energy — the descent stopped short of it, and a better solver does not give its curve"),
            kc < ks && cc < cs && (kc - kw).abs() <= 0.25 * kw && (cc - cw).abs() <= 0.25 * cw,
        ))
    });
    s.attempt(Dam1998, "§8.2", VELOCITY, |s| {
        let set = examples::table_5_1();
        let w = Vec3::new(0.0, 0.0, 0.0);
        let mut v = vec![None; set.keys.len()];
        v[3] = Some(w);
        let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain)
            .and_then(|k| k.with_velocities(&v))
            .map_err(|e| e.to_string())?;
        // Squad's one-sided velocity at key 3, by a second-order difference in h.
        let sq = Squad::new(&keys).map_err(|e| e.to_string())?;
        let e = 1e-5;
        let q3 = keys.quats()[3];
        let d = (sq.eval(3, 0.0) * -3.0 + sq.eval(3, e) * 4.0 - sq.eval(3, 2.0 * e)) * (0.5 / e);
        let squad_w = ((d * q3.conjugate()).vector() * 2.0).norm();
        let r = spring(&keys, 550, Timing::Angle, &SpringConfig::converged(), &mut |_| {})
            .map_err(|e| e.to_string())?;
        let i = r.frames.iter().position(|f| f.key == Some(3)).ok_or("key 3 is not a frame")?;
        let (b, c) = (r.frames[i], r.frames[i + 1]);
        let spring_w = (c.q * b.q.conjugate()).log().map_err(|e| e.to_string())?.vector().norm()
            * 2.0
            / (c.t - b.t);
        if figures == Figures::Draw {
            let q: Vec<_> = r.frames.iter().map(|f| f.q).collect();
            let run = Run {
                spec: spec(Keys::Set("table5.1"), Curve::Spring(SpringConfig::converged()), 550),
                velocity: chasles::analysis::velocity::velocity_chord(&q),
                frames: r.frames.clone(),
                iterations: r.history.len() - 1,
            };
            s.try_figure(
                "beyond-key-velocity.png",
                Ok::<_, String>(picture(&run)),
                &format!("Table 5.1 by the converged Spring (550 frames by angle) asked to pass its fourth key at rest (angular velocity 0): the velocity graph falls to {spring_w:.1e} rad per unit there and rises again. Squad, asked the same, leaves the key at {squad_w:.1e}."),
            );
        }
        Ok::<_, String>((
            format!("asked for 0 at key 3 of Table 5.1: Squad leaves it at {squad_w:.1e} rad per unit, the converged Spring at {spring_w:.1e}"),
            squad_w < 1e-6 && spring_w < 1e-6,
        ))
    });
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every claim is measured (none fails to run); §7.6's remark does not hold (the
    /// finding), key velocities do. (§8.2's speed verdict compares times: not asserted.)
    #[test]
    fn the_section_measures_each_claim() {
        let s = beyond_the_report(Figures::Skip);
        let claims: Vec<_> = s.claims().collect();
        assert_eq!(claims.len(), 3);
        for c in &claims {
            assert!(
                !matches!(c.verdict, crate::Verdict::Failed(_)),
                "{}",
                c.measured()
            );
        }
        assert!(!claims[1].verdict.agrees(), "{}", claims[1].measured());
        assert!(claims[2].verdict.agrees(), "{}", claims[2].measured());
    }
}
