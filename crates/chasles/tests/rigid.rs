//! Key-frame curves of rigid motions (`chasles::interp::rigid`, issue 22 item 1): keys met
//! exactly, C¹ at the keys (Squad; Spring's frames), bi-invariance, the reductions to the
//! quaternion methods (no translation) and to Euclidean curves (no rotation), f32 against
//! f64, and bad input. Past 500 lines because the Euclidean reductions carry their closed
//! forms (the polygon, the Catmull–Rom cubic, the natural spline solved densely) beside the
//! curves they check.

// Index loops read as the formulas they check (second differences, elimination).
#![allow(clippy::needless_range_loop)]

use chasles::interp::{
    interpolate, interpolate_rigid, rigid_spring, spring, Hemisphere, KeyFrames, Method,
    RigidEnergy, RigidFrame, RigidKeys, RigidMethod, RigidSpringConfig, RigidSquad, SpringConfig,
    Timing,
};
use chasles::{DualQuat, Error, Quat, Vec3};
use common::random_rigid;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

mod common;

fn rt(axis: [f64; 3], angle: f64, t: [f64; 3]) -> DualQuat<f64> {
    DualQuat::from_rotation_translation(
        Quat::from_axis_angle(Vec3::new(axis[0], axis[1], axis[2]), angle).unwrap(),
        Vec3::new(t[0], t[1], t[2]),
    )
}

/// Five keys that turn and move.
fn keys5() -> Vec<DualQuat<f64>> {
    vec![
        rt([0.0, 0.0, 1.0], 0.0, [0.0, 0.0, 0.0]),
        rt([0.0, 0.0, 1.0], 1.2, [2.0, 1.0, 0.0]),
        rt([1.0, 1.0, 0.0], 2.0, [3.0, -1.0, 1.0]),
        rt([0.2, -1.0, 0.5], 2.8, [5.0, 0.0, 2.5]),
        rt([1.0, 0.0, 0.3], 1.0, [6.0, 2.0, 2.0]),
    ]
}

/// The distance of two poses as points of ℝ⁸, either sign.
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

fn methods() -> Vec<(&'static str, RigidMethod)> {
    vec![
        ("sclerp", RigidMethod::ScLerp),
        ("squad", RigidMethod::Squad),
        ("spring", RigidMethod::Spring(RigidSpringConfig::default())),
        ("spring-screw", RigidMethod::Spring(screw())),
    ]
}

/// Spring with the dual-quaternion curve's own energy.
fn screw() -> RigidSpringConfig {
    RigidSpringConfig {
        energy: RigidEnergy::Screw,
        ..Default::default()
    }
}

fn run(m: &RigidMethod, k: &[DualQuat<f64>], frames: usize) -> Vec<RigidFrame<f64>> {
    interpolate_rigid(m, &RigidKeys::new(k, None).unwrap(), frames).unwrap()
}

#[test]
fn keys_are_met_exactly() {
    let k = keys5();
    let keys = RigidKeys::new(&k, None).unwrap();
    for (name, m) in methods() {
        let f = run(&m, &k, 81);
        assert_eq!(f.len(), 81);
        let at: Vec<_> = f.iter().filter_map(|x| x.key.map(|i| (i, x.dq))).collect();
        assert_eq!(at.len(), 5, "{name}");
        for (i, d) in at {
            assert_eq!(d, keys.dual_quats()[i], "{name} key {i}");
            assert_eq!(apart(d, k[i]), 0.0, "{name} key {i}");
        }
        assert!(f.iter().all(|x| x.dq.is_unit(1e-12)), "{name}");
    }
    // Squad's formula itself reaches the keys: just before h = 1 it is within the step.
    let sq = RigidSquad::new(&keys).unwrap();
    for i in 0..4 {
        let near = sq.eval(i, 1.0 - 1e-9).unwrap();
        assert!(apart(near, keys.dual_quats()[i + 1]) < 1e-7);
    }
}

/// One-sided second-order derivatives in h at key i: from interval i (h = 0) and from
/// interval i − 1 (h = 1); their difference over the larger.
fn jump_at_key(eval: &dyn Fn(usize, f64) -> DualQuat<f64>, i: usize) -> f64 {
    let e = 1e-4;
    let d = |a: DualQuat<f64>, b: DualQuat<f64>, c: DualQuat<f64>, s: f64| {
        let (a, b, c) = (a.to_array(), b.to_array(), c.to_array());
        (0..8)
            .map(|j| s * (-3.0 * a[j] + 4.0 * b[j] - c[j]) / (2.0 * e))
            .collect::<Vec<f64>>()
    };
    let right = d(eval(i, 0.0), eval(i, e), eval(i, 2.0 * e), 1.0);
    let left = d(
        eval(i - 1, 1.0),
        eval(i - 1, 1.0 - e),
        eval(i - 1, 1.0 - 2.0 * e),
        -1.0,
    );
    let n = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let diff: Vec<f64> = right.iter().zip(&left).map(|(a, b)| a - b).collect();
    n(&diff) / n(&right).max(n(&left))
}

#[test]
fn squad_is_c1_at_the_keys_and_sclerp_is_not() {
    let keys = RigidKeys::new(&keys5(), None).unwrap();
    let sq = RigidSquad::new(&keys).unwrap();
    let q = keys.dual_quats().to_vec();
    let squad = |i: usize, h: f64| sq.eval(i, h).unwrap();
    let sclerp = |i: usize, h: f64| {
        let l = (q[i].conjugate() * q[i + 1]).log().unwrap();
        q[i] * (l * h).exp()
    };
    let mut worst = (0.0f64, f64::INFINITY);
    for i in 1..4 {
        worst.0 = worst.0.max(jump_at_key(&squad, i));
        worst.1 = worst.1.min(jump_at_key(&sclerp, i));
    }
    println!(
        "relative jump of dq/dh across the keys: squad at most {:.1e}, sclerp at least {:.2}",
        worst.0, worst.1
    );
    // Second-order differences with step 1e-4: truncation ~1e-8.
    assert!(worst.0 < 1e-6, "{worst:?}");
    assert!(worst.1 > 0.1, "{worst:?}");
}

/// The largest relative jump, across an interior key, of the frames' body velocity
/// `log(f_k* f_{k+1})` extrapolated to the key from the two segments on each side.
fn frame_velocity_jump(f: &[RigidFrame<f64>]) -> f64 {
    let w = |k: usize| {
        let l = (f[k].dq.conjugate() * f[k + 1].dq).log().unwrap();
        let dt = f[k + 1].t - f[k].t;
        // In world-aligned form (left-translated to the key's frame below).
        (f[k].dq, l * (1.0 / dt))
    };
    let mut worst = 0.0f64;
    for i in 2..f.len() - 2 {
        if f[i].key.is_none() {
            continue;
        }
        // Body velocities at the key: each segment's twist moved to the key's frame.
        let at = |k: usize| {
            let (p, l) = w(k);
            let g = f[i].dq.conjugate() * p;
            let m = g * l * g.conjugate();
            [m.real.x, m.real.y, m.real.z, m.dual.x, m.dual.y, m.dual.z]
        };
        let (l1, l2, r1, r2) = (at(i - 1), at(i - 2), at(i), at(i + 1));
        let left: Vec<f64> = (0..6).map(|j| 1.5 * l1[j] - 0.5 * l2[j]).collect();
        let right: Vec<f64> = (0..6).map(|j| 1.5 * r1[j] - 0.5 * r2[j]).collect();
        let n = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let d: Vec<f64> = left.iter().zip(&right).map(|(a, b)| a - b).collect();
        worst = worst.max(n(&d) / n(&left).max(n(&right)));
    }
    worst
}

#[test]
fn spring_frames_turn_and_move_smoothly_through_the_keys() {
    let k = keys5();
    let mut jumps = Vec::new();
    for frames in [81usize, 321] {
        let sp = run(
            &RigidMethod::Spring(RigidSpringConfig::default()),
            &k,
            frames,
        );
        let ss = run(&RigidMethod::Spring(screw()), &k, frames);
        let sc = run(&RigidMethod::ScLerp, &k, frames);
        let sq = run(&RigidMethod::Squad, &k, frames);
        jumps.push([
            frame_velocity_jump(&sc),
            frame_velocity_jump(&sq),
            frame_velocity_jump(&sp),
            frame_velocity_jump(&ss),
        ]);
    }
    println!("velocity jump across keys (sclerp, squad, spring, spring-screw) at 81 and 321 frames: {jumps:?}");
    for j in &jumps {
        assert!(
            j[0] > 0.1 && j[1] < 0.05 && j[2] < 0.05 && j[3] < 0.05,
            "{j:?}"
        );
    }
    // The C¹ curves' jump is the differences' truncation: it shrinks with the spacing.
    for m in 1..4 {
        assert!(jumps[1][m] < jumps[0][m] / 4.0, "{jumps:?}");
    }
}

#[test]
fn spring_lowers_the_energy_to_its_minimum() {
    let keys = RigidKeys::new(&keys5(), None).unwrap();
    let r = rigid_spring(&keys, 161, &screw()).unwrap();
    let split = rigid_spring(&keys, 161, &RigidSpringConfig::default()).unwrap();
    println!(
        "split spring, 161 frames: F {:.6e} (Slerp and the polygon) -> {:.6e}, gradient ratio {:.1e}",
        split.energy.0, split.energy.1, split.gradient_ratio
    );
    assert!(split.energy.1 < split.energy.0 && split.gradient_ratio < 1e-9);
    println!(
        "screw spring, 161 frames: F {:.6e} (ScLERP) -> {:.6e} in {} steps, gradient ratio {:.1e}",
        r.energy.0, r.energy.1, r.iterations, r.gradient_ratio
    );
    assert!(r.energy.1 < 0.5 * r.energy.0);
    assert!(r.gradient_ratio < 1e-9, "{}", r.gradient_ratio);
    // Below every small perturbation of a frame: a minimum.
    let x: Vec<DualQuat<f64>> = r.frames.iter().map(|f| f.dq).collect();
    let f0 = chasles::interp::rigid_spring::rigid_energy(&x, 1.0);
    let mut rng = StdRng::seed_from_u64(3);
    for _ in 0..20 {
        let mut y = x.clone();
        let i = rng.random_range(1..x.len() - 1);
        if r.frames[i].key.is_some() {
            continue;
        }
        let d = DualQuat::new(
            Quat::new(
                0.0,
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                0.0,
            ) * 1e-4,
            Quat::new(
                0.0,
                0.0,
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            ) * 1e-4,
        );
        y[i] = y[i] * d.exp();
        assert!(chasles::interp::rigid_spring::rigid_energy(&y, 1.0) > f0);
    }
}

/// Every frame of `a` moved by `f` against the frames of `b`.
fn worst_moved(
    a: &[RigidFrame<f64>],
    b: &[RigidFrame<f64>],
    f: &dyn Fn(DualQuat<f64>) -> DualQuat<f64>,
) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| apart(f(x.dq), y.dq))
        .fold(0.0, f64::max)
}

#[test]
fn sclerp_and_squad_are_bi_invariant_spring_left_invariant() {
    let mut rng = StdRng::seed_from_u64(22);
    let mut report = Vec::new();
    for trial in 0..6 {
        let k: Vec<DualQuat<f64>> = (0..5).map(|_| random_rigid(&mut rng)).collect();
        let a = random_rigid(&mut rng);
        let left: Vec<_> = k.iter().map(|q| a * *q).collect();
        let right: Vec<_> = k.iter().map(|q| *q * a).collect();
        let rot = DualQuat::from_rotation(a.real);
        let right_rot: Vec<_> = k.iter().map(|q| *q * rot).collect();
        for (name, m) in methods() {
            let base = run(&m, &k, 61);
            let l = worst_moved(&base, &run(&m, &left, 61), &|d| a * d);
            let r = worst_moved(&base, &run(&m, &right, 61), &|d| d * a);
            let rr = worst_moved(&base, &run(&m, &right_rot, 61), &|d| d * rot);
            if trial == 0 {
                report.push(format!(
                    "{name}: left {l:.1e}, right {r:.1e}, right by a rotation {rr:.1e}"
                ));
            }
            assert!(l < 1e-12, "{name} left {l}");
            assert!(rr < 1e-12, "{name} right rotation {rr}");
            if name.starts_with("spring") {
                // A translation on the right shears the relative motions: not invariant.
                assert!(r > 1e-6, "{name} right {r}");
            } else {
                assert!(r < 1e-12, "{name} right {r}");
            }
        }
    }
    println!("invariance (first trial): {}", report.join("; "));
}

#[test]
fn pure_rotations_give_the_quaternion_curves() {
    let q: Vec<Quat<f64>> = chasles::interp::examples::table_5_1().keys();
    let k: Vec<DualQuat<f64>> = q.iter().map(|q| DualQuat::from_rotation(*q)).collect();
    let qk = KeyFrames::new(&q, None, Hemisphere::Chain).unwrap();
    let frames = 121;
    let slerp = interpolate(Method::Slerp, &qk, frames, Timing::Uniform).unwrap();
    let squad = interpolate(Method::Squad, &qk, frames, Timing::Uniform).unwrap();
    let sp = spring(
        &qk,
        frames,
        Timing::Uniform,
        &SpringConfig::converged(),
        &mut |_| {},
    )
    .unwrap();
    let cases = [
        (
            "sclerp/slerp",
            RigidMethod::ScLerp,
            slerp.iter().map(|f| f.q).collect::<Vec<_>>(),
            1e-14,
        ),
        (
            "squad/squad",
            RigidMethod::Squad,
            squad.iter().map(|f| f.q).collect(),
            1e-14,
        ),
        (
            "spring/spring",
            RigidMethod::Spring(RigidSpringConfig::default()),
            sp.frames.iter().map(|f| f.q).collect(),
            1e-8,
        ),
        (
            "spring-screw/spring",
            RigidMethod::Spring(screw()),
            sp.frames.iter().map(|f| f.q).collect(),
            1e-8,
        ),
    ];
    for (name, m, quat, tol) in cases {
        let f = run(&m, &k, frames);
        let worst = f
            .iter()
            .zip(&quat)
            .map(|(a, b)| (a.dq.real - *b).norm().min((a.dq.real + *b).norm()))
            .fold(0.0, f64::max);
        let dual = f.iter().map(|a| a.dq.dual.norm()).fold(0.0, f64::max);
        println!("{name}: rotation parts {worst:.1e} apart, largest dual part {dual:.1e}");
        assert!(worst < tol, "{name}: {worst}");
        assert_eq!(dual, 0.0, "{name}");
    }
}

/// The translations of keys that do not turn.
fn translations() -> Vec<Vec3<f64>> {
    vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(2.0, 1.0, 0.0),
        Vec3::new(3.0, -1.0, 1.0),
        Vec3::new(5.0, 0.0, 2.5),
        Vec3::new(6.0, 2.0, 2.0),
    ]
}

#[test]
fn pure_translations_give_euclidean_curves() {
    let t = translations();
    let k: Vec<DualQuat<f64>> = t.iter().map(|v| DualQuat::from_translation(*v)).collect();
    let n = t.len();
    let frames = 4 * 10 + 5; // ten in-between frames per interval
    let h = |j: usize| j as f64 / 11.0;
    // ScLERP: the polygon.
    let f = run(&RigidMethod::ScLerp, &k, frames);
    let mut worst = [0.0f64; 3];
    for (idx, fr) in f.iter().enumerate() {
        let (i, j) = ((idx / 11).min(n - 2), idx % 11);
        let (i, s) = if idx == frames - 1 {
            (n - 2, 1.0)
        } else {
            (i, h(j))
        };
        let want = t[i] * (1.0 - s) + t[i + 1] * s;
        worst[0] = worst[0].max((fr.dq.translation() - want).norm());
        assert!((fr.dq.real - Quat::identity()).norm() == 0.0);
    }
    // Squad: the cubic Hermite curve with Catmull–Rom tangents (t_{i+1} − t_{i−1})/2 and
    // t_1 − t_0, t_N − t_{N−1} at the ends.
    let tangent = |i: usize| {
        if i == 0 {
            t[1] - t[0]
        } else if i == n - 1 {
            t[n - 1] - t[n - 2]
        } else {
            (t[i + 1] - t[i - 1]) * 0.5
        }
    };
    let f = run(&RigidMethod::Squad, &k, frames);
    for (idx, fr) in f.iter().enumerate() {
        let (i, s) = if idx == frames - 1 {
            (n - 2, 1.0)
        } else {
            ((idx / 11).min(n - 2), h(idx % 11))
        };
        let (s2, s3) = (s * s, s * s * s);
        let want = t[i] * (2.0 * s3 - 3.0 * s2 + 1.0)
            + tangent(i) * (s3 - 2.0 * s2 + s)
            + t[i + 1] * (-2.0 * s3 + 3.0 * s2)
            + tangent(i + 1) * (s3 - s2);
        worst[1] = worst[1].max((fr.dq.translation() - want).norm());
        assert!((fr.dq.real - Quat::identity()).norm() == 0.0);
    }
    // Spring: the discrete natural spline, min Σ ‖t_{k−1} − 2t_k + t_{k+1}‖² with the keys
    // fixed, solved here densely by its normal equations.
    let f = run(
        &RigidMethod::Spring(RigidSpringConfig::default()),
        &k,
        frames,
    );
    let free: Vec<usize> = (0..frames).filter(|i| f[*i].key.is_none()).collect();
    let col = |i: usize| free.iter().position(|x| *x == i);
    let m = free.len();
    let mut a = vec![vec![0.0; m]; m];
    let mut b = vec![[0.0; 3]; m];
    for c in 1..frames - 1 {
        let coef = [(c - 1, 1.0), (c, -2.0), (c + 1, 1.0)];
        // Known part of the second difference.
        let mut known = [0.0; 3];
        for (i, w) in coef {
            if col(i).is_none() {
                let p = f[i].dq.translation().to_array();
                for d in 0..3 {
                    known[d] += w * p[d];
                }
            }
        }
        for (i, wi) in coef {
            let Some(ci) = col(i) else { continue };
            for (j, wj) in coef {
                if let Some(cj) = col(j) {
                    a[ci][cj] += wi * wj;
                }
            }
            for d in 0..3 {
                b[ci][d] -= wi * known[d];
            }
        }
    }
    // Gaussian elimination (symmetric positive definite: no pivoting needed).
    for p in 0..m {
        for r in p + 1..m {
            let l = a[r][p] / a[p][p];
            if l == 0.0 {
                continue;
            }
            for c in p..m {
                a[r][c] -= l * a[p][c];
            }
            for d in 0..3 {
                b[r][d] -= l * b[p][d];
            }
        }
    }
    let mut x = vec![[0.0; 3]; m];
    for p in (0..m).rev() {
        for d in 0..3 {
            let s: f64 = (p + 1..m).map(|c| a[p][c] * x[c][d]).sum();
            x[p][d] = (b[p][d] - s) / a[p][p];
        }
    }
    for (ci, i) in free.iter().enumerate() {
        let got = f[*i].dq.translation();
        worst[2] = worst[2].max((got - Vec3::new(x[ci][0], x[ci][1], x[ci][2])).norm());
        assert_eq!(f[*i].dq.real, Quat::identity());
    }
    // The screw energy turns the frames (its module docs): measured, not the Euclidean curve.
    let g = run(&RigidMethod::Spring(screw()), &k, frames);
    let turn = g
        .iter()
        .map(|x| x.dq.real.angle_to(Quat::identity()).unwrap().to_degrees())
        .fold(0.0, f64::max);
    let off = g
        .iter()
        .zip(&f)
        .map(|(a, b)| (a.dq.translation() - b.dq.translation()).norm())
        .fold(0.0, f64::max);
    println!("pure translations, screw energy: frames turn up to {turn:.2} degrees, the path up to {off:.3} from the natural spline");
    assert!(turn > 1.0 && off > 0.01);
    println!("pure translations: sclerp vs polygon {:.1e}, squad vs Catmull-Rom {:.1e}, spring vs the discrete natural spline {:.1e}", worst[0], worst[1], worst[2]);
    assert!(
        worst[0] < 1e-14 && worst[1] < 1e-13 && worst[2] < 1e-9,
        "{worst:?}"
    );
}

#[test]
fn f32_follows_f64() {
    let mut rng = StdRng::seed_from_u64(32);
    let mut worst = [0.0f64; 4];
    for _ in 0..5 {
        let k: Vec<DualQuat<f64>> = (0..4).map(|_| random_rigid(&mut rng)).collect();
        let k32: Vec<DualQuat<f32>> = k.iter().map(|d| d.cast()).collect();
        for (w, (_, m)) in worst.iter_mut().zip(methods()) {
            let a = run(&m, &k, 40);
            let b = interpolate_rigid(&m, &RigidKeys::new(&k32, None).unwrap(), 40).unwrap();
            for (x, y) in a.iter().zip(&b) {
                *w = w.max(apart(x.dq, y.dq.cast()));
            }
        }
    }
    println!("f32 against f64 (sclerp, squad, spring, spring-screw): {worst:?}");
    assert!(worst.iter().all(|w| *w < 1e-4), "{worst:?}");
}

#[test]
fn bad_input_is_a_typed_error() {
    let k = keys5();
    let one = &k[..1];
    assert!(matches!(
        RigidKeys::new(one, None),
        Err(Error::TooFewKeys { .. })
    ));
    let mut nan = k.clone();
    nan[2] = DualQuat::from_array([f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let e = RigidKeys::new(&nan, None).unwrap_err();
    assert!(matches!(e, Error::BadKey { index: 2, .. }), "{e}");
    let mut zero = k.clone();
    zero[1] = DualQuat::from_array([0.0; 8]);
    assert!(matches!(
        RigidKeys::new(&zero, None),
        Err(Error::BadKey { index: 1, .. })
    ));
    let mut scaled = k.clone();
    scaled[4] = scaled[4] * 2.0;
    assert!(matches!(
        RigidKeys::new(&scaled, None),
        Err(Error::BadKey { index: 4, .. })
    ));
    let e = RigidKeys::new(&k, Some(&[0.0, 1.0, 1.0, 2.0, 3.0])).unwrap_err();
    assert!(matches!(e, Error::BadKeyTime { index: 2, .. }), "{e}");
    let e = RigidKeys::new(&k, Some(&[0.0, 1.0])).unwrap_err();
    assert!(
        matches!(
            e,
            Error::WrongLength {
                what: "key times",
                got: 2,
                ..
            }
        ),
        "{e}"
    );
    let keys = RigidKeys::new(&k, None).unwrap();
    for (_, m) in methods() {
        assert!(matches!(
            interpolate_rigid(&m, &keys, 3),
            Err(Error::TooFewFrames { .. })
        ));
        assert!(matches!(
            interpolate_rigid(&m, &keys, usize::MAX / 2),
            Err(Error::TooManyFrames { .. })
        ));
    }
    for cfg in [
        RigidSpringConfig {
            length_scale: 0.0,
            ..Default::default()
        },
        RigidSpringConfig {
            length_scale: f64::NAN,
            ..Default::default()
        },
        RigidSpringConfig {
            tolerance: 1.0,
            ..Default::default()
        },
        RigidSpringConfig {
            tolerance: -1.0,
            ..Default::default()
        },
        RigidSpringConfig {
            max_iterations: 0,
            ..Default::default()
        },
    ] {
        assert!(matches!(
            rigid_spring(&keys, 20, &cfg),
            Err(Error::BadParameter { .. })
        ));
    }
    // Keys given with either sign: the same curve (chained to one hemisphere).
    let mut flipped = k.clone();
    flipped[2] = -flipped[2];
    for (name, m) in methods() {
        let a = run(&m, &k, 30);
        let b = run(&m, &flipped, 30);
        assert!(worst_moved(&a, &b, &|d| d) < 1e-14, "{name}");
    }
}

#[test]
fn repeated_half_turn_and_far_keys_stay_finite() {
    // A key repeated (no motion in an interval), a half turn (the shorter screw is ambiguous:
    // the sign as chained is taken), and keys far from the origin.
    let half = rt([1.0, 0.0, 0.0], std::f64::consts::PI, [1.0, 2.0, 0.0]);
    let sets = [
        vec![
            DualQuat::identity(),
            DualQuat::identity(),
            half,
            half,
            DualQuat::identity(),
        ],
        keys5()
            .iter()
            .map(|k| DualQuat::from_rotation_translation(k.real, k.translation() * 1e6))
            .collect(),
    ];
    for k in &sets {
        for (name, m) in methods() {
            let f = run(&m, k, 41);
            assert!(
                f.iter().all(|x| x.dq.is_finite() && x.dq.is_unit(1e-9)),
                "{name}"
            );
            let at: Vec<_> = f.iter().filter_map(|x| x.key.map(|i| (i, x.dq))).collect();
            for (i, d) in at {
                assert!(apart(d, k[i]) == 0.0, "{name} key {i}");
            }
        }
    }
}
