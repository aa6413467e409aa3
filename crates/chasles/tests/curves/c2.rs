//! The C² spline by number: continuous angular velocity and acceleration at the keys (where
//! Catmull–Rom's acceleration jumps), its closed-form derivatives against finite
//! differences, the clamped scalar cubic spline on one axis, errors.

use super::*;
use chasles::Error;

#[test]
fn angular_acceleration_is_continuous_at_the_keys() {
    for times in [None, Some(uneven(7))] {
        let kf = keys(&wild::<f64>(), times.as_deref());
        let c2 = C2Spline::new(&kf).unwrap();
        through_keys(&c2, kf.quats(), 1e-15);
        let span = spans(&kf);
        let dv = largest_velocity_jump(&c2, &span);
        let da = largest_acceleration_jump(&c2, &span);
        let cr = largest_acceleration_jump(&CatmullRom::new(&kf).unwrap(), &span);
        // The closed forms, at the keys and inside the intervals.
        let mut off = (0.0f64, 0.0f64);
        for k in 1..kf.len() - 1 {
            let (vl, vr) = velocity_sides(&c2, &span, k);
            let (al, ar) = acceleration_sides(&c2, &span, k);
            let (v, a) = (c2.angular_velocity(k, 0.0), c2.angular_acceleration(k, 0.0));
            let (v1, a1) = (
                c2.angular_velocity(k - 1, 1.0),
                c2.angular_acceleration(k - 1, 1.0),
            );
            assert!((v - c2.key_velocities()[k]).norm() < 1e-14);
            off.0 = off
                .0
                .max((vl - v).norm())
                .max((vr - v).norm())
                .max((v1 - v).norm());
            off.1 = off.1.max((al - a).norm()).max((ar - a).norm());
            assert!(
                (a1 - a).norm() < 1e-9 * (1.0 + a.norm()),
                "key {k}: {a1:?} {a:?}"
            );
        }
        println!(
            "C2 spline, times {:?}: jumps at the keys: velocity {dv:.1e}, acceleration {da:.1e} (Catmull-Rom {cr:.2}); closed forms within {:.1e} / {:.1e}; {} iterations",
            times.is_some(),
            off.0,
            off.1,
            c2.iterations()
        );
        assert!(dv < 1e-6, "{dv}");
        assert!(da < 1e-4, "{da}");
        assert!(cr > 0.1, "{cr}");
        assert!(off.0 < 1e-6 && off.1 < 1e-4, "{off:?}");
    }
}

#[test]
fn closed_form_derivatives_inside_the_intervals() {
    let kf = keys(&table::<f64>(), Some(&uneven(6)));
    let c2 = C2Spline::new(&kf).unwrap();
    let span = spans(&kf);
    for (i, span) in span.iter().enumerate() {
        for h in [0.2, 0.5, 0.85] {
            let q = c2.eval(i, h);
            let d = 1e-4 / span;
            let g = |s: f64| rotvec(q, c2.eval(i, h + s));
            let v = (g(d) - g(-d)) / (2.0 * 1e-4);
            let dd = 1e-3 / span;
            let g2 = |s: f64| rotvec(q, c2.eval(i, h + s));
            let a = (g2(dd) + g2(-dd)) / 1e-6;
            assert!((v - c2.angular_velocity(i, h)).norm() < 1e-7, "{i} {h}");
            assert!((a - c2.angular_acceleration(i, h)).norm() < 1e-4, "{i} {h}");
        }
    }
}

/// The clamped cubic spline through `(x_k, y_k)` with the end slopes the chords': slopes at
/// the knots, by the tridiagonal system of second-derivative continuity.
fn clamped_slopes(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let d: Vec<f64> = (0..n - 1).map(|i| x[i + 1] - x[i]).collect();
    let mut m = vec![0.0; n];
    m[0] = (y[1] - y[0]) / d[0];
    m[n - 1] = (y[n - 1] - y[n - 2]) / d[n - 2];
    // Rows k = 1..n−2: 2/d_{k−1} m_{k−1} + 4(1/d_{k−1} + 1/d_k) m_k + 2/d_k m_{k+1} = rhs.
    let inner = n - 2;
    let mut a = vec![0.0; inner];
    let mut b = vec![0.0; inner];
    let mut c = vec![0.0; inner];
    let mut r = vec![0.0; inner];
    for j in 0..inner {
        let k = j + 1;
        a[j] = 2.0 / d[k - 1];
        b[j] = 4.0 * (1.0 / d[k - 1] + 1.0 / d[k]);
        c[j] = 2.0 / d[k];
        r[j] =
            6.0 * ((y[k] - y[k - 1]) / (d[k - 1] * d[k - 1]) + (y[k + 1] - y[k]) / (d[k] * d[k]));
    }
    r[0] -= a[0] * m[0];
    r[inner - 1] -= c[inner - 1] * m[n - 1];
    for j in 1..inner {
        let w = a[j] / b[j - 1];
        b[j] -= w * c[j - 1];
        r[j] -= w * r[j - 1];
    }
    m[inner] = r[inner - 1] / b[inner - 1];
    for j in (0..inner - 1).rev() {
        m[j + 1] = (r[j] - c[j] * m[j + 2]) / b[j];
    }
    m
}

#[test]
fn about_one_axis_it_is_the_clamped_scalar_spline() {
    let angles = [0.2, 1.1, 0.7, 2.9, 3.6, 3.1];
    let (q, n) = about_axis(&angles);
    for times in [None, Some(uneven(6))] {
        let kf = keys(&q, times.as_deref());
        let x: Vec<f64> = match &times {
            Some(t) => t.clone(),
            None => (0..angles.len()).map(|i| i as f64).collect(),
        };
        let m = clamped_slopes(&x, &angles);
        let c2 = C2Spline::new(&kf).unwrap();
        let mut worst = 0.0f64;
        for i in 0..angles.len() - 1 {
            let d = x[i + 1] - x[i];
            for j in 0..=10 {
                let h = j as f64 / 10.0;
                let a = hermite(angles[i], m[i] * d, angles[i + 1], m[i + 1] * d, h);
                worst = worst.max(diff(c2.eval(i, h), Quat::from_axis_angle(n, a).unwrap()));
            }
        }
        assert!(worst < 1e-12, "{worst}");
        for (k, w) in c2.key_velocities().iter().enumerate() {
            assert!((*w - n * m[k]).norm() < 1e-12);
        }
    }
}

#[test]
fn keys_a_full_turn_apart_the_long_way_are_an_error() {
    let q = Quat::from_euler(EulerOrder::DAM, [0.3, -0.2, 0.9]);
    let kf = KeyFrames::new(&[q, q, -q], None, Hemisphere::AsGiven).unwrap();
    let e = C2Spline::new(&kf).unwrap_err();
    match &e {
        Error::BadKey { index: 2, source } => {
            assert!(matches!(**source, Error::BadParameter { .. }))
        }
        _ => panic!("{e}"),
    }
    // Chained, the same keys are three equal rotations.
    let kf = KeyFrames::new(&[q, q, -q], None, Hemisphere::Chain).unwrap();
    assert!(C2Spline::new(&kf).is_ok());
    // The long way short of a full turn is a curve, through the keys.
    let far = Quat::from_axis_angle(Vec3::new(1.0, 1.0, 0.0), 5.0).unwrap();
    let kf = KeyFrames::new(
        &[Quat::identity(), far, Quat::identity()],
        None,
        Hemisphere::AsGiven,
    )
    .unwrap();
    let c2 = C2Spline::new(&kf).unwrap();
    through_keys(&c2, kf.quats(), 1e-12);
}
