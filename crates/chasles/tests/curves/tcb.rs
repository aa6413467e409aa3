//! Kochanek–Bartels by number: zero parameters are Catmull–Rom, the tangents of eq. 8–9,
//! local control, the scalar spline on one axis, range errors.

use super::*;
use chasles::interp::TcbKey;
use chasles::Error;

fn tcb(tension: f64, continuity: f64, bias: f64) -> Tcb {
    Tcb {
        tension,
        continuity,
        bias,
    }
}

#[test]
fn zero_parameters_are_catmull_rom() {
    for times in [None, Some(uneven(7))] {
        let kf = keys(&wild::<f64>(), times.as_deref());
        let cr = CatmullRom::new(&kf).unwrap();
        // Zero by default, and zero given per key over a non-zero default.
        let per_key = vec![
            TcbKey {
                tension: Some(0.0),
                continuity: Some(0.0),
                bias: Some(0.0),
            };
            kf.len()
        ];
        let kf0 = kf.clone().with_tcb(per_key).unwrap();
        let a = KochanekBartels::new(&kf, Tcb::CATMULL_ROM).unwrap();
        let b = KochanekBartels::new(&kf0, tcb(0.7, -0.4, 0.9)).unwrap();
        let mut worst = 0.0f64;
        for i in 0..kf.len() - 1 {
            for j in 0..=50 {
                let h = j as f64 / 50.0;
                let want = cr.eval(i, h);
                worst = worst
                    .max(diff(a.eval(i, h), want))
                    .max(diff(b.eval(i, h), want));
            }
        }
        println!("TCB(0, 0, 0) against Catmull-Rom: {worst:.1e}");
        assert!(worst < 1e-12, "{worst}");
        // Through interpolate too.
        let f = interpolate(
            Method::KochanekBartels(Tcb::CATMULL_ROM),
            &kf,
            200,
            Timing::Angle,
        )
        .unwrap();
        let g = interpolate(Method::CatmullRom, &kf, 200, Timing::Angle).unwrap();
        assert!(f.iter().zip(&g).all(|(x, y)| diff(x.q, y.q) < 1e-12));
    }
}

/// The chord angular velocities `2 u` into and out of key k (uniform spans).
fn chords(q: &[Quat<f64>], k: usize) -> (Vec3<f64>, Vec3<f64>) {
    (rotvec(q[k - 1], q[k]), rotvec(q[k], q[k + 1]))
}

#[test]
fn tangents_follow_eq_8_and_9() {
    let kf = keys(&wild::<f64>(), None);
    let q = kf.quats();
    let span = spans(&kf);
    let k = 3;
    let (u_in, u_out) = chords(q, k);
    let cr_tangent = (u_in + u_out) * 0.5;
    // (parameters at key k, the angular velocity arriving, leaving)
    let cases = [
        (tcb(1.0, 0.0, 0.0), Vec3::zero(), Vec3::zero()),
        (tcb(-1.0, 0.0, 0.0), cr_tangent * 2.0, cr_tangent * 2.0),
        (tcb(0.5, 0.0, 0.0), cr_tangent * 0.5, cr_tangent * 0.5),
        (tcb(0.0, 0.0, 1.0), u_in, u_in),
        (tcb(0.0, 0.0, -1.0), u_out, u_out),
        (tcb(0.0, -1.0, 0.0), u_in, u_out),
        (tcb(0.0, 1.0, 0.0), u_out, u_in),
        // A mixed one, straight from eq. 8–9 with α = β = ½.
        (
            tcb(0.3, -0.6, 0.4),
            (u_in * (1.6 * 1.4) + u_out * (0.4 * 0.6)) * (0.7 * 0.5),
            (u_in * (0.4 * 1.4) + u_out * (1.6 * 0.6)) * (0.7 * 0.5),
        ),
    ];
    let mut worst = 0.0f64;
    for (p, arrive, leave) in cases {
        let mut per_key = vec![TcbKey::default(); kf.len()];
        per_key[k] = TcbKey {
            tension: Some(p.tension),
            continuity: Some(p.continuity),
            bias: Some(p.bias),
        };
        let c =
            KochanekBartels::new(&kf.clone().with_tcb(per_key).unwrap(), Tcb::CATMULL_ROM).unwrap();
        through_keys(&c, q, 1e-15);
        let (l, r) = velocity_sides(&c, &span, k);
        let e = (l - arrive).norm().max((r - leave).norm());
        let e2 = (c.arriving()[k] - arrive)
            .norm()
            .max((c.leaving()[k] - leave).norm());
        worst = worst.max(e);
        assert!(
            e < 1e-6,
            "{p:?}: arriving {l:?} want {arrive:?}, leaving {r:?} want {leave:?}"
        );
        assert!(e2 < 1e-14, "{p:?}");
        // The corner is 2 (TS − TD): zero exactly when c = 0.
        let corner = (r - l).norm();
        if p.continuity == 0.0 {
            assert!(corner < 1e-6, "{p:?}: {corner}");
        } else {
            assert!(((leave - arrive).norm() - corner).abs() < 1e-6 && corner > 0.1);
        }
        // The other keys keep Catmull–Rom's C¹.
        for j in (1..kf.len() - 1).filter(|j| *j != k) {
            let (l, r) = velocity_sides(&c, &span, j);
            assert!((l - r).norm() < 1e-6);
        }
    }
    println!("TCB tangents against eq. 8-9 by finite differences: within {worst:.1e}");
}

#[test]
fn continuity_minus_one_everywhere_is_slerp() {
    // Each side takes its own chord at both ends: the segment is the great arc.
    let kf = keys(&wild::<f64>(), None);
    let c = KochanekBartels::new(&kf, tcb(0.0, -1.0, 0.0)).unwrap();
    let q = kf.quats();
    let mut worst = 0.0f64;
    for i in 0..kf.len() - 1 {
        for j in 0..=20 {
            let h = j as f64 / 20.0;
            worst = worst.max(diff(
                c.eval(i, h),
                chasles::interp::slerp::slerp(q[i], q[i + 1], h),
            ));
        }
    }
    assert!(worst < 1e-12, "{worst}");
}

#[test]
fn uneven_times_weight_the_chords_like_catmull_rom() {
    let t = uneven(7);
    let kf = keys(&wild::<f64>(), Some(&t));
    let span = spans(&kf);
    let p = tcb(-0.4, 0.3, 0.2);
    let c = KochanekBartels::new(&kf, p).unwrap();
    let q = kf.quats();
    for k in 1..kf.len() - 1 {
        let u_in = rotvec(q[k - 1], q[k]) / span[k - 1];
        let u_out = rotvec(q[k], q[k + 1]) / span[k];
        let (alpha, beta) = (
            span[k] / (span[k - 1] + span[k]),
            span[k - 1] / (span[k - 1] + span[k]),
        );
        let (t, cc, b) = (p.tension, p.continuity, p.bias);
        let leave = (u_in * ((1.0 + cc) * (1.0 + b) * alpha)
            + u_out * ((1.0 - cc) * (1.0 - b) * beta))
            * (1.0 - t);
        let arrive = (u_in * ((1.0 - cc) * (1.0 + b) * alpha)
            + u_out * ((1.0 + cc) * (1.0 - b) * beta))
            * (1.0 - t);
        let (l, r) = velocity_sides(&c, &span, k);
        assert!(
            (l - arrive).norm() < 1e-6 && (r - leave).norm() < 1e-6,
            "key {k}"
        );
    }
}

#[test]
fn one_key_changes_only_its_two_intervals() {
    let kf = keys(&wild::<f64>(), None);
    let base = KochanekBartels::new(&kf, Tcb::CATMULL_ROM).unwrap();
    let j = 3;
    let mut per_key = vec![TcbKey::default(); kf.len()];
    per_key[j].tension = Some(0.8);
    per_key[j].bias = Some(-0.5);
    let c = KochanekBartels::new(&kf.clone().with_tcb(per_key).unwrap(), Tcb::CATMULL_ROM).unwrap();
    assert_eq!(c.params()[j], tcb(0.8, 0.0, -0.5));
    for i in 0..kf.len() - 1 {
        let moved = (1..20)
            .map(|s| diff(c.eval(i, s as f64 / 20.0), base.eval(i, s as f64 / 20.0)))
            .fold(0.0, f64::max);
        if i + 1 == j || i == j {
            assert!(moved > 1e-3, "interval {i}");
        } else {
            assert!(moved < 1e-15, "interval {i}: {moved}");
        }
    }
}

#[test]
fn about_one_axis_it_is_the_scalar_kochanek_bartels_spline() {
    let angles = [0.2, 1.1, 0.7, 2.9, 3.6, 3.1];
    let (q, n) = about_axis(&angles);
    let kf = keys(&q, None);
    let p = tcb(0.25, -0.5, 0.6);
    let c = KochanekBartels::new(&kf, p).unwrap();
    let (t, cc, b) = (p.tension, p.continuity, p.bias);
    let d = |i: usize| angles[i + 1] - angles[i];
    let last = angles.len() - 1;
    // The phantom keys: the chord beyond an end is the end interval's own.
    let d_in = |k: usize| d(k.saturating_sub(1).min(last - 1));
    let d_out = |k: usize| d(k.min(last - 1));
    let ts = |k: usize| {
        let (a, o) = (d_in(k), d_out(k));
        (1.0 - t) * ((1.0 + cc) * (1.0 + b) * a + (1.0 - cc) * (1.0 - b) * o) / 2.0
    };
    let td = |k: usize| {
        let (a, o) = (d_in(k), d_out(k));
        (1.0 - t) * ((1.0 - cc) * (1.0 + b) * a + (1.0 + cc) * (1.0 - b) * o) / 2.0
    };
    let mut worst = 0.0f64;
    for i in 0..last {
        for j in 0..=10 {
            let h = j as f64 / 10.0;
            let a = hermite(angles[i], ts(i), angles[i + 1], td(i + 1), h);
            worst = worst.max(diff(c.eval(i, h), Quat::from_axis_angle(n, a).unwrap()));
        }
    }
    assert!(worst < 1e-12, "{worst}");
}

#[test]
fn parameters_out_of_range_are_typed_errors() {
    for (p, what) in [
        (tcb(1.5, 0.0, 0.0), "tension"),
        (tcb(0.0, -1.01, 0.0), "continuity"),
        (tcb(0.0, 0.0, f64::NAN), "bias"),
        (tcb(f64::INFINITY, 0.0, 0.0), "tension"),
    ] {
        let e = Tcb::new(p.tension, p.continuity, p.bias).unwrap_err();
        assert!(
            matches!(e, Error::BadParameter { what: w, .. } if w == what),
            "{e}"
        );
        let kf = keys(&table::<f64>(), None);
        let e = interpolate(Method::KochanekBartels(p), &kf, 50, Timing::Angle).unwrap_err();
        assert!(
            matches!(e, Error::BadParameter { what: w, .. } if w == what),
            "{e}"
        );
    }
    assert!(Tcb::new(-1.0, 1.0, 0.5).is_ok());
    let kf = keys(&table::<f64>(), None);
    let mut per_key = vec![TcbKey::default(); kf.len()];
    per_key[2].continuity = Some(-1.01);
    let e = kf.clone().with_tcb(per_key).unwrap_err();
    match &e {
        Error::BadKey { index: 2, source } => {
            assert!(matches!(
                **source,
                Error::BadParameter {
                    what: "continuity",
                    ..
                }
            ))
        }
        _ => panic!("{e}"),
    }
    assert_eq!(
        e.to_string(),
        "key frame 2: continuity must be a finite number in [-1, 1], got -1.01"
    );
    let e = kf.clone().with_tcb(vec![TcbKey::default(); 2]).unwrap_err();
    assert!(matches!(e, Error::WrongLength { got: 2, .. }));
}
