//! Blending of rigid transformations (Kavan et al. 2006): weights and each method's
//! defining behaviour (Table 1 and the paper's claims are measured in `chasles-paper`).

mod common;

use chasles::blend::dib::{dib, dib_convex};
use chasles::blend::dlb::{dlb, dlb_convex};
use chasles::blend::log::{
    exp_twist, log_blend, log_blend_iterative, log_blend_iterative_from, log_rigid,
};
use chasles::blend::qlb::{qlb, qlb_convex};
use chasles::blend::sclerp::sclerp;
use chasles::blend::weights::convex_weights;
use chasles::blend::{blend_dual_quats, blend_matrices, Method, Options};
use chasles::{DualQuat, Error, Mat4, Quat, Vec3};
use proptest::prelude::*;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn rigid(axis: [f64; 3], angle: f64, t: [f64; 3]) -> DualQuat<f64> {
    DualQuat::from_rotation_translation(
        Quat::from_axis_angle(Vec3::from_array(axis), angle).unwrap(),
        Vec3::from_array(t),
    )
}

fn rng(seed: u64) -> StdRng {
    StdRng::seed_from_u64(seed)
}

#[test]
fn weights_are_checked_and_scaled() {
    assert_eq!(convex_weights(&[1.0f64, 3.0], 2).unwrap(), vec![0.25, 0.75]);
    assert_eq!(
        convex_weights(&[-0.1f64, 1.0], 2),
        Err(Error::BadWeight {
            index: 0,
            value: -0.1
        })
    );
    assert!(matches!(
        convex_weights(&[0.5f64, f64::NAN], 2),
        Err(Error::BadWeight { index: 1, .. })
    ));
    assert!(matches!(
        convex_weights(&[0.5f64, f64::INFINITY], 2),
        Err(Error::BadWeight { index: 1, .. })
    ));
    assert_eq!(
        convex_weights(&[0.0f64, 0.0], 2),
        Err(Error::WeightSum { sum: 0.0 })
    );
    assert!(matches!(
        convex_weights(&[1.0f64], 2),
        Err(Error::BlendInput { .. })
    ));
    assert!(matches!(
        convex_weights::<f64>(&[], 0),
        Err(Error::BlendInput { .. })
    ));
    let x = [DualQuat::<f64>::identity(); 2];
    for m in Method::ALL {
        let e = blend_dual_quats(m, &x, &[0.0, 0.0], &Options::default()).unwrap_err();
        assert!(e.to_string().contains("sum to 0"), "{m:?}: {e}");
    }
    // A non-rigid input matrix is named.
    let mut bad = Mat4::<f64>::identity();
    bad.m[0][0] = 2.0;
    let e = blend_matrices(
        Method::Dlb,
        &[Mat4::identity(), bad],
        &[0.5, 0.5],
        &Options::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("transform 1"), "{e}");
}

#[test]
fn alexa_blends_the_long_way_and_the_iterative_version_fixes_it() {
    // ±170° about z: axis–angle blending goes through 0°, the long way (Bloom et al.).
    let a = rigid([0.0, 0.0, 1.0], 170f64.to_radians(), [0.0; 3]).to_matrix4();
    let b = rigid([0.0, 0.0, 1.0], -170f64.to_radians(), [0.0; 3]).to_matrix4();
    let mid = log_blend(&[a, b], &[0.5, 0.5]).unwrap();
    assert!(
        mid.max_abs_diff(&Mat4::identity()) < 1e-12,
        "Alexa's midpoint is the identity"
    );
    // §5's iterative version from the identity stays on that long-way fixed point …
    let (it_mid, steps) = log_blend_iterative(&[a, b], &[0.5, 0.5], 1e-12, 50).unwrap();
    assert!(it_mid.max_abs_diff(&Mat4::identity()) < 1e-12 && steps == 0);
    // … started at an input it reaches the half turn, the shortest-path blend.
    let (from_a, _) = log_blend_iterative_from(&[a, b], &[0.5, 0.5], a, 1e-12, 50).unwrap();
    let half_turn = rigid([0.0, 0.0, 1.0], std::f64::consts::PI, [0.0; 3]).to_matrix4();
    assert!(from_a.max_abs_diff(&half_turn) < 1e-9, "{from_a:?}");
    // One iteration of the iterative version is Alexa's blend.
    let mut r = rng(4);
    for _ in 0..50 {
        let x: Vec<Mat4<f64>> = (0..3)
            .map(|_| common::random_rigid(&mut r).to_matrix4())
            .collect();
        let w = [0.2, 0.3, 0.5];
        let (one, _) = log_blend_iterative(&x, &w, 0.0, 1).unwrap();
        assert!(one.max_abs_diff(&log_blend(&x, &w).unwrap()) < 1e-12);
    }
}

#[test]
fn convex_blends_check_lengths_and_never_panic() {
    let q = [DualQuat::<f32>::identity(); 2];
    let c = Vec3::zero();
    for w in [&[][..], &[1.0f32][..], &[0.5, 0.25, 0.25][..]] {
        let what = |e: Error| matches!(e, Error::BlendInput { .. });
        assert!(what(dlb_convex(&q, w).unwrap_err()), "{w:?}");
        assert!(what(dib_convex(&q, w, 1e-5, 8).unwrap_err()), "{w:?}");
        assert!(what(qlb_convex(&q, w, c).unwrap_err()), "{w:?}");
    }
    assert!(
        dlb_convex(&[] as &[DualQuat<f32>], &[]).is_err(),
        "nothing to blend"
    );
    assert!(
        qlb_convex(&[] as &[DualQuat<f32>], &[], c).is_err(),
        "nothing to blend"
    );
}

proptest! {
    // The allocation-free blends (skinning calls them once per vertex) are the checked
    // blends after the weights are made convex: the same numbers, bit for bit, in f32 and
    // f64.
    #[test]
    fn convex_blends_are_the_blends_with_convex_weights(seed in 0u64..1000, n in 1usize..6) {
        let mut r = rng(seed);
        let x: Vec<DualQuat<f64>> = (0..n).map(|_| common::random_rigid(&mut r)).collect();
        let raw: Vec<f64> = (0..n).map(|i| 0.2 + ((seed as usize * 7 + i * 13) % 10) as f64).collect();
        let w = convex_weights(&raw, n).unwrap();
        let c = Vec3::new(0.3, -1.0, 2.0);
        prop_assert_eq!(dlb(&x, &raw).unwrap(), dlb_convex(&x, &w).unwrap());
        prop_assert_eq!(dib(&x, &raw, 1e-10, 20).unwrap(), dib_convex(&x, &w, 1e-10, 20).unwrap());
        prop_assert_eq!(qlb(&x, &raw, c).unwrap(), qlb_convex(&x, &w, c).unwrap());
        let x32: Vec<DualQuat<f32>> = x.iter().map(|d| d.cast()).collect();
        let (raw32, c32): (Vec<f32>, _) = (raw.iter().map(|v| *v as f32).collect(), c.cast());
        let w32 = convex_weights(&raw32, n).unwrap();
        prop_assert_eq!(dib(&x32, &raw32, 1e-5, 8).unwrap(), dib_convex(&x32, &w32, 1e-5, 8).unwrap());
        prop_assert_eq!(qlb(&x32, &raw32, c32).unwrap(), qlb_convex(&x32, &w32, c32).unwrap());
    }

    /// The twist of a screw motion in closed form: turning by θ about the axis n through c
    /// and sliding τ along it is `ω = θ n`, `v = c × ω + τ n` — at θ = π (the quaternion's
    /// w = 0, D's cotangent 0), just past the series' 1e-2, and between; f64 and f32.
    #[test]
    fn the_twist_of_a_screw_is_its_closed_form(
        axis in prop::array::uniform3(-1.0f64..1.0),
        c in prop::array::uniform3(-3.0f64..3.0),
        tau in -2.0f64..2.0,
        which in 0usize..5,
    ) {
        let n = Vec3::from_array(axis);
        prop_assume!(n.norm() > 0.1);
        let n = n.normalize().unwrap();
        let theta = [std::f64::consts::PI, 1.0e-2 + 1e-9, 0.3, 2.0, 3.1][which];
        let c = Vec3::from_array(c);
        let r = Quat::from_axis_angle(n, theta).unwrap();
        // x ↦ R (x − c) + c + τ n.
        let t = c - r.rotate(c) + n * tau;
        let m = DualQuat::from_rotation_translation(r, t).to_matrix4();
        // The twist, its ω on the side of `near` at θ = π only: there the axis's sign is
        // either, ω and −ω both turning by π (the slide stays τ n); below π it is θ n.
        let half_turn = which == 0;
        let want = |near: Vec3<f64>| {
            let w = n * theta * if half_turn && near.dot(n) < 0.0 { -1.0 } else { 1.0 };
            (w, c.cross(w) + n * tau)
        };
        let got = log_rigid(&m).unwrap();
        let (w, v) = want(got.w);
        prop_assert!((got.w - w).norm() < 1e-12 && (got.v - v).norm() < 1e-11, "{got:?} against {w:?} {v:?}");
        let m32 = DualQuat::from_rotation_translation(r, t).cast::<f32>().to_matrix4();
        let got32 = log_rigid(&m32).unwrap();
        let (w32, v32) = (got32.w.cast::<f64>(), got32.v.cast::<f64>());
        let scale = 1.0 + v.norm();
        // f32 at θ = π: the axis's sign again, and rounding through the half-turn.
        let (w, v) = want(w32);
        prop_assert!((w32 - w).norm() < 1e-5 && (v32 - v).norm() < 2e-5 * scale, "{got32:?} against {w:?} {v:?}");
    }

    #[test]
    fn rigid_log_and_exp_are_inverse(q in prop::array::uniform4(-1.0f64..1.0), t in prop::array::uniform3(-5.0f64..5.0), small in 0usize..4) {
        let q = Quat::from_array(q);
        prop_assume!(q.norm() > 0.1);
        // Also near the identity and near the half turn, where the series take over.
        let q = match small {
            0 => q.normalize().unwrap(),
            1 => Quat::from_rotation_vector(q.vector() * 1e-7).unwrap(),
            2 => Quat::from_axis_angle(q.vector(), std::f64::consts::PI - 1e-9).unwrap_or(Quat::identity()),
            _ => Quat::identity(),
        };
        let m = DualQuat::from_rotation_translation(q, Vec3::from_array(t)).to_matrix4();
        let back = exp_twist(&log_rigid(&m).unwrap());
        prop_assert!(back.max_abs_diff(&m) < 1e-12, "{}", back.max_abs_diff(&m));
    }

    #[test]
    fn matrix_and_dual_quaternion_inputs_agree(seed in 0u64..1000) {
        let mut r = rng(seed);
        let x: Vec<DualQuat<f64>> = (0..4).map(|_| common::random_rigid(&mut r)).collect();
        let m: Vec<Mat4<f64>> = x.iter().map(|d| d.to_matrix4()).collect();
        let w = [0.1, 0.2, 0.3, 0.4];
        for method in Method::ALL.into_iter().filter(|m| *m != Method::ScLerp) {
            let a = blend_dual_quats(method, &x, &w, &Options::default()).unwrap();
            let b = blend_matrices(method, &m, &w, &Options::default()).unwrap();
            prop_assert!(a.matrix.max_abs_diff(&b.matrix) < 1e-9, "{:?}", method);
            prop_assert_eq!(a.iterations, b.iterations);
            prop_assert_eq!(method.iterates(), a.iterations.is_some());
        }
    }
}

#[test]
fn sclerp_is_defined_at_the_half_turn_and_exact_at_the_ends() {
    let p = rigid([1.0, 2.0, 3.0], 0.4, [1.0, 0.0, -1.0]);
    // q is p followed by a half turn about some axis with a slide: p* q has w0 = 0.
    let q = p * rigid([0.0, 1.0, 0.0], std::f64::consts::PI, [0.5, 2.0, 0.0]);
    for t in [0.0, 0.25, 0.5, 1.0] {
        let s = sclerp(p, q, t).unwrap();
        assert!(s.is_finite() && s.is_unit(1e-12));
    }
    assert!(
        sclerp(p, q, 0.0)
            .unwrap()
            .to_matrix4()
            .max_abs_diff(&p.to_matrix4())
            < 1e-14
    );
    assert!(
        sclerp(p, q, 1.0)
            .unwrap()
            .to_matrix4()
            .max_abs_diff(&q.to_matrix4())
            < 1e-14
    );
    // Through blend_*: exactly two transforms.
    let e = blend_dual_quats(
        Method::ScLerp,
        &[p, q, p],
        &[1.0, 1.0, 1.0],
        &Options::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("exactly two"));
}

#[test]
fn dlb_handles_antipodal_inputs_and_lin_is_not_rigid() {
    let q = rigid([0.0, 1.0, 0.0], 1.0, [1.0, 2.0, 3.0]);
    // q and −q are the same transformation: DLB must not cancel them.
    let b = dlb(&[q, -q], &[0.5, 0.5]).unwrap();
    assert!(b.to_matrix4().max_abs_diff(&q.to_matrix4()) < 1e-14);
    let (d, it) = dib(&[q, -q, q], &[0.2, 0.5, 0.3], 1e-12, 10).unwrap();
    assert!(d.to_matrix4().max_abs_diff(&q.to_matrix4()) < 1e-12 && it <= 1);
    // Lin of two rotations 120° apart shrinks: not rigid, reported as such.
    let a = rigid([0.0, 0.0, 1.0], 0.0, [0.0; 3]);
    let c = rigid([0.0, 0.0, 1.0], 2.0 * std::f64::consts::FRAC_PI_3, [0.0; 3]);
    let l = blend_dual_quats(Method::Lin, &[a, c], &[0.5, 0.5], &Options::default()).unwrap();
    assert!(!l.rigid);
    assert!(
        (l.matrix.linear_part().determinant() - 0.25).abs() < 1e-12,
        "det {}",
        l.matrix.linear_part().determinant()
    );
    assert!(l.dq.is_unit(1e-12), "its rotation part is still a rotation");
}

#[test]
fn dec_depends_on_its_centre() {
    let a = rigid([0.0, 0.0, 1.0], 0.0, [0.0; 3]);
    let b = rigid([0.0, 0.0, 1.0], std::f64::consts::FRAC_PI_2, [0.0; 3]);
    let at = |c: Vec3<f64>| {
        let opt = Options {
            center: c,
            ..Options::default()
        };
        blend_dual_quats(Method::Dec, &[a, b], &[0.3, 0.7], &opt).unwrap()
    };
    let o = at(Vec3::zero());
    let off = at(Vec3::new(1.0, 0.0, 0.0));
    assert!(
        (o.dq.translation()).norm() < 1e-12,
        "about the origin, pure rotations blend to a rotation"
    );
    assert!(
        off.dq.translation().norm() > 0.1,
        "about another centre the result moves"
    );
    // Both have the same rotation: 0.7 × 90° about z (the spherical average of two is Slerp).
    let half =
        Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 0.7 * std::f64::consts::FRAC_PI_2).unwrap();
    assert!((o.dq.real - half).norm() < 1e-12 && (off.dq.real - half).norm() < 1e-12);
    assert_eq!(o.iterations, Some(1));
}

#[test]
fn blends_in_f32_match_f64() {
    let mut r = rng(21);
    for _ in 0..100 {
        let x: Vec<DualQuat<f64>> = (0..4).map(|_| common::random_rigid(&mut r)).collect();
        let x32: Vec<DualQuat<f32>> = x.iter().map(|d| d.cast()).collect();
        let w = [0.1, 0.2, 0.3, 0.4];
        let w32 = [0.1f32, 0.2, 0.3, 0.4];
        for m in [
            Method::Dlb,
            Method::Dib,
            Method::Qlb,
            Method::Lin,
            Method::Log,
        ] {
            let a = blend_dual_quats(m, &x, &w, &Options::default())
                .unwrap()
                .matrix;
            let b = blend_dual_quats(m, &x32, &w32, &Options::default())
                .unwrap()
                .matrix;
            let d = Mat4::from_rows(b.m.map(|row| row.map(f64::from))).max_abs_diff(&a);
            assert!(d < 1e-4, "{m:?}: f32 differs by {d}");
        }
    }
}

fn sclerp_closed_form_matches_definition<T: chasles::Real>(
    p: DualQuat<T>,
    q: DualQuat<T>,
    tol: f64,
) {
    use chasles::blend::sclerp::sclerp_pow;
    for k in 0..=10 {
        let t = T::from_f64(k as f64 / 10.0);
        let a = sclerp(p, q, t).unwrap().to_matrix4();
        let b = sclerp_pow(p, q, t).unwrap().to_matrix4();
        let d = a.max_abs_diff(&b).to_f64();
        assert!(d < tol, "t = {t}: {d:e}");
    }
}

proptest! {
    #[test]
    fn sclerp_closed_form_equals_the_power_definition(seed in 0u64..10_000, scale in prop::sample::select(vec![1.0, 1e-2, 1e-4, 1e-7, 0.0])) {
        // Random pairs, and pairs whose relative rotation is tiny or zero (pure translation).
        let mut r = rng(seed);
        let p = common::random_rigid(&mut r);
        let rel = common::random_rigid(&mut r);
        let small = DualQuat::from_rotation_translation(
            Quat::from_rotation_vector(rel.real.vector() * scale).unwrap(),
            rel.translation(),
        );
        let q = if scale == 1.0 { rel } else { p * small };
        sclerp_closed_form_matches_definition(p, q, 1e-12);
        sclerp_closed_form_matches_definition(p.cast::<f32>(), q.cast::<f32>(), 2e-5);
    }

    /// q̂ and −q̂ are one rigid motion, and ScLERP takes the shorter screw from either:
    /// the same numbers bit for bit (the sign is folded into q̂'s weights with no branch),
    /// for every t — inside [0, 1], at its ends, and extrapolating — in f64 and f32.
    #[test]
    fn sclerp_of_q_and_minus_q_agree_bit_for_bit(seed in 0u64..10_000, t in prop::sample::select(vec![0.0, 0.25, 0.5, 0.999, 1.0, -0.5, 1.5])) {
        let mut r = rng(seed);
        let (p, q) = (common::random_rigid(&mut r), common::random_rigid(&mut r));
        let t = if t == 0.25 { r.random_range(0.0..1.0) } else { t };
        let bits = |d: DualQuat<f64>| d.to_array().map(f64::to_bits);
        prop_assert_eq!(bits(sclerp(p, q, t).unwrap()), bits(sclerp(p, -q, t).unwrap()));
        let (p, q) = (p.cast::<f32>(), q.cast::<f32>());
        let bits = |d: DualQuat<f32>| d.to_array().map(f32::to_bits);
        prop_assert_eq!(bits(sclerp(p, q, t as f32).unwrap()), bits(sclerp(p, -q, t as f32).unwrap()));
    }
}
