//! Interpolation (Dam et al. 1998, chapters 5–7), shown by number: Slerp's constant speed
//! on the great arc (Propositions 27–29), Lerp's mid-interval speed peak, LinEuler leaving
//! the arc, Squad through every key and C¹ there (Proposition 30) while Slerp is not,
//! frame distribution (§6.2). Tolerances of `common::Tol` (1e-12 f64, 1e-5 f32).

mod common;
use chasles::analysis::curvature::{curvature_energy, Width};
use chasles::analysis::velocity::{velocity_angle, velocity_chord};
use chasles::interp::lerp::{lerp, nlerp};
use chasles::interp::lin_mat::{lin_mat, non_rigidity, rotation_part};
use chasles::interp::slerp::{slerp, slerp_pow, slerp_shortest, slerp_trig};
use chasles::interp::timing::{distribute, largest_remainder};
use chasles::interp::{examples, interpolate, Frame, Hemisphere, KeyFrames, Method, Squad, Timing};
use chasles::{Error, EulerOrder, Quat, Real, Vec3};
use common::*;
use proptest::prelude::*;

fn qs<T: Real>(f: &[Frame<T>]) -> Vec<Quat<T>> {
    f.iter().map(|x| x.q).collect()
}

fn slerp_great_arc<T: Tol>((p, q): ([f64; 4], [f64; 4]), tol: f64) -> Result<(), TestCaseError> {
    let (p, q) = (quat_of::<T>(p), quat_of::<T>(q));
    let omega = (p - q).norm().atan2((p + q).norm()).to_f64() * 2.0;
    prop_assume!(omega > 1e-3 && omega < 3.1);
    let n = 20;
    let frames: Vec<Quat<T>> = (0..=n)
        .map(|k| slerp(p, q, T::from_f64(k as f64 / n as f64)))
        .collect();
    // Endpoints (6.8–6.9), unit length (6.10).
    close(&frames[0].to_array(), &p.to_array(), tol)?;
    close(&frames[n].to_array(), &q.to_array(), tol * 10.0)?;
    for f in &frames {
        close(&[f.norm()], &[T::ONE], tol)?;
        // In the plane of p and q: f = a p + b q exactly (Proposition 28).
        let pq = p.dot(q);
        let (fp, fq) = (f.dot(p), f.dot(q));
        let det = T::ONE - pq * pq;
        let a = (fp - fq * pq) / det;
        let b = (fq - fp * pq) / det;
        close(&(p * a + q * b).to_array(), &f.to_array(), tol * 100.0)?;
    }
    // Constant speed: every step turns by Ω/n in 4D.
    for w in frames.windows(2) {
        let step = T::TWO * (w[1] - w[0]).norm().atan2((w[1] + w[0]).norm());
        close(&[step], &[T::from_f64(omega / n as f64)], tol * 100.0)?;
    }
    // The shorter arc between the 4D points (Proposition 29): p·slerp(½) ≥ 0.
    prop_assert!(p.dot(frames[n / 2]) >= T::ZERO);
    // Eq. 6.13 = eq. 6.4–6.7 (Proposition 27), and symmetry.
    let h = T::from_f64(0.3);
    let want = slerp(p, q, h).to_array();
    close(&slerp_pow(p, q, h).unwrap().to_array(), &want, tol * 10.0)?;
    close(
        &((p * q.conjugate()).powf(T::ONE - h).unwrap() * q).to_array(),
        &want,
        tol * 10.0,
    )?;
    close(
        &((q * p.conjugate()).powf(h).unwrap() * p).to_array(),
        &want,
        tol * 10.0,
    )?;
    close(
        &(q * (q.conjugate() * p).powf(T::ONE - h).unwrap()).to_array(),
        &want,
        tol * 10.0,
    )?;
    close(&slerp(q, p, T::ONE - h).to_array(), &want, tol * 10.0)
}
both_precisions!(
    slerp_is_the_constant_speed_great_arc,
    slerp_great_arc,
    unit_quat(),
    unit_quat()
);

fn slerp_tiny_angles<T: Tol>(
    (p, axis): ([f64; 4], [f64; 3]),
    tol: f64,
) -> Result<(), TestCaseError> {
    let p = quat_of::<T>(p);
    let axis = vec_of::<T>(axis);
    prop_assume!(axis.norm().to_f64() > 0.1);
    for d in [0.0, 1e-30, 1e-15, 1e-9, 1e-5] {
        let q = p * Quat::from_axis_angle(axis, T::from_f64(d)).unwrap();
        for h in [0.0, 0.25, 0.5, 1.0] {
            let h = T::from_f64(h);
            let s = slerp(p, q, h);
            prop_assert!(s.is_finite(), "d = {d}");
            close(&[s.norm()], &[T::ONE], tol)?;
            close(&s.to_array(), &nlerp(p, q, h).to_array(), tol)?;
        }
    }
    // Antipodal keys: defined, unit, constant speed; the shortest rotation stays put.
    let q = -p;
    let frames: Vec<Quat<T>> = (0..=8)
        .map(|k| slerp(p, q, T::from_f64(k as f64 / 8.0)))
        .collect();
    close(&frames[8].to_array(), &q.to_array(), tol * 10.0)?;
    let steps: Vec<T> = frames.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
    for s in &steps {
        close(&[*s], &[steps[0]], tol * 10.0)?;
    }
    for k in 0..=8 {
        let s = slerp_shortest(p, q, T::from_f64(k as f64 / 8.0));
        close(&s.to_array(), &p.to_array(), tol)?;
    }
    Ok(())
}
both_precisions!(
    slerp_is_exact_for_tiny_and_antipodal_angles,
    slerp_tiny_angles,
    unit_quat(),
    any_vec()
);

fn two_keys<T: Real>(angle: f64) -> KeyFrames<T> {
    let a = Quat::identity();
    let b = Quat::from_axis_angle(Vec3::new(T::ONE, T::TWO, T::ZERO), T::from_f64(angle)).unwrap();
    KeyFrames::new(&[a, b], None, Hemisphere::Chain).unwrap()
}

#[test]
fn lerp_speed_peaks_mid_interval_and_slerp_is_flat() {
    let keys = two_keys::<f64>(2.5);
    let n = 101;
    let lerp_v = velocity_angle(&qs(
        &interpolate(Method::Nlerp, &keys, n, Timing::Uniform).unwrap()
    ));
    let slerp_v = velocity_angle(&qs(
        &interpolate(Method::Slerp, &keys, n, Timing::Uniform).unwrap()
    ));
    let mid = n / 2;
    let (lmax, lmin) = (lerp_v[mid], lerp_v[1]);
    assert!(
        lerp_v.iter().all(|v| *v <= lmax + 1e-15),
        "Lerp's speed peaks mid-interval"
    );
    // At the middle the chord is cos(Ω/2) = cos(0.625) long: speed × 1/cos² ≈ 1.5.
    assert!(lmax / lmin > 1.45, "peak {lmax} vs end {lmin}");
    let (smin, smax) = slerp_v
        .iter()
        .fold((f64::MAX, 0.0f64), |(a, b), v| (a.min(*v), b.max(*v)));
    assert!(
        (smax - smin) / smax < 1e-12,
        "Slerp speed varies by {}",
        (smax - smin) / smax
    );
    // The raw Lerp is a chord of constant chord speed, inside the sphere.
    let raw = interpolate(Method::Lerp, &keys, n, Timing::Uniform).unwrap();
    let chord = velocity_chord(&qs(&raw));
    assert!((chord[mid] - chord[1]).abs() < 1e-12);
    assert!(raw[mid].q.norm() < 0.9);
    assert_eq!(lerp(keys.quats()[0], keys.quats()[1], 0.5f64), raw[mid].q);
}

#[test]
fn lin_euler_leaves_the_great_arc_and_slerp_does_not() {
    let set = examples::table_5_1();
    let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain).unwrap();
    let off_arc = |m| {
        let f = interpolate(m, &keys, 300, Timing::Uniform).unwrap();
        // Distance of each frame from the plane of its interval's two keys.
        f.iter()
            .filter(|x| x.key.is_none())
            .map(|x| {
                let i = x.t.floor() as usize;
                let (p, q) = (keys.quats()[i], keys.quats()[i + 1]);
                let pq = p.dot(q);
                let det = 1.0 - pq * pq;
                let (fp, fq) = (x.q.dot(p), x.q.dot(q));
                let proj = p * ((fp - fq * pq) / det) + q * ((fq - fp * pq) / det);
                (x.q - proj).norm()
            })
            .fold(0.0f64, f64::max)
    };
    let lin_euler = off_arc(Method::LinEuler(EulerOrder::DAM));
    let slerp = off_arc(Method::Slerp);
    assert!(lin_euler > 0.05, "LinEuler off the arc by only {lin_euler}");
    assert!(slerp < 1e-12, "Slerp off the arc by {slerp}");
    // LinEuler's frames are rotations (unit), unlike raw Lerp.
    let f = interpolate(
        Method::LinEuler(EulerOrder::DAM),
        &keys,
        300,
        Timing::Uniform,
    )
    .unwrap();
    assert!(f.iter().all(|x| (x.q.norm() - 1.0).abs() < 1e-12));
}

/// Eq. 6.1 on the triples given: keys (0, 0, 0) and (0, 0, 4) in order xyz pass the
/// rotation by 2 rad about z halfway, where angles re-extracted from the key rotations
/// (principal value 4 − 2π ≈ −2.28) would give −1.14 rad; keys given as rotations, or
/// LinEuler in another order, still take the extracted angles; bad triples are typed errors.
#[test]
fn lin_euler_interpolates_the_given_euler_triples() {
    let xyz: EulerOrder = "xyz".parse().unwrap();
    let triples = [[0.0, 0.0, 0.0], [0.0, 0.0, 4.0]];
    let keys = KeyFrames::from_euler(xyz, &triples, None, Hemisphere::Chain).unwrap();
    assert_eq!(keys.euler(), Some((xyz, &triples[..])));
    let f = interpolate(Method::LinEuler(xyz), &keys, 3, Timing::Uniform).unwrap();
    let want = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 2.0).unwrap();
    assert!(f[1].q.dot(want).abs() > 1.0 - 1e-15, "{:?}", f[1].q);
    // Frames along the way turn steadily about z, 4 h rad at h, the quaternions continuous
    // through the last key too (its stored, hemisphere-chained sign is the other one): the
    // velocity of eq. 5.1 has no jump.
    let f = interpolate(Method::LinEuler(xyz), &keys, 9, Timing::Uniform).unwrap();
    for (k, x) in f.iter().enumerate() {
        let a = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 4.0 * k as f64 / 8.0).unwrap();
        assert!(x.q.dot(a) > 1.0 - 1e-15, "frame {k}: {:?}", x.q);
    }
    assert!(
        keys.quats()[1].dot(f[8].q) < -1.0 + 1e-15,
        "the key's chained sign"
    );
    let v = velocity_chord(&qs(&f));
    let (lo, hi) = v
        .iter()
        .fold((f64::MAX, 0.0f64), |(a, b), x| (a.min(*x), b.max(*x)));
    assert!(hi / lo < 1.0 + 1e-12, "{v:?}");
    // The same rotations as plain keys: the principal angles, −1.14 rad halfway.
    let plain = KeyFrames::new(keys.quats(), None, Hemisphere::Chain).unwrap();
    let f = interpolate(Method::LinEuler(xyz), &plain, 3, Timing::Uniform).unwrap();
    let principal = (4.0 - std::f64::consts::TAU) / 2.0;
    let want = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), principal).unwrap();
    assert!(f[1].q.dot(want).abs() > 1.0 - 1e-12, "{:?}", f[1].q);
    // LinEuler in another order than the keys': extracted, not the given triples.
    let zyx: EulerOrder = "zyx".parse().unwrap();
    let f = interpolate(Method::LinEuler(zyx), &keys, 3, Timing::Uniform).unwrap();
    assert!(f[1].q.dot(want).abs() > 1.0 - 1e-12, "{:?}", f[1].q);
    let bad = KeyFrames::<f64>::from_euler(
        xyz,
        &[[0.0; 3], [f64::NAN, 0.0, 0.0]],
        None,
        Hemisphere::Chain,
    );
    assert!(
        matches!(bad, Err(Error::BadKey { index: 1, .. })),
        "{bad:?}"
    );
}

/// Left and right derivatives d/dh at key `k` (second-order one-sided differences).
fn one_sided(eval: &dyn Fn(usize, f64) -> Quat<f64>, k: usize) -> (Quat<f64>, Quat<f64>) {
    let d = 1e-4;
    let l = (eval(k - 1, 1.0) * 3.0 - eval(k - 1, 1.0 - d) * 4.0 + eval(k - 1, 1.0 - 2.0 * d))
        / (2.0 * d);
    let r = (eval(k, 0.0) * -3.0 + eval(k, d) * 4.0 - eval(k, 2.0 * d)) / (2.0 * d);
    (l, r)
}

#[test]
fn squad_passes_through_keys_and_is_c1_there_while_slerp_is_not() {
    for set in examples::all() {
        let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain).unwrap();
        let sq = Squad::new(&keys).unwrap();
        let q = keys.quats();
        for k in 0..q.len() - 1 {
            assert_eq!(sq.eval(k, 0.0), q[k], "{}: key {k}", set.name);
            assert!(
                (sq.eval(k, 1.0) - q[k + 1]).norm() < 1e-15,
                "{}: key {}",
                set.name,
                k + 1
            );
        }
        let mut slerp_jump = 0.0f64;
        for k in 1..q.len() - 1 {
            let (l, r) = one_sided(&|i, h| sq.eval(i, h), k);
            assert!(
                (l - r).norm() < 1e-6,
                "{}: Squad derivative jumps by {} at key {k}",
                set.name,
                (l - r).norm()
            );
            let (l, r) = one_sided(&|i, h| slerp(q[i], q[i + 1], h), k);
            slerp_jump = slerp_jump.max((l - r).norm());
        }
        assert!(
            slerp_jump > 1e-2,
            "{}: Slerp is C1? jump {slerp_jump}",
            set.name
        );
        // Every key appears exactly once among the frames, flagged.
        let f = interpolate(Method::Squad, &keys, 120, Timing::Angle).unwrap();
        assert_eq!(f.len(), 120);
        let flagged: Vec<usize> = f.iter().filter_map(|x| x.key).collect();
        assert_eq!(flagged, (0..q.len()).collect::<Vec<_>>());
        for x in &f {
            if let Some(k) = x.key {
                assert_eq!(x.q, q[k]);
            }
        }
    }
}

#[test]
fn squad_in_f32_matches_f64() {
    let set = examples::table_5_1();
    let k64 = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain).unwrap();
    let k32 = KeyFrames::new(&set.keys::<f32>(), None, Hemisphere::Chain).unwrap();
    let a = interpolate(Method::Squad, &k64, 200, Timing::Angle).unwrap();
    let b = interpolate(Method::Squad, &k32, 200, Timing::Angle).unwrap();
    for (x, y) in a.iter().zip(&b) {
        let d = (x.q - y.q.cast::<f64>()).norm();
        assert!(d < 1e-5, "f32 Squad differs by {d}");
    }
}

#[test]
fn every_method_stays_on_the_pendulum_arc() {
    let set = examples::by_name("pendulum").unwrap();
    let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain).unwrap();
    for m in [
        Method::Slerp,
        Method::Nlerp,
        Method::Squad,
        Method::LinMat,
        Method::LinEuler(EulerOrder::DAM),
    ] {
        for f in interpolate(m, &keys, 100, Timing::Angle).unwrap() {
            assert!(
                f.q.y.abs() < 1e-12 && f.q.z.abs() < 1e-12,
                "{m:?} leaves the arc: {:?}",
                f.q
            );
        }
    }
}

#[test]
fn angle_timing_shares_frames_by_interval_angle() {
    let set = examples::table_5_1();
    let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain).unwrap();
    let counts = distribute(&keys, 550, Timing::Angle).unwrap();
    assert_eq!(counts.iter().sum::<usize>(), 550 - 6);
    let q = keys.quats();
    let angles: Vec<f64> = q
        .windows(2)
        .map(|w| w[0].dot(w[1]).abs().min(1.0).acos())
        .collect();
    let total: f64 = angles.iter().sum();
    for (c, a) in counts.iter().zip(&angles) {
        assert!((*c as f64 - a / total * 544.0).abs() <= 1.0, "{counts:?}");
    }
    // Slerp with angle timing has (nearly) constant speed across intervals (Figure 6.8).
    let v = velocity_angle(&qs(
        &interpolate(Method::Slerp, &keys, 550, Timing::Angle).unwrap()
    ));
    let inner = &v[1..v.len() - 1];
    let (lo, hi) = inner
        .iter()
        .fold((f64::MAX, 0.0f64), |(a, b), x| (a.min(*x), b.max(*x)));
    assert!(hi / lo < 1.1, "speed ratio {}", hi / lo);
    let u = velocity_angle(&qs(&interpolate(
        Method::Slerp,
        &keys,
        550,
        Timing::Uniform,
    )
    .unwrap()));
    let (lo, hi) = u[1..u.len() - 1]
        .iter()
        .fold((f64::MAX, 0.0f64), |(a, b), x| (a.min(*x), b.max(*x)));
    assert!(hi / lo > 1.3, "uniform timing should vary: {}", hi / lo);
    assert_eq!(
        largest_remainder(&[1.0, 1.0, 1.0], 10)
            .iter()
            .sum::<usize>(),
        10
    );
    assert_eq!(largest_remainder(&[0.0, 0.0], 3), vec![2, 1]);
}

#[test]
fn key_times_set_the_parameter_and_uniform_timing_follows_them() {
    let q: Vec<Quat<f64>> = examples::table_5_1().keys()[..3].to_vec();
    let keys = KeyFrames::new(&q, Some(&[0.0, 1.0, 5.0]), Hemisphere::Chain).unwrap();
    let f = interpolate(Method::Slerp, &keys, 53, Timing::Uniform).unwrap();
    assert_eq!(
        distribute(&keys, 53, Timing::Uniform).unwrap(),
        vec![10, 40]
    );
    assert_eq!(f[0].t, 0.0);
    assert_eq!(f[11].t, 1.0);
    assert_eq!(f[11].key, Some(1));
    assert_eq!(f[52].t, 5.0);
    assert!(f.windows(2).all(|w| w[1].t > w[0].t));
}

#[test]
fn lin_mat_is_not_rigid_and_its_rotation_part_is_nearest() {
    let a = Quat::<f64>::identity();
    let b = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 2.0).unwrap();
    let (ma, mb) = (a.to_rotation_matrix(), b.to_rotation_matrix());
    let mid = lin_mat(&ma, &mb, 0.5);
    assert!(
        non_rigidity(&mid) > 0.3,
        "LinMat midpoint should shrink: {}",
        non_rigidity(&mid)
    );
    assert!(non_rigidity(&ma) < 1e-15);
    // Rotation part of the midpoint of a turn about z is the half turn (symmetry).
    let r = rotation_part(&mid).unwrap();
    let want = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 1.0).unwrap();
    assert!((r - want).norm() < 1e-12, "{r:?}");
    assert!((rotation_part(&mb).unwrap() - b).norm() < 1e-15);
    // 180° apart: the midpoint is singular — a typed error, not a NaN.
    let c = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), std::f64::consts::PI).unwrap();
    let m = lin_mat(&ma, &c.to_rotation_matrix(), 0.5);
    assert!(matches!(rotation_part(&m), Err(Error::NotRotation { .. })));
}

#[test]
fn curvature_energy_of_a_great_arc_is_zero_and_of_squad_is_not() {
    let keys = two_keys::<f64>(1.5);
    let arc = qs(&interpolate(Method::Slerp, &keys, 50, Timing::Uniform).unwrap());
    assert!(curvature_energy(&arc, Width::Unit) < 1e-28);
    assert!(curvature_energy(&arc, Width::Centered) < 1e-24);
    assert!(curvature_energy(&arc, Width::Angle) < 1e-24);
    let set = examples::table_5_1();
    let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain).unwrap();
    let e_squad = curvature_energy(
        &qs(&interpolate(Method::Squad, &keys, 550, Timing::Angle).unwrap()),
        Width::Unit,
    );
    let e_slerp = curvature_energy(
        &qs(&interpolate(Method::Slerp, &keys, 550, Timing::Angle).unwrap()),
        Width::Unit,
    );
    assert!(
        e_squad > 0.0 && e_squad < e_slerp / 10.0,
        "squad {e_squad} slerp {e_slerp}"
    );
}

#[test]
fn bad_keys_get_typed_errors() {
    let one = [Quat::<f64>::identity()];
    assert!(matches!(
        KeyFrames::new(&one, None, Hemisphere::Chain),
        Err(Error::TooFewKeys { got: 1, .. })
    ));
    let zero = [Quat::<f64>::identity(), Quat::zero(), Quat::identity()];
    let e = KeyFrames::new(&zero, None, Hemisphere::Chain).unwrap_err();
    assert!(matches!(e, Error::BadKey { index: 1, .. }), "{e}");
    assert!(e.to_string().contains("key frame 1"));
    let two = [Quat::<f64>::identity(), Quat::identity()];
    assert!(matches!(
        KeyFrames::new(&two, Some(&[1.0, 1.0]), Hemisphere::Chain),
        Err(Error::BadKeyTime { index: 1, .. })
    ));
    assert!(matches!(
        KeyFrames::new(&two, Some(&[0.0, f64::NAN]), Hemisphere::Chain),
        Err(Error::BadKeyTime { .. })
    ));
    assert!(matches!(
        KeyFrames::new(&two, Some(&[0.0]), Hemisphere::Chain),
        Err(Error::WrongLength { .. })
    ));
    let keys = KeyFrames::new(&two, None, Hemisphere::Chain).unwrap();
    assert!(matches!(
        interpolate(Method::Slerp, &keys, 1, Timing::Uniform),
        Err(Error::TooFewFrames { frames: 1, keys: 2 })
    ));
    // Hemisphere: Chain flips a key into the previous one's hemisphere; AsGiven keeps it.
    let flip = [Quat::<f64>::identity(), -Quat::identity()];
    assert_eq!(
        KeyFrames::new(&flip, None, Hemisphere::Chain)
            .unwrap()
            .quats()[1],
        Quat::identity()
    );
    assert_eq!(
        KeyFrames::new(&flip, None, Hemisphere::AsGiven)
            .unwrap()
            .quats()[1],
        -Quat::identity()
    );
}

#[test]
fn reduced_weights_match_trigonometry_to_f64_rounding() {
    // The weights Slerp uses up to a quarter turn, against sin(hΩ)/sin Ω in f64 (sinc form
    // at small Ω), from Ω = 1e-9 to π/2; exact at h = 0 and h = 1, and 1 − h, h at Ω = 0.
    use chasles::interp::slerp::slerp_weights_reduced;
    let p = Quat::new(0.5, -0.5, 0.5, 0.5);
    let perp = Quat::new(0.5, 0.5, 0.5, -0.5); // p·perp = 0
    let mut worst = 0.0f64;
    let omegas = (0..=400)
        .map(|i| i as f64 / 400.0 * std::f64::consts::FRAC_PI_2)
        .chain([1e-9, 1e-6, 1e-4, 1e-2]);
    for omega in omegas {
        let q = p * omega.cos() + perp * omega.sin();
        for k in 0..=100 {
            let h = k as f64 / 100.0;
            let (a, b) = slerp_weights_reduced(p, q, h);
            let w = |t: f64| {
                if omega < 1e-3 {
                    let sinc = |x: f64| if x == 0.0 { 1.0 } else { x.sin() / x };
                    t * sinc(t * omega) / sinc(omega)
                } else {
                    (t * omega).sin() / omega.sin()
                }
            };
            assert!(a.is_finite() && b.is_finite(), "Ω = {omega}, h = {h}");
            worst = worst.max((a - w(1.0 - h)).abs()).max((b - w(h)).abs());
        }
        assert_eq!(slerp_weights_reduced(p, q, 0.0), (1.0, 0.0), "Ω = {omega}");
        assert_eq!(slerp_weights_reduced(p, q, 1.0), (0.0, 1.0), "Ω = {omega}");
    }
    assert!(worst < 2e-15, "reduced weights off by {worst:e}");
    assert_eq!(slerp_weights_reduced(p, p, 0.25), (0.75, 0.25));
}

#[test]
fn eberly_series_weights_match_trigonometry() {
    use chasles::interp::slerp::slerp_weights_series;
    let mut worst = 0.0f64;
    for i in 0..=400 {
        let omega = i as f64 / 400.0 * std::f64::consts::FRAC_PI_2;
        for k in 0..=100 {
            let h = k as f64 / 100.0;
            let (a, b) = slerp_weights_series(omega.cos(), h);
            let (wa, wb) = if omega == 0.0 {
                (1.0 - h, h)
            } else {
                (
                    ((1.0 - h) * omega).sin() / omega.sin(),
                    (h * omega).sin() / omega.sin(),
                )
            };
            worst = worst.max((a - wa).abs()).max((b - wb).abs());
        }
    }
    assert!(worst < 4e-8, "series weights off by {worst}");
    assert_eq!(slerp_weights_series(0.3f32, 0.0), (1.0, 0.0));
    assert_eq!(slerp_weights_series(0.3f32, 1.0), (0.0, 1.0));
}

#[test]
fn f32_weights_match_trigonometry_to_f32_rounding() {
    // The weights f32 Slerp uses up to a quarter turn, computed in f32, against
    // sin(hΩ)/sin Ω in f64 at the very f32 cosine they were given (so only their own
    // rounding counts): within four ulp of 1 everywhere (2.2e-7 measured, near a quarter
    // turn with h near 0 or 1), near Ω = 0 included, and exact at h = 0 and h = 1.
    use chasles::interp::slerp::slerp_weights_f32;
    let mut worst = 0.0f64;
    let xs = (0..=2000)
        .map(|i| i as f32 / 2000.0)
        .chain((1..=200).map(|i| 1.0 - i as f32 * 1e-7))
        .chain([1.0 - f32::EPSILON, 1.0]);
    for x in xs {
        let omega = f64::from(x).acos();
        for k in 0..=200 {
            let h = k as f32 / 200.0;
            let (a, b) = slerp_weights_f32(x, h);
            let w = |t: f64| {
                let sinc = |u: f64| if u == 0.0 { 1.0 } else { u.sin() / u };
                t * sinc(t * omega) / sinc(omega)
            };
            let h64 = f64::from(h);
            let e = (f64::from(a) - w(1.0 - h64))
                .abs()
                .max((f64::from(b) - w(h64)).abs());
            worst = worst.max(e);
        }
        assert_eq!(slerp_weights_f32(x, 0.0), (1.0, 0.0), "x = {x}");
        assert_eq!(slerp_weights_f32(x, 1.0), (0.0, 1.0), "x = {x}");
    }
    assert!(worst < 2.4e-7, "f32 weights off by {worst:e}");
    // Through Slerp: every f32 pair within a quarter turn, against the f64 form.
    let p = Quat::new(0.5f32, -0.5, 0.5, 0.5);
    let perp = Quat::new(0.5f32, 0.5, 0.5, -0.5);
    for i in 0..=90 {
        let omega = (i as f32).to_radians();
        let q = p * omega.cos() + perp * omega.sin();
        for k in 0..=10 {
            let h = k as f32 / 10.0;
            let got = slerp(p, q, h).cast::<f64>();
            let want = slerp_trig(p.cast::<f64>(), q.cast::<f64>(), f64::from(h));
            assert!(
                (got - want).norm() < 3e-7,
                "Ω = {i}°, h = {h}: {got:?} vs {want:?}"
            );
        }
    }
}

proptest! {
    /// `slerp_shortest` takes the shorter arc's sign by a mask and puts it on q's weight
    /// (f64): the bits of `slerp` towards the flipped q, and the same from q and −q, in f64
    /// and f32, for h in [0, 1] (where the kernels run).
    #[test]
    fn shortest_slerp_is_slerp_to_the_flipped_end_bit_for_bit(a in unit_quat(), b in unit_quat(), h in 0.0f64..=1.0) {
        let (p, q) = (quat_of::<f64>(a), quat_of::<f64>(b));
        let sq = if p.dot(q) < 0.0 { -q } else { q };
        let bits = |q: Quat<f64>| q.to_array().map(f64::to_bits);
        prop_assert_eq!(bits(slerp_shortest(p, q, h)), bits(slerp(p, sq, h)));
        // At p·q = 0 exactly both arcs are as short and q is taken as given, so q and −q
        // give different (equally short) arcs there.
        if p.dot(q) != 0.0 {
            prop_assert_eq!(bits(slerp_shortest(p, q, h)), bits(slerp_shortest(p, -q, h)));
        }
        let (p, q, h) = (p.cast::<f32>(), q.cast::<f32>(), h as f32);
        let sq = if p.dot(q) < 0.0 { -q } else { q };
        let bits = |q: Quat<f32>| q.to_array().map(f32::to_bits);
        prop_assert_eq!(bits(slerp_shortest(p, q, h)), bits(slerp(p, sq, h)));
    }
}

#[test]
fn shortest_slerp_batch_is_the_per_pair_slerp_and_extrapolates_by_trigonometry() {
    use chasles::interp::slerp::{slerp_shortest, slerp_shortest_batch, slerp_trig};
    let p: Vec<Quat<f64>> = (0..50)
        .map(|i| Quat::from_axis_angle(Vec3::new(1.0, i as f64, 2.0), 0.1 * i as f64).unwrap())
        .collect();
    let q: Vec<Quat<f64>> = (0..50)
        .map(|i| {
            let r = Quat::from_axis_angle(Vec3::new(-1.0, 0.5, i as f64), 0.07 * i as f64);
            // Every other one on the far hemisphere: the batch takes the shorter arc.
            r.unwrap() * if i % 2 == 0 { 1.0 } else { -1.0 }
        })
        .collect();
    let h: Vec<f64> = (0..50).map(|i| i as f64 / 49.0).collect();
    let mut out = vec![Quat::identity(); 50];
    slerp_shortest_batch(&p, &q, &h, &mut out).unwrap();
    for i in 0..50 {
        assert_eq!(out[i], slerp_shortest(p[i], q[i], h[i]), "pair {i}");
    }
    // Outside [0, 1]: extrapolation along the same great circle, by trigonometry, in the
    // batch as per pair.
    let far: Vec<f64> = (0..50).map(|i| -1.0 + 4.0 * i as f64 / 49.0).collect();
    slerp_shortest_batch(&p, &q, &far, &mut out).unwrap();
    for i in 0..50 {
        let qi = if p[i].dot(q[i]) < 0.0 { -q[i] } else { q[i] };
        let want = slerp_trig(p[i], qi, far[i]);
        assert!((out[i] - want).norm() < 1e-12, "pair {i} at h = {}", far[i]);
        assert!((out[i].norm() - 1.0).abs() < 1e-12);
    }
    // h = 2 is the rotation p (p* q)²: twice the way.
    let (a, b) = (p[7], q[8]);
    let b = if a.dot(b) < 0.0 { -b } else { b };
    let twice = a * (a.conjugate() * b) * (a.conjugate() * b);
    assert!((slerp_shortest(a, b, 2.0) - twice).norm() < 1e-12);
    let e = slerp_shortest_batch(&p, &q[..3], &h, &mut out).unwrap_err();
    assert_eq!(
        e.to_string(),
        "slerp_shortest_batch: p and q: 50 and 3 values, which must be as many"
    );
}

/// f32 `slerp_shortest` extrapolates without a call (its own reduction of hΩ by π, so that
/// a loop of it is vectorized): against the f64 trigonometric form on random pairs, a
/// quarter of them close together, for h far outside [0, 1]; the error grows as the
/// rounding of hΩ itself does. Far past what f32 resolves it still gives unit quaternions
/// on the great circle; NaN or infinite h gives NaN; h = 0 and 1 give p and q exactly.
/// Each error is scaled by 1 + |h|, the growth of the rounding of hΩ.
#[test]
fn f32_shortest_slerp_extrapolates_without_trigonometry() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::StdRng::seed_from_u64(18);
    let unit = |rng: &mut rand::rngs::StdRng| loop {
        let q = Quat::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        let n: f64 = q.norm();
        if n > 0.1 && n < 1.0 {
            return q * (1.0 / n);
        }
    };
    let (mut worst, mut worst_trig) = (0f64, 0f64);
    for i in 0..20_000 {
        let p = unit(&mut rng);
        let q = if i % 4 == 0 {
            let d = unit(&mut rng) * 1e-3;
            (p + d).normalize().unwrap()
        } else {
            unit(&mut rng)
        };
        let h: f64 = rng.random_range(-40.0..40.0);
        let (p32, q32, h32) = (p.cast::<f32>(), q.cast::<f32>(), h as f32);
        // The reference on the f32 inputs, in f64.
        let (pw, qw, hw) = (p32.cast::<f64>(), q32.cast::<f64>(), f64::from(h32));
        let qw = if pw.dot(qw) < 0.0 { -qw } else { qw };
        let want = slerp_trig(pw, qw, hw);
        let got = slerp_shortest(p32, q32, h32).cast::<f64>();
        let err = (got - want).norm() / (1.0 + hw.abs());
        // The f32 trigonometric form on the same inputs: acos or atan2, and sin.
        let q32 = if p32.dot(q32) < 0.0 { -q32 } else { q32 };
        let trig = (slerp_trig(p32, q32, h32).cast::<f64>() - want).norm() / (1.0 + hw.abs());
        worst = worst.max(err);
        worst_trig = worst_trig.max(trig);
    }
    // Measured: 2.9e-7 against the f32 trigonometric form's 2.4e-7.
    assert!(
        worst < 1.5 * worst_trig && worst_trig < 4e-7,
        "extrapolation off by {worst:e} (the f32 trigonometric form by {worst_trig:e})"
    );
    let (p, q) = (
        Quat::<f32>::from_axis_angle(Vec3::new(1.0, 2.0, 3.0), 0.3).unwrap(),
        Quat::<f32>::from_axis_angle(Vec3::new(-1.0, 0.0, 2.0), 1.1).unwrap(),
    );
    assert_eq!(slerp_shortest(p, q, 0.0), p);
    assert_eq!(slerp_shortest(p, q, 1.0), q);
    assert_eq!(slerp_shortest(p, -q, 1.0), q);
    let (pw, qw) = (p.cast::<f64>(), q.cast::<f64>());
    let e2 = (qw - pw * qw.dot(pw)).normalize().unwrap();
    for h in [1e5f32, -3e6, 1e9, -1e20, f32::MAX, f32::MIN] {
        let s = slerp_shortest(p, q, h);
        assert!((s.norm() - 1.0).abs() < 1e-6, "h = {h}: {s:?}");
        // On the great circle through p and q: no component off their plane.
        let s = s.cast::<f64>();
        let off = s - pw * s.dot(pw) - e2 * s.dot(e2);
        assert!(off.norm() < 1e-6, "h = {h}: {off:?}");
    }
    // p = q: every h gives p (no 0/0 at Ω = 0), up to the rounding of (1 − h) p + h p.
    for h in [-7.0f32, 3.5, 1e3] {
        let tol = 4.0 * f32::EPSILON * h.abs().max(1.0);
        assert!((slerp_shortest(p, p, h) - p).norm() <= tol, "h = {h}");
    }
    for h in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let s = slerp_shortest(p, q, h);
        assert!(s.w.is_nan(), "h = {h}: {s:?}");
    }
}

#[test]
fn lineuler_on_angles_at_the_top_of_f64_gives_unit_frames() {
    // (1 − h) a + h b never rounds past f64's largest value, and the sine and cosine of any
    // finite angle are finite: every frame is a unit quaternion (interpolate would refuse a
    // frame that is not finite rather than return it).
    use chasles::EulerOrder;
    let m = f64::MAX;
    let triples = [[m, -m, m], [-m, m, 0.0], [m, m, -m]];
    let keys = KeyFrames::from_euler(EulerOrder::DAM, &triples, None, Hemisphere::Chain).unwrap();
    let frames = interpolate(
        Method::LinEuler(EulerOrder::DAM),
        &keys,
        101,
        Timing::Uniform,
    )
    .unwrap();
    assert!(
        frames.iter().all(|f| (f.q.norm() - 1.0).abs() < 1e-12),
        "a frame that is not unit"
    );
}
