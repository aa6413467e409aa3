//! Dam et al. 1998's figures of chapters 5 and 6 checked against what their captions and
//! the text beside them say, by number, on the runs of [`super::dam_figures`] (each with
//! its caption's parameters): a verdict for every figure.
//!
//! * 5.1 / 6.8 Slerp: on the sphere, constant speed between the keys (up to whole frame
//!   counts); 5.2 / 6.11 Squad: the velocity continuous, with local minima at the keys;
//!   5.3 / 6.1 LinEuler: unit quaternions that leave the keys' space z = 0 which the sphere
//!   shows (the "dip"), at a speed that is not constant; 6.2 LinMat: not constant speed;
//!   6.3 Lerp: faster in the middle; 6.6 Slerp: one speed, one great arc.
//! * 6.7 against 6.8: uniform frames make Slerp's speed differ from interval to interval,
//!   frames by angle only by rounding; 6.11: sharing Squad's frames by interval angle, "a
//!   simple and effective heuristic", evens its speed out without making it constant.
//! * 6.15 against 6.17: the one-step velocity "resembles an electrocardiogram" (a larger
//!   total variation of the velocity over its maximum) and its curve is less round at the
//!   keys (geodesic curvature); 6.16: the first step lowers the energy of its Slerp start;
//!   6.18 against 6.19: c_k = 1.2 lowers the curvature at the sharp key; 6.20 against 6.17:
//!   c_k = 1.3 is "only marginally better".

use super::dam_figures::{energy, inner, run, speed_spread, Curve, Run, Spec};
use super::interpolation::speed_ratio_within_intervals;
use super::squad_and_spring::{curvature_near_key, key_frame};
use crate::claim::Paper::Dam1998;
use crate::section::Section;
use chasles::interp::{Method, Timing};

/// The run of figure `n`, or why there is none.
fn get<'a>(runs: &'a [Run], n: &str) -> Result<&'a Run, String> {
    runs.iter()
        .find(|r| r.spec.number == n)
        .ok_or_else(|| format!("Figure {n} was not made"))
}

/// The largest distance of a frame from the unit sphere.
fn off_unit(r: &Run) -> f64 {
    r.frames
        .iter()
        .map(|f| (f.q.norm() - 1.0).abs())
        .fold(0.0, f64::max)
}

/// The largest |z| of a unit frame: how far it leaves the keys' space z = 0 (the sphere of
/// (w, x, y) the pictures show).
fn off_picture(r: &Run) -> f64 {
    r.frames
        .iter()
        .map(|f| (f.q.z / f.q.norm()).abs())
        .fold(0.0, f64::max)
}

/// The total variation of the velocity (inner frames) over its maximum: small for a smooth
/// graph whatever the frame count, large for a jagged one.
fn roughness(r: &Run) -> f64 {
    let v = inner(&r.velocity);
    let max = v.iter().copied().fold(0.0, f64::max);
    v.windows(2).map(|w| (w[1] - w[0]).abs()).sum::<f64>() / max
}

/// The number of inner keys of the run.
fn inner_keys(r: &Run) -> usize {
    r.frames
        .iter()
        .filter(|f| f.key.is_some())
        .count()
        .saturating_sub(2)
}

/// The largest geodesic curvature near any inner key.
fn worst_at_keys(r: &Run) -> f64 {
    (1..=inner_keys(r))
        .map(|k| curvature_near_key(r, k))
        .fold(0.0, f64::max)
}

/// Chapter 5's three figures, checked.
pub fn chapter_5_claims(s: &mut Section, runs: &[Run]) {
    s.attempt(Dam1998, "Figure 5.1", "The interpolation curve stays on the surface of the sphere [...] the angular velocity is constant between keys", |_| {
        let r = get(runs, "5.1")?;
        let (unit, ratio) = (off_unit(r), speed_ratio_within_intervals(&r.frames, &r.velocity));
        Ok::<_, String>((
            format!("frames off the unit sphere by at most {unit:.0e}; velocity max/min inside an interval {ratio:.6}"),
            unit < 1e-12 && ratio < 1.001,
        ))
    });
    s.attempt(Dam1998, "Figure 5.2", "The angular velocity graph is continuous and assumes local minima at the key frames", |_| {
        let r = get(runs, "5.2")?;
        let v = &r.velocity;
        let keys: Vec<usize> = (1..=inner_keys(r)).filter_map(|k| key_frame(r, k)).collect();
        let minima: Vec<usize> = (1..v.len() - 1).filter(|&i| v[i] <= v[i - 1] && v[i] <= v[i + 1]).collect();
        // How far each inner key is from the nearest local minimum of the velocity.
        let off: Vec<usize> = keys.iter().map(|&k| minima.iter().map(|&m| m.abs_diff(k)).min().unwrap_or(usize::MAX)).collect();
        let worst = off.iter().copied().max().unwrap_or(0);
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        let jump = inner(v).windows(2).map(|w| (w[1] - w[0]).abs()).fold(0.0, f64::max) / mean;
        Ok::<_, String>((
            format!("the velocity has a local minimum within {worst} frames of each of the {} inner keys (offsets {off:?}, of {} frames); its largest step from frame to frame is {jump:.3} of its mean", keys.len(), v.len()),
            worst * 100 <= v.len() && jump < 0.05,
        ))
    });
    s.attempt(Dam1998, "Figure 5.3, §6.1.1", "This interpolation curve dips below the surface of the three-dimensional unit sphere [...] (§6.1.1: The curve consists of unit quaternions but their z coordinate is not generally equal to zero. Therefore the curve disappears from the surface of the sphere in the illustration.)", |_| {
        let r = get(runs, "5.3")?;
        let (unit, z) = (off_unit(r), off_picture(r));
        Ok::<_, String>((
            format!("frames are unit to {unit:.0e}, and leave the keys' z = 0 by up to {z:.3}: off the sphere the picture shows"),
            unit < 1e-12 && z > 0.05,
        ))
    });
}

/// Chapter 6's figures, checked.
pub fn chapter_6_claims(s: &mut Section, runs: &[Run]) {
    s.attempt(Dam1998, "Figures 6.1–6.3, 6.6", "LinEuler, LinMat and Lerp do not move at constant speed — Lerp has larger velocity in the middle of the curve — while Slerp has constant angular velocity (between two keys, 300 frames)", |_| {
        let (e, m, l, sl) = (get(runs, "6.1")?, get(runs, "6.2")?, get(runs, "6.3")?, get(runs, "6.6")?);
        let v = &l.velocity;
        let (mid, end) = (v[v.len() / 2], v[1]);
        let (se, sm, ss) = (speed_spread(e), speed_spread(m), speed_spread(sl));
        Ok::<_, String>((
            format!("velocity max/min: LinEuler {se:.3}, LinMat {sm:.3}, Slerp {ss:.9}; Lerp's velocity at the middle {:.3}× its velocity at the ends", mid / end),
            se > 1.05 && sm > 1.05 && mid > 1.05 * end && ss < 1.0 + 1e-9,
        ))
    });
    s.attempt(Dam1998, "Figures 6.7–6.8", "Since the number of frames in each subinterval necessarily has to be an integer the angular velocity is, due to rounding, only approximately constant. Compare figure 6.7 and figure 6.8.", |_| {
        let (u, a) = (get(runs, "6.7")?, get(runs, "6.8")?);
        let (su, sa) = (speed_spread(u), speed_spread(a));
        Ok::<_, String>((
            format!("Slerp's velocity max/min over the whole curve: {su:.3} with uniform frames (6.7), {sa:.4} with frames by interval angle (6.8)"),
            su > 1.3 && sa < 1.05,
        ))
    });
    s.attempt(Dam1998, "Figure 6.11, §6.2.1", "We choose to determine the number of frames between each pair of key frames relative to the distance between the two key frames. This is not the optimal choice, but a simple and effective heuristic.", |_| {
        // The same figure with the frames shared equally.
        let by_angle = get(runs, "6.11")?;
        let uniform = run(&Spec { timing: Timing::Uniform, ..by_angle.spec.clone() }).map_err(|e| e.to_string())?;
        let (a, u) = (speed_spread(by_angle), speed_spread(&uniform));
        Ok::<_, String>((
            format!("Squad's velocity max/min over the curve: {a:.2} with frames by interval angle, {u:.2} with equal shares — more even, not constant"),
            a < u && a > 1.5,
        ))
    });
    s.attempt(Dam1998, "Figures 6.15–6.17", "If the one-step method is used (see figure 6.15), the velocity curve resembles an electrocardiogram, while the velocity curve for the multi-step algorithm (6.17) is somewhat nicer", |_| {
        let (one, first, multi) = (get(runs, "6.15")?, get(runs, "6.16")?, get(runs, "6.17")?);
        let (r1, r3) = (roughness(one), roughness(multi));
        let (k1, k3) = (worst_at_keys(one), worst_at_keys(multi));
        // The first step's own start: Slerp through the same keys and frames.
        let start = run(&Spec { curve: Curve::Piecewise(Method::Slerp), ..first.spec.clone() }).map_err(|e| e.to_string())?;
        let e0 = energy(&start);
        Ok::<_, String>((
            format!("velocity roughness (total variation over maximum): one step {r1:.2}, three steps {r3:.2}; largest geodesic curvature at a key: {k1:.0} against {k3:.0}; the first step (6.16) takes the energy from {e0:.3e} (Slerp) to {:.3e}", energy(first)),
            r1 > r3 && k1 > k3 && energy(first) < e0,
        ))
    });
    s.attempt(Dam1998, "Figures 6.18–6.19, §6.3.7", "each key frame can simply ask its neighbours to be more considerate [...] In practice, a good value for c_k is about 1.2. The effect of the weighting function can be seen in figure 6.19.", |_| {
        let (plain, weighted) = (get(runs, "6.18")?, get(runs, "6.19")?);
        let (a, b) = (worst_at_keys(plain), worst_at_keys(weighted));
        Ok::<_, String>((
            format!("largest geodesic curvature at a key: {a:.1} with c_k = 1, {b:.1} with c_k = 1.2"),
            b < a,
        ))
    });
    s.attempt(Dam1998, "Figure 6.20, §6.3.7", "In figure 6.20, the effect of using Spring can be seen. The result is only marginally better than the version that does not include special treatment of curvature at the key frames.", |_| {
        let (plain, spring) = (get(runs, "6.17")?, get(runs, "6.20")?);
        let (a, b) = (worst_at_keys(plain), worst_at_keys(spring));
        let (ea, eb) = (energy(plain), energy(spring));
        Ok::<_, String>((
            format!("curvature energy {eb:.4e} against {ea:.4e} ({:+.1} %); largest geodesic curvature at a key {b:.1} against {a:.1}", (eb / ea - 1.0) * 100.0),
            b < a && (eb / ea - 1.0).abs() < 0.1,
        ))
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiments::dam_figures::{chapter_5, chapter_6, section};
    use crate::experiments::Figures;

    /// Every caption's claim holds on the figures made with the caption's parameters.
    #[test]
    fn chapters_5_and_6_captions_hold() {
        let (mut s, runs) = section("ch. 5", &chapter_5(), Figures::Skip);
        chapter_5_claims(&mut s, &runs);
        let (mut t, runs) = section("ch. 6", &chapter_6(), Figures::Skip);
        chapter_6_claims(&mut t, &runs);
        let claims: Vec<_> = s.claims().chain(t.claims()).collect();
        assert_eq!(claims.len(), 9);
        for c in claims {
            assert!(c.verdict.agrees(), "{}: {}", c.source(), c.measured());
        }
    }
}
