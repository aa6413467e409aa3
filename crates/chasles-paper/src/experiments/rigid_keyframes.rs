//! Key-frame curves of rigid motions (`chasles::interp::rigid`), measured for the tour's
//! "beyond Kavan et al." section: Kavan et al. 2006 §7 lists "spatial keyframing" among the
//! uses of dual-quaternion blending. Igarashi et al.'s spatial keyframing blends poses
//! placed at points of a control space; what every key-framing of rigid motions needs, and
//! what is measured here, is the curve through keys that turn and move: piecewise ScLERP,
//! the dual-quaternion Squad (Dam et al. Definition 17 on dual quaternions) and Spring on
//! rigid motions (§6.3.7). Measured on five keys: the jump of dq/dh across the keys (one-
//! sided second-order differences), the curves' screw energy, bi-invariance under a random
//! rigid motion, and the screw energy's Spring on keys that only translate.

use super::Figures;
use crate::claim::Paper::Kavan2006;
use crate::section::Section;
use crate::table::{Cell, Number, Table};
use chasles::interp::rigid_spring::rigid_energy;
use chasles::interp::{
    interpolate_rigid, RigidEnergy, RigidFrame, RigidKeys, RigidMethod, RigidSpringConfig,
    RigidSquad,
};
use chasles::{DualQuat, Quat, Vec3};

/// §7's words.
const KEYFRAMING: &str = "spatial keyframing – extension of [Igarashi et al. 2005]";

/// A key: `angle` about `axis`, then `t`.
fn rt(axis: [f64; 3], angle: f64, t: [f64; 3]) -> chasles::Result<DualQuat<f64>> {
    Ok(DualQuat::from_rotation_translation(
        Quat::from_axis_angle(Vec3::new(axis[0], axis[1], axis[2]), angle)?,
        Vec3::new(t[0], t[1], t[2]),
    ))
}

/// Five keys that turn and move (those of `tests/rigid.rs`).
fn keys() -> chasles::Result<Vec<DualQuat<f64>>> {
    Ok(vec![
        rt([0.0, 0.0, 1.0], 0.0, [0.0, 0.0, 0.0])?,
        rt([0.0, 0.0, 1.0], 1.2, [2.0, 1.0, 0.0])?,
        rt([1.0, 1.0, 0.0], 2.0, [3.0, -1.0, 1.0])?,
        rt([0.2, -1.0, 0.5], 2.8, [5.0, 0.0, 2.5])?,
        rt([1.0, 0.0, 0.3], 1.0, [6.0, 2.0, 2.0])?,
    ])
}

/// The largest relative jump of dq/dh across an interior key of `eval` (one-sided
/// second-order differences, step 1e-4).
fn jump(
    eval: &dyn Fn(usize, f64) -> chasles::Result<DualQuat<f64>>,
    n: usize,
) -> chasles::Result<f64> {
    let e = 1e-4;
    let mut worst = 0.0f64;
    for i in 1..n - 1 {
        let d = |a: DualQuat<f64>, b: DualQuat<f64>, c: DualQuat<f64>, s: f64| {
            let (a, b, c) = (a.to_array(), b.to_array(), c.to_array());
            core::array::from_fn::<f64, 8, _>(|j| s * (-3.0 * a[j] + 4.0 * b[j] - c[j]) / (2.0 * e))
        };
        let r = d(eval(i, 0.0)?, eval(i, e)?, eval(i, 2.0 * e)?, 1.0);
        let l = d(
            eval(i - 1, 1.0)?,
            eval(i - 1, 1.0 - e)?,
            eval(i - 1, 1.0 - 2.0 * e)?,
            -1.0,
        );
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let diff: Vec<f64> = r.iter().zip(&l).map(|(a, b)| a - b).collect();
        worst = worst.max(norm(&diff) / norm(&r).max(norm(&l)));
    }
    Ok(worst)
}

/// The distance of two poses in ℝ⁸, either sign.
fn apart(a: DualQuat<f64>, b: DualQuat<f64>) -> f64 {
    let d = |x: DualQuat<f64>, y: DualQuat<f64>| {
        x.to_array()
            .iter()
            .zip(y.to_array())
            .map(|(p, q)| (p - q).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    d(a, b).min(d(a, -b))
}

/// The methods pictured and measured.
fn methods() -> [(&'static str, RigidMethod); 4] {
    let screw = RigidSpringConfig {
        energy: RigidEnergy::Screw,
        ..Default::default()
    };
    [
        ("ScLERP", RigidMethod::ScLerp),
        ("Squad", RigidMethod::Squad),
        ("Spring", RigidMethod::Spring(RigidSpringConfig::default())),
        ("Spring screw", RigidMethod::Spring(screw)),
    ]
}

/// The poses of frames.
fn poses(f: &[RigidFrame<f64>]) -> Vec<DualQuat<f64>> {
    f.iter().map(|x| x.dq).collect()
}

/// Adds the claim on key-frame curves of rigid motions, with its table and pictures.
pub fn rigid_keyframes(s: &mut Section, figures: Figures) {
    s.attempt(Kavan2006, "§7", KEYFRAMING, |s| {
        let k = keys().map_err(|e| e.to_string())?;
        let rk = RigidKeys::new(&k, None).map_err(|e| e.to_string())?;
        let sq = RigidSquad::new(&rk).map_err(|e| e.to_string())?;
        let q = rk.dual_quats().to_vec();
        let squad_jump = jump(&|i, h| sq.eval(i, h), q.len()).map_err(|e| e.to_string())?;
        let sclerp_jump = jump(
            &|i, h| Ok(q[i] * ((q[i].conjugate() * q[i + 1]).log()? * h).exp()),
            q.len(),
        )
        .map_err(|e| e.to_string())?;
        // Invariance under one rigid motion on the left and on the right.
        let a = rt([0.3, 1.0, -0.2], 1.3, [-2.0, 0.5, 1.0]).map_err(|e| e.to_string())?;
        let left: Vec<_> = k.iter().map(|x| a * *x).collect();
        let right: Vec<_> = k.iter().map(|x| *x * a).collect();
        let mut table = Table::new(
            "five keys that turn and move, 161 frames: each curve's screw energy (the dual-quaternion curve's curvature, Σ‖V(q̂ᵢ* q̂ᵢ₋₁ + q̂ᵢ* q̂ᵢ₊₁)‖²) and how far it moves from the curve through the keys moved by a rigid motion a (left: a q̂ᵢ, right: q̂ᵢ a)",
            &["curve", "screw energy", "left", "right"],
        );
        let mut made = Vec::new();
        let mut worst_bi = 0.0f64;
        for (name, m) in methods() {
            let run = |keys: &[DualQuat<f64>]| {
                RigidKeys::new(keys, None)
                    .and_then(|rk| interpolate_rigid(&m, &rk, 161))
                    .map_err(|e| e.to_string())
            };
            let (base, l, r) = (run(&k)?, run(&left)?, run(&right)?);
            let dl = base.iter().zip(&l).map(|(x, y)| apart(a * x.dq, y.dq)).fold(0.0, f64::max);
            let dr = base.iter().zip(&r).map(|(x, y)| apart(x.dq * a, y.dq)).fold(0.0, f64::max);
            if !matches!(m, RigidMethod::Spring(_)) {
                worst_bi = worst_bi.max(dl).max(dr);
            }
            let e = rigid_energy(&poses(&base), 1.0);
            table.row(vec![
                Cell::text(name),
                Cell::Number(Number::sci(e, 3)),
                Cell::Number(Number::sci(dl, 1)),
                Cell::Number(Number::sci(dr, 1)),
            ]);
            made.push((name, base, e, dl));
        }
        s.table(table);
        // Keys that only translate: the screw energy turns the frames.
        let t: Vec<DualQuat<f64>> = k.iter().map(|x| DualQuat::from_translation(x.translation())).collect();
        let tk = RigidKeys::new(&t, None).map_err(|e| e.to_string())?;
        let turned = interpolate_rigid(&methods()[3].1, &tk, 45).map_err(|e| e.to_string())?;
        let turn = turned
            .iter()
            .map(|f| f.dq.real.angle_to(Quat::identity()).map(f64::to_degrees))
            .collect::<chasles::Result<Vec<f64>>>()
            .map_err(|e| e.to_string())?
            .into_iter()
            .fold(0.0, f64::max);
        if figures == Figures::Draw {
            let panels: Vec<_> = made
                .iter()
                .map(|(name, f, _, _)| chasles_viz::rigid::path(&k, &poses(f), 6, (400, 330), name))
                .collect();
            let top = chasles_viz::Image::side_by_side(&panels[..2]);
            let bottom = chasles_viz::Image::side_by_side(&panels[2..]);
            s.try_figure(
                "beyond-rigid-paths.png",
                Ok::<_, String>(chasles_viz::Image::stacked(&[top, bottom]).png()),
                &format!("Five keys that turn and move (grey letters R), 161 frames by each curve: the path of the top of the R's stem (blue dots) and the R at six frames (red, darker later). ScLERP turns and slides about a fixed screw axis in each interval and breaks at the keys (dq/dh jumps by {sclerp_jump:.2} relative); the dual-quaternion Squad is C¹ (jump {squad_jump:.1e}, the differences' truncation); Spring (the rotations' Spring energy plus the translations' second differences) and Spring on the dual-quaternion curve's own energy: screw energies {:.2e} and {:.2e} against Squad's {:.2e} and ScLERP's {:.2e}.", made[2].2, made[3].2, made[1].2, made[0].2),
            );
            let frames = poses(&interpolate_rigid(&RigidMethod::Squad, &rk, 72).map_err(|e| e.to_string())?);
            let gif = chasles_viz::gif(&chasles_viz::rigid::animate(&k, &frames, 260), 6).map_err(|e| e.to_string())?;
            s.try_figure(
                "beyond-rigid-squad.gif",
                Ok::<_, String>(gif),
                "The R moved along the dual-quaternion Squad through the five keys (72 frames): it turns and moves at once, without a stop or a kink at the keys.",
            );
        }
        Ok::<_, String>((
            format!(
                "through five keys: dq/dh jumps across the keys by {sclerp_jump:.2} (relative) for ScLERP and {squad_jump:.1e} for the dual-quaternion Squad (C¹); ScLERP and Squad bi-invariant to {worst_bi:.1e}; Spring left-invariant to {:.1e}, {:.1e} (split, screw: its solver's precision); screw energy ScLERP {:.3e}, Squad {:.3e}, Spring {:.3e} (split: it minimizes another energy, and lands a little above Squad on this one) and {:.3e} (screw, its minimum); on keys that only translate the screw energy's Spring turns the frames by up to {turn:.1}°",
                made[2].3, made[3].3, made[0].2, made[1].2, made[2].2, made[3].2
            ),
            squad_jump < 1e-6
                && sclerp_jump > 0.1
                && worst_bi < 1e-12
                && made[2].3 < 1e-10
                && made[3].3 < 1e-10
                && made[3].2 < made[1].2.min(made[2].2)
                && made[1].2 < made[0].2,
        ))
    });
}
