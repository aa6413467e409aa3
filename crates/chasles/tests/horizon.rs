//! Camera paths with a stable horizon (issue 21, item 5; Shoemake 1994): after every method
//! (Spring too), with z or y up, no frame rolls (the roll of the yaw–pitch–roll angles,
//! intrinsic ZYX or YZX, by the library's Euler extraction, ≤ 1e-12), the keys are still
//! met (≤ 1e-12), and the viewing direction is the method's own; f32 too; a rolling key is
//! a typed error naming it; looking straight up has no panic.

use chasles::interp::horizon::{camera, check_keys, interpolate_camera, level, level_frames, roll};
use chasles::interp::{
    interpolate, spring, Hemisphere, KeyFrames, Method, SpringConfig, Tcb, Timing, Up,
};
use chasles::{Error, EulerOrder, Quat, Real, Vec3};

/// A camera's keys: (yaw, pitch) in radians.
const SHOTS: [(f64, f64); 6] = [
    (0.0, 0.0),
    (0.9, -0.4),
    (1.8, 0.3),
    (2.2, 0.9),
    (3.4, -0.2),
    (4.0, 0.5),
];

fn keys<T: Real>(up: Up) -> KeyFrames<T> {
    let q: Vec<Quat<T>> = SHOTS
        .iter()
        .map(|(y, p)| camera(up, T::from_f64(*y), T::from_f64(*p)))
        .collect();
    KeyFrames::new(&q, None, Hemisphere::Chain).unwrap()
}

fn methods() -> Vec<Method> {
    vec![
        Method::LinEuler(EulerOrder::DAM),
        Method::LinMat,
        Method::Nlerp,
        Method::Slerp,
        Method::Squad,
        Method::CatmullRom,
        Method::KochanekBartels(Tcb {
            tension: 0.2,
            continuity: -0.3,
            bias: 0.4,
        }),
        Method::Bezier,
        Method::C2,
    ]
}

fn same(p: Quat<f64>, q: Quat<f64>) -> f64 {
    (p - q).norm().min((p + q).norm())
}

/// The roll by the library's own Euler extraction (not `horizon::roll`).
fn euler_roll(q: Quat<f64>, up: Up) -> f64 {
    q.normalize().unwrap().to_euler(up.order()).unwrap().angles[2]
}

#[test]
fn camera_keys_have_no_roll() {
    for up in [Up::Z, Up::Y] {
        for (y, p) in SHOTS {
            let q = camera(up, y, p);
            let e = q.to_euler(up.order()).unwrap().angles;
            assert!(e[2].abs() < 1e-15 && roll(q, up).abs() < 1e-15);
            // The camera looks along its x axis: yaw about up, pitch down positive (z up).
            let d = q.rotate(Vec3::unit(0));
            let want = match up {
                Up::Z => Vec3::new(p.cos() * y.cos(), p.cos() * y.sin(), -p.sin()),
                Up::Y => Vec3::new(p.cos() * y.cos(), p.sin(), -p.cos() * y.sin()),
            };
            assert!((d - want).norm() < 1e-15, "{up:?} {y} {p}");
        }
        let rolled = Quat::from_euler(up.order(), [0.4, 0.2, 0.3]);
        assert!((roll(rolled, up) - 0.3).abs() < 1e-15);
        assert!(roll(level(rolled, up), up).abs() < 1e-15);
    }
}

#[test]
fn no_frame_rolls_after_any_method() {
    for up in [Up::Z, Up::Y] {
        let kf = keys::<f64>(up);
        for m in methods() {
            let raw = interpolate(m, &kf, 240, Timing::Angle).unwrap();
            let f = interpolate_camera(m, &kf, 240, Timing::Angle, up).unwrap();
            let before = raw
                .iter()
                .map(|f| euler_roll(f.q, up).abs())
                .fold(0.0, f64::max);
            let after = f
                .iter()
                .map(|f| euler_roll(f.q, up).abs())
                .fold(0.0, f64::max);
            let keys_off = f
                .iter()
                .filter_map(|f| f.key.map(|k| same(f.q, kf.quats()[k])))
                .fold(0.0, f64::max);
            let look = raw
                .iter()
                .zip(&f)
                .map(|(a, b)| (a.q.rotate(Vec3::unit(0)) - b.q.rotate(Vec3::unit(0))).norm())
                .fold(0.0, f64::max);
            println!(
                "{up:?} up, {m:?}: largest roll {:.2}° before, {after:.1e} rad after; keys within {keys_off:.1e}",
                before.to_degrees()
            );
            assert!(after < 1e-12, "{m:?}: {after}");
            assert!(keys_off < 1e-12, "{m:?}: {keys_off}");
            assert!(look < 1e-12, "{m:?}: {look}");
            assert_eq!(f.iter().filter(|f| f.key.is_some()).count(), kf.len());
            if m == Method::Slerp {
                assert!(before.to_degrees() > 1.0, "{before}");
            }
        }
    }
}

#[test]
fn spring_keeps_the_horizon_too() {
    let kf = keys::<f64>(Up::Z);
    let r = spring(
        &kf,
        120,
        Timing::Angle,
        &SpringConfig::spring(),
        &mut |_| {},
    )
    .unwrap();
    let mut frames = r.frames;
    let removed = level_frames(&mut frames, Up::Z);
    assert!(removed > 1e-3);
    for f in &frames {
        assert!(euler_roll(f.q, Up::Z).abs() < 1e-12);
        if let Some(k) = f.key {
            assert!(same(f.q, kf.quats()[k]) < 1e-12);
        }
    }
}

#[test]
fn in_f32() {
    for up in [Up::Z, Up::Y] {
        let kf = keys::<f32>(up);
        for m in methods() {
            let f = interpolate_camera(m, &kf, 120, Timing::Uniform, up).unwrap();
            for x in &f {
                assert!(roll(x.q, up).abs() < 1e-6, "{m:?}");
            }
        }
    }
}

#[test]
fn a_key_that_rolls_is_an_error_naming_it() {
    let mut q: Vec<Quat<f64>> = SHOTS.iter().map(|(y, p)| camera(Up::Z, *y, *p)).collect();
    q[3] = Quat::from_euler(Up::Z.order(), [2.2, 0.9, 0.05]);
    let kf = KeyFrames::new(&q, None, Hemisphere::Chain).unwrap();
    let e = interpolate_camera(Method::Squad, &kf, 100, Timing::Angle, Up::Z).unwrap_err();
    match &e {
        Error::BadKey { index: 3, source } => match **source {
            Error::BadParameter {
                what: "roll",
                value,
                ..
            } => assert!((value - 0.05).abs() < 1e-12),
            _ => panic!("{e}"),
        },
        _ => panic!("{e}"),
    }
    // Cameras made with z up roll when y is up, and the other way round.
    assert!(check_keys(&keys::<f64>(Up::Z), Up::Y).is_err());
    assert!(check_keys(&keys::<f64>(Up::Y), Up::Y).is_ok());
}

#[test]
fn looking_straight_up_or_down_is_finite() {
    let half = core::f64::consts::FRAC_PI_2;
    for up in [Up::Z, Up::Y] {
        let q: Vec<Quat<f64>> = [
            (0.0, 0.0),
            (0.5, -half),
            (1.0, 0.3),
            (2.0, half),
            (2.5, 0.0),
        ]
        .iter()
        .map(|(y, p)| camera(up, *y, *p))
        .collect();
        let kf = KeyFrames::new(&q, None, Hemisphere::Chain).unwrap();
        for m in methods() {
            let f = interpolate_camera(m, &kf, 100, Timing::Uniform, up).unwrap();
            assert!(f
                .iter()
                .all(|f| f.q.is_finite() && (f.q.norm() - 1.0).abs() < 1e-12 || m == Method::Lerp));
            for x in f.iter().filter(|x| x.key.is_some()) {
                assert!(same(x.q, q[x.key.unwrap()]) < 1e-12, "{m:?}");
            }
        }
    }
}
