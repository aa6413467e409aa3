//! Angular velocities at key frames (Dam et al. 1998 §8.2, "supply the angular velocity at
//! an arbitrary key frame"; Barr et al. 1992): Squad, by its inner control points, and the
//! converged Spring, by the frames beside the key, leave and reach each such key at the
//! velocity given, to 1e-6; keys without one keep Squad's C¹ tangent; bad velocities and
//! methods that cannot honour them get typed errors.

use chasles::interp::{
    examples, spring, Hemisphere, KeyFrames, Solver, SpringConfig, Squad, Stopped, Timing,
};
use chasles::{Error, Quat, Vec3};

const TIMES: [f64; 6] = [0.0, 1.0, 2.5, 3.0, 4.2, 5.0];

fn keys(velocities: &[Option<Vec3<f64>>]) -> KeyFrames<f64> {
    KeyFrames::new(
        &examples::table_5_1().keys::<f64>(),
        Some(&TIMES),
        Hemisphere::Chain,
    )
    .unwrap()
    .with_velocities(velocities)
    .unwrap()
}

/// The world angular velocity `2 q̇ q*` from a quaternion derivative.
fn omega(q: Quat<f64>, dq: Quat<f64>) -> Vec3<f64> {
    (dq * q.conjugate()).vector() * 2.0
}

/// Squad's one-sided derivatives in time at key i (second-order differences in h).
fn squad_sides(
    s: &Squad<f64>,
    k: &KeyFrames<f64>,
    i: usize,
) -> (Option<Vec3<f64>>, Option<Vec3<f64>>) {
    let e = 1e-5;
    let q = k.quats()[i];
    let right = (i + 1 < k.len()).then(|| {
        let d = (s.eval(i, 0.0) * -3.0 + s.eval(i, e) * 4.0 - s.eval(i, 2.0 * e)) * (0.5 / e);
        omega(q, d * (1.0 / k.duration(i)))
    });
    let left = (i > 0).then(|| {
        let j = i - 1;
        let d = (s.eval(j, 1.0) * 3.0 - s.eval(j, 1.0 - e) * 4.0 + s.eval(j, 1.0 - 2.0 * e))
            * (0.5 / e);
        omega(q, d * (1.0 / k.duration(j)))
    });
    (left, right)
}

#[test]
fn squad_leaves_and_reaches_a_key_at_its_velocity() {
    let w2 = Vec3::new(0.4, -1.1, 0.7);
    let w0 = Vec3::new(0.0, 0.9, 0.2);
    let mut v = vec![None; 6];
    v[2] = Some(w2);
    v[0] = Some(w0);
    let k = keys(&v);
    let s = Squad::new(&k).unwrap();
    for (i, w) in [(2, w2), (0, w0)] {
        let (left, right) = squad_sides(&s, &k, i);
        for side in [left, right].into_iter().flatten() {
            assert!((side - w).norm() < 1e-6, "key {i}: {side:?} vs {w:?}");
        }
    }
    // The other keys keep eq. 6.15's tangent, continuous in each interval's own parameter h
    // (Proposition 30): in time the two sides differ by the ratio of the intervals' lengths.
    for i in [1, 3, 4] {
        let (l, r) = squad_sides(&s, &k, i);
        let (l, r) = (l.unwrap() * k.duration(i - 1), r.unwrap() * k.duration(i));
        assert!(
            (l - r).norm() < 1e-6 * (1.0 + l.norm()),
            "key {i}: {l:?} vs {r:?}"
        );
    }
    // It still passes through every key.
    for i in 0..5 {
        assert!((s.eval(i, 0.0) - k.quats()[i]).norm() < 1e-15);
        assert!((s.eval(i, 1.0) - k.quats()[i + 1]).norm() < 1e-15);
    }
    // Without velocities the inner control points of both sides are eq. 6.15's.
    let plain = Squad::new(&keys(&[None; 6])).unwrap();
    assert_eq!(plain.controls(), plain.incoming_controls());
}

#[test]
fn the_converged_spring_honours_key_velocities() {
    let w = Vec3::new(0.3, 0.8, -0.5);
    let mut v = vec![None; 6];
    v[3] = Some(w);
    let k = keys(&v);
    let r = spring(
        &k,
        300,
        Timing::Angle,
        &SpringConfig::converged(),
        &mut |_| {},
    )
    .unwrap();
    assert_eq!(r.stopped, Stopped::Converged, "{:?}", r.history.last());
    let i = r.frames.iter().position(|f| f.key == Some(3)).unwrap();
    let (a, b, c) = (r.frames[i - 1], r.frames[i], r.frames[i + 1]);
    assert_eq!(b.q, k.quats()[3]);
    // One-sided differences in time, on either side: 2 log(q_{i±1} q_i*) / Δt.
    let right = ((c.q * b.q.conjugate()).log().unwrap().vector()) * (2.0 / (c.t - b.t));
    let left = ((b.q * a.q.conjugate()).log().unwrap().vector()) * (2.0 / (b.t - a.t));
    assert!((right - w).norm() < 1e-6, "{right:?}");
    assert!((left - w).norm() < 1e-6, "{left:?}");
    // The constraint costs energy: F is above the free minimum's.
    let free = spring(
        &keys(&[None; 6]),
        300,
        Timing::Angle,
        &SpringConfig::converged(),
        &mut |_| {},
    )
    .unwrap();
    assert!(r.history.last().unwrap().energy > free.history.last().unwrap().energy);
}

#[test]
fn velocities_that_cannot_be_honoured_are_errors() {
    let base = KeyFrames::new(
        &examples::table_5_1().keys::<f64>(),
        None,
        Hemisphere::Chain,
    )
    .unwrap();
    assert!(matches!(
        base.clone().with_velocities(&[None; 3]),
        Err(Error::WrongLength { .. })
    ));
    let mut v = vec![None; 6];
    v[4] = Some(Vec3::new(f64::NAN, 0.0, 0.0));
    assert!(matches!(
        base.clone().with_velocities(&v),
        Err(Error::BadKey { index: 4, .. })
    ));
    v[4] = Some(Vec3::new(0.0, 1.0, 0.0));
    let k = base.with_velocities(&v).unwrap();
    // The report's descent cannot honour them.
    let e = spring(
        &k,
        200,
        Timing::Angle,
        &SpringConfig::justdoit(),
        &mut |_| {},
    )
    .unwrap_err();
    assert!(matches!(e, Error::KeyVelocity { index: 4, .. }), "{e}");
    // Nor can any solver when the frame beside the key is a key.
    let e = spring(
        &k,
        6,
        Timing::Angle,
        &SpringConfig::converged(),
        &mut |_| {},
    )
    .unwrap_err();
    assert!(matches!(e, Error::KeyVelocity { index: 4, .. }), "{e}");
    let mut cfg = SpringConfig::converged();
    cfg.solver = Solver::Converged {
        tolerance: 1e-10,
        max_iterations: 50,
    };
    assert!(spring(&k, 200, Timing::Angle, &cfg, &mut |_| {}).is_ok());
}
