//! Spring (Dam et al. 1998, §6.3.7): the analytic gradient equals finite differences; the
//! descent lowers the curvature energy of its Slerp start on every built-in set and ends
//! below Squad's; the pendulum stays on its arc; keys stay put; stopping rules work.

use chasles::analysis::curvature::{curvature_energy, Width};
use chasles::interp::spring::{energy_and_gradient, Level};
use chasles::interp::{
    examples, interpolate, spring, Frame, Hemisphere, KeyFrames, Method, SpringConfig, StepRule,
    Timing,
};
use chasles::{Error, Quat};
use proptest::prelude::*;

fn energy(f: &[Frame<f64>]) -> f64 {
    curvature_energy(&f.iter().map(|x| x.q).collect::<Vec<_>>(), Width::Unit)
}

fn keys_of(name: &str) -> KeyFrames<f64> {
    KeyFrames::new(
        &examples::by_name(name).unwrap().keys::<f64>(),
        None,
        Hemisphere::Chain,
    )
    .unwrap()
}

proptest! {
    #[test]
    fn analytic_gradient_equals_finite_differences(
        noise in prop::collection::vec(prop::array::uniform4(-0.3f64..0.3), 9),
        ck in 1.0f64..4.0, cg in 0.0f64..3.0, cw in 0.0f64..2.0, width in 0usize..3,
    ) {
        // A wobbly curve near a great arc, not unit: every term of F is active.
        let q: Vec<Quat<f64>> = noise.iter().enumerate().map(|(i, n)| {
            let a = i as f64 * 0.2;
            Quat::new(a.cos() + n[0], a.sin() + n[1], n[2], n[3])
        }).collect();
        let is_key: Vec<bool> = (0..q.len()).map(|i| i == 0 || i == 4 || i == q.len() - 1).collect();
        let mut cfg = SpringConfig::spring();
        cfg.key_weight = ck;
        cfg.unit_penalty = cg;
        cfg.velocity_penalty = cw;
        cfg.width = [Width::Unit, Width::Centered, Width::Angle][width];
        let (f0, g) = energy_and_gradient(&q, &is_key, &cfg);
        let h = 1e-6;
        for i in 0..q.len() {
            for c in 0..4 {
                let mut e = [0.0; 4];
                e[c] = h;
                let d = Quat::from_array(e);
                let mut p = q.clone();
                p[i] = q[i] + d;
                let fp = energy_and_gradient(&p, &is_key, &cfg).0;
                p[i] = q[i] - d;
                let fm = energy_and_gradient(&p, &is_key, &cfg).0;
                let fd = (fp - fm) / (2.0 * h);
                let an = g[i].to_array()[c];
                if is_key[i] {
                    prop_assert_eq!(an, 0.0, "the gradient is zero at key frames");
                } else {
                    prop_assert!((an - fd).abs() <= 1e-6 * (1.0 + fd.abs()),
                        "frame {} coord {}: analytic {} vs finite difference {} (F = {})", i, c, an, fd, f0);
                }
            }
        }
    }
}

#[test]
fn spring_lowers_the_energy_of_its_slerp_start_and_ends_below_squad() {
    for set in examples::all() {
        let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain).unwrap();
        let n = if set.name == "table5.1" { 550 } else { 200 };
        let slerp = energy(&interpolate(Method::Slerp, &keys, n, Timing::Angle).unwrap());
        let squad = energy(&interpolate(Method::Squad, &keys, n, Timing::Angle).unwrap());
        for (name, cfg) in [
            ("spring", SpringConfig::spring()),
            ("justdoit", SpringConfig::justdoit()),
        ] {
            let r = spring(&keys, n, Timing::Angle, &cfg, &mut |_| {}).unwrap();
            let e = energy(&r.frames);
            assert!(
                e < slerp / 10.0,
                "{} {name}: {e} vs Slerp start {slerp}",
                set.name
            );
            // F never rises within a level.
            for w in r.history.windows(2) {
                if w[0].level == w[1].level {
                    assert!(
                        w[1].energy <= w[0].energy,
                        "{} {name}: F rose {:?}",
                        set.name,
                        w
                    );
                }
            }
            if name == "spring" {
                assert!(
                    e < squad,
                    "{}: Spring {e} not below Squad {squad}",
                    set.name
                );
            }
        }
    }
}

#[test]
fn spring_keeps_keys_and_the_pendulum_arc() {
    for name in ["pendulum", "table5.1"] {
        let keys = keys_of(name);
        let r = spring(
            &keys,
            200,
            Timing::Angle,
            &SpringConfig::spring(),
            &mut |_| {},
        )
        .unwrap();
        assert_eq!(r.frames.len(), 200);
        let flagged: Vec<usize> = r.frames.iter().filter_map(|f| f.key).collect();
        assert_eq!(flagged, (0..keys.len()).collect::<Vec<_>>());
        for f in &r.frames {
            if let Some(k) = f.key {
                assert!((f.q - keys.quats()[k]).norm() < 1e-15);
            }
            assert!(
                (f.q.norm() - 1.0).abs() < 1e-12,
                "Spring's result is normalized"
            );
            if name == "pendulum" {
                assert!(
                    f.q.y.abs() < 1e-12 && f.q.z.abs() < 1e-12,
                    "left the arc: {:?}",
                    f.q
                );
            }
        }
    }
}

#[test]
fn multi_step_beats_one_step_at_equal_effort() {
    // Figures 6.15–6.17: three levels with 450 iterations beat one level with 500.
    let keys = keys_of("table5.1");
    let one = spring(
        &keys,
        550,
        Timing::Angle,
        &SpringConfig::slerpsvupti(),
        &mut |_| {},
    )
    .unwrap();
    let three = spring(
        &keys,
        550,
        Timing::Angle,
        &SpringConfig::justdoit(),
        &mut |_| {},
    )
    .unwrap();
    assert!(energy(&three.frames) < energy(&one.frames) / 3.0);
    let levels: Vec<usize> = three
        .history
        .iter()
        .filter(|h| h.iteration == 0)
        .map(|h| h.frames)
        .collect();
    assert_eq!(levels, vec![22, 110, 550]);
    // squadsvupti starts lower than slerpsvupti.
    let sq = spring(
        &keys,
        550,
        Timing::Angle,
        &SpringConfig::squadsvupti(),
        &mut |_| {},
    )
    .unwrap();
    assert!(sq.history[0].energy < one.history[0].energy);
}

#[test]
fn step_rules_and_stopping_rules() {
    let keys = keys_of("cusp");
    let start = energy(&interpolate(Method::Slerp, &keys, 60, Timing::Angle).unwrap());
    for step in [
        StepRule::Fixed(0.02),
        StepRule::Normalized(0.002),
        StepRule::Adaptive(0.02),
        StepRule::Accelerated(0.05),
    ] {
        let mut cfg = SpringConfig::spring();
        cfg.step = step;
        cfg.levels = vec![Level {
            fraction: 1.0,
            iterations: 300,
        }];
        let r = spring(&keys, 60, Timing::Angle, &cfg, &mut |_| {}).unwrap();
        assert!(
            energy(&r.frames) < start / 2.0,
            "{step:?}: {} vs {start}",
            energy(&r.frames)
        );
    }
    let mut cfg = SpringConfig::justdoit();
    cfg.min_energy_change = 1e-3;
    let r = spring(&keys, 200, Timing::Angle, &cfg, &mut |_| {}).unwrap();
    assert!(
        r.history.len() < 450,
        "stopped early on energy change: {}",
        r.history.len()
    );
    let mut cfg = SpringConfig::justdoit();
    cfg.min_gradient_norm = 1e9;
    let r = spring(&keys, 200, Timing::Angle, &cfg, &mut |_| {}).unwrap();
    assert_eq!(r.history.len(), 3, "one record per level, no iterations");
    // Progress is reported for every iteration.
    let mut calls = 0;
    spring(
        &keys,
        100,
        Timing::Angle,
        &SpringConfig::justdoit(),
        &mut |_| calls += 1,
    )
    .unwrap();
    assert!(calls > 100);
}

#[test]
fn spring_in_f32_lowers_the_energy_too() {
    let set = examples::table_5_1();
    let keys = KeyFrames::new(&set.keys::<f32>(), None, Hemisphere::Chain).unwrap();
    let start = interpolate(Method::Slerp, &keys, 200, Timing::Angle).unwrap();
    let r = spring(
        &keys,
        200,
        Timing::Angle,
        &SpringConfig::spring(),
        &mut |_| {},
    )
    .unwrap();
    let e = |f: &[Frame<f32>]| {
        curvature_energy(&f.iter().map(|x| x.q).collect::<Vec<_>>(), Width::Unit)
    };
    assert!(
        e(&r.frames) < e(&start) / 10.0,
        "f32: {} vs start {}",
        e(&r.frames),
        e(&start)
    );
}

#[test]
fn bad_spring_settings_get_typed_errors() {
    let keys = keys_of("cusp");
    let mut cfg = SpringConfig::spring();
    cfg.key_weight = -1.0;
    assert!(matches!(
        spring(&keys, 50, Timing::Angle, &cfg, &mut |_| {}),
        Err(Error::BadParameter { .. })
    ));
    let mut cfg = SpringConfig::spring();
    cfg.step = StepRule::Fixed(f64::NAN);
    assert!(matches!(
        spring(&keys, 50, Timing::Angle, &cfg, &mut |_| {}),
        Err(Error::BadParameter { .. })
    ));
    let mut cfg = SpringConfig::spring();
    cfg.levels.clear();
    assert!(matches!(
        spring(&keys, 50, Timing::Angle, &cfg, &mut |_| {}),
        Err(Error::BadParameter { .. })
    ));
    assert!(matches!(
        spring(
            &keys,
            3,
            Timing::Angle,
            &SpringConfig::spring(),
            &mut |_| {}
        ),
        Err(Error::TooFewFrames { frames: 3, keys: 5 })
    ));
}
