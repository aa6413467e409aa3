//! Round trips through glam, nalgebra and mint are exact (`==`): the conversions map
//! components by name (glam and nalgebra store x, y, z, w; we store w, x, y, z) and do no
//! arithmetic. Run with `cargo test -p chasles --all-features` (`.ci/run` does).
#![cfg(all(feature = "glam", feature = "nalgebra", feature = "mint"))]

mod common;
use chasles::{DualQuat, EulerOrder, Mat3, Mat4, Quat, Vec3};
use common::*;
use proptest::prelude::*;

proptest! {
    #[test]
    fn glam_round_trips_are_exact(q in unit_quat(), v in any_vec(), r in unit_dq()) {
        let q64 = quat_of::<f64>(q);
        let g: glam::DQuat = q64.into();
        // Same rotation, glam's memory order x, y, z, w.
        prop_assert_eq!(g.to_array(), [q64.x, q64.y, q64.z, q64.w]);
        prop_assert_eq!(Quat::from(g), q64);
        let q32 = quat_of::<f32>(q);
        prop_assert_eq!(Quat::from(glam::Quat::from(q32)), q32);
        let v64 = vec_of::<f64>(v);
        prop_assert_eq!(Vec3::from(glam::DVec3::from(v64)), v64);
        let v32 = vec_of::<f32>(v);
        prop_assert_eq!(Vec3::from(glam::Vec3::from(v32)), v32);
        let m = q64.to_rotation_matrix();
        prop_assert_eq!(Mat3::from(glam::DMat3::from(m)), m);
        let m4 = dq_of::<f64>(r).to_matrix4();
        prop_assert_eq!(Mat4::from(glam::DMat4::from(m4)), m4);
        let m4f = dq_of::<f32>(r).to_matrix4();
        prop_assert_eq!(Mat4::from(glam::Mat4::from(m4f)), m4f);
        // Same meaning: glam rotates a vector as we do, and its matrix is ours.
        let p = glam::DVec3::from(v64);
        let ours = q64.rotate(v64);
        let theirs = g * p;
        prop_assert!((ours - Vec3::from(theirs)).norm() < 1e-12);
        // glam builds the matrix in another order of operations: equal to rounding, a few
        // ulps of entries of size ≤ 1 (1e-15 was once exceeded by a proptest draw).
        let gm = glam::DMat3::from_quat(g);
        prop_assert!(Mat3::from(gm).max_abs_diff(&m) < 16.0 * f64::EPSILON);
        let t = glam::DMat4::from(m4).transform_point3(p);
        prop_assert!((Vec3::from(t) - m4.transform_point(v64)).norm() < 1e-12);
    }

    #[test]
    fn nalgebra_round_trips_are_exact(q in unit_quat(), v in any_vec(), r in unit_dq()) {
        let q64 = quat_of::<f64>(q);
        let nq: nalgebra::Quaternion<f64> = q64.into();
        prop_assert_eq!(nq.coords.as_slice(), &[q64.x, q64.y, q64.z, q64.w][..]);
        prop_assert_eq!(Quat::from(nq), q64);
        let u: nalgebra::UnitQuaternion<f64> = q64.try_into().unwrap();
        prop_assert_eq!(Quat::from(u), q64);
        let u32: nalgebra::UnitQuaternion<f32> = quat_of::<f32>(q).try_into().unwrap();
        prop_assert_eq!(Quat::from(u32), quat_of::<f32>(q));
        let dq = dq_of::<f64>(r);
        let nd: nalgebra::UnitDualQuaternion<f64> = dq.try_into().unwrap();
        prop_assert_eq!(DualQuat::from(nd), dq);
        let v64 = vec_of::<f64>(v);
        prop_assert_eq!(Vec3::from(nalgebra::Vector3::from(v64)), v64);
        let m = q64.to_rotation_matrix();
        prop_assert_eq!(Mat3::from(nalgebra::Matrix3::from(m)), m);
        let m4 = dq.to_matrix4();
        prop_assert_eq!(Mat4::from(nalgebra::Matrix4::from(m4)), m4);
        // Same meaning: rotation, rigid transform and Isometry3.
        let p = nalgebra::Point3::new(v64.x, v64.y, v64.z);
        prop_assert!((Vec3::from(u * nalgebra::Vector3::from(v64)) - q64.rotate(v64)).norm() < 1e-12);
        let moved = nd.transform_point(&p);
        prop_assert!((Vec3::new(moved.x, moved.y, moved.z) - dq.transform_point(v64)).norm() < 1e-12);
        let iso: nalgebra::Isometry3<f64> = dq.try_into().unwrap();
        let back = DualQuat::from(iso);
        prop_assert!((back.transform_point(v64) - dq.transform_point(v64)).norm() < 1e-12);
        prop_assert!(Mat4::from(iso.to_homogeneous()).max_abs_diff(&m4) < 1e-12);
    }

    #[test]
    fn mint_round_trips_are_exact(q in unit_quat(), r in unit_dq()) {
        let q64 = quat_of::<f64>(q);
        let mq: mint::Quaternion<f64> = q64.into();
        prop_assert_eq!(mq.s, q64.w);
        prop_assert_eq!(Quat::from(mq), q64);
        let m = q64.to_rotation_matrix();
        let rows: mint::RowMatrix3<f64> = m.into();
        prop_assert_eq!(rows.x.y, m.m[0][1]);
        prop_assert_eq!(Mat3::from(rows), m);
        let cols: mint::ColumnMatrix3<f64> = m.into();
        prop_assert_eq!(cols.y.x, m.m[0][1]);
        prop_assert_eq!(Mat3::from(cols), m);
        let m4 = dq_of::<f32>(r).to_matrix4();
        prop_assert_eq!(Mat4::from(mint::RowMatrix4::from(m4)), m4);
        prop_assert_eq!(Mat4::from(mint::ColumnMatrix4::from(m4)), m4);
    }
}

#[test]
fn non_unit_values_are_refused_by_the_unit_types() {
    let q = Quat::<f64>::new(2.0, 0.0, 0.0, 0.0);
    let r: Result<nalgebra::UnitQuaternion<f64>, _> = q.try_into();
    assert!(matches!(r, Err(chasles::Error::NotUnitQuat { norm }) if norm == 2.0));
    let dq = DualQuat::new(Quat::<f64>::identity(), Quat::new(1.0, 0.0, 0.0, 0.0));
    let r: Result<nalgebra::UnitDualQuaternion<f64>, _> = dq.try_into();
    assert!(matches!(r, Err(chasles::Error::NotUnit { .. })));
    let r: Result<nalgebra::Isometry3<f64>, _> = dq.try_into();
    assert!(r.is_err());
    // Euler angles agree with glam's extrinsic/intrinsic conventions: glam's EulerRot::XYZ
    // is intrinsic X then Y then Z, our "XYZ".
    let g = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.1, 0.2, 0.3);
    let ours = Quat::from_euler("XYZ".parse::<EulerOrder>().unwrap(), [0.1, 0.2, 0.3]);
    assert!((Quat::from(g) - ours).norm() < 1e-15);
}

#[test]
fn f32_slerp_is_as_accurate_as_glams() {
    // Against an f64 reference on the same (rounded) inputs, over random same-hemisphere
    // pairs and parameters: the worst error of our f32 Slerp is no larger than glam's.
    use chasles::interp::slerp::{slerp, slerp_trig};
    let mut seed = 12345u64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let (mut ours, mut theirs) = (0.0f64, 0.0f64);
    for i in 0..20000 {
        let p = Quat::new(rnd() as f32, rnd() as f32, rnd() as f32, rnd() as f32)
            .normalize()
            .unwrap();
        let mut q = Quat::new(rnd() as f32, rnd() as f32, rnd() as f32, rnd() as f32);
        if i % 4 == 0 {
            // Nearby keys, as in a dense animation.
            q = p + q * 1e-3;
        }
        let mut q = q.normalize().unwrap();
        if p.dot(q) < 0.0 {
            q = -q;
        }
        let h = (rnd() * 0.5 + 0.5) as f32;
        let reference = slerp_trig(p.cast::<f64>(), q.cast::<f64>(), h as f64);
        let a = slerp(p, q, h).cast::<f64>();
        let g: glam::Quat = glam::Quat::from(p).slerp(glam::Quat::from(q), h);
        let b = Quat::from(g).cast::<f64>();
        ours = ours.max((a - reference).norm());
        theirs = theirs.max((b - reference).norm());
    }
    assert!(
        ours <= theirs.max(4e-7),
        "chasles f32 slerp error {ours:e} vs glam {theirs:e}"
    );
    assert!(ours < 1e-6, "{ours:e}");
}

#[test]
fn sclerp_against_nalgebra_accuracy_and_the_half_turn() {
    // Reference: the definition p̂ (p̂* q̂)^t. Relative screws from 1 rad down to 1e-6 rad.
    use chasles::blend::sclerp::{sclerp, sclerp_pow};
    let p = DualQuat::from_rotation_translation(
        Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0), 0.7).unwrap(),
        Vec3::new(0.3, -1.0, 2.0),
    );
    let (mut ours, mut theirs) = (0.0f64, 0.0f64);
    for k in 0..7 {
        let angle = 10f64.powi(-k);
        let rel = DualQuat::from_rotation_translation(
            Quat::from_axis_angle(Vec3::new(0.0, 1.0, 1.0), angle).unwrap(),
            Vec3::new(1.0, 0.5, 0.0),
        );
        let q = p * rel;
        let reference = sclerp_pow(p, q, 0.3).unwrap().to_matrix4();
        ours = ours.max(
            sclerp(p, q, 0.3)
                .unwrap()
                .to_matrix4()
                .max_abs_diff(&reference),
        );
        let np: nalgebra::UnitDualQuaternion<f64> = p.try_into().unwrap();
        let nq: nalgebra::UnitDualQuaternion<f64> = q.try_into().unwrap();
        let n = DualQuat::from(np.sclerp(&nq, 0.3));
        theirs = theirs.max(n.to_matrix4().max_abs_diff(&reference));
    }
    assert!(ours < 1e-13, "ours {ours:e}");
    assert!(theirs > ours, "nalgebra {theirs:e} vs ours {ours:e}");
    // A half turn between the inputs: nalgebra's try_sclerp gives up, ours is defined.
    let q = p * DualQuat::from_rotation(Quat::from_axis_index(0, std::f64::consts::PI));
    let np: nalgebra::UnitDualQuaternion<f64> = p.try_into().unwrap();
    let nq: nalgebra::UnitDualQuaternion<f64> = q.try_into().unwrap();
    assert!(np.try_sclerp(&nq, 0.5, 1e-9).is_none());
    assert!(sclerp(p, q, 0.5).unwrap().is_unit(1e-12));
    println!("sclerp max error vs definition, 1 rad … 1e-6 rad: chasles {ours:.1e}, nalgebra {theirs:.1e}");
}

proptest! {
    #[test]
    fn the_methods_go_the_shorter_way_as_glam_and_nalgebra(
        p in unit_quat(), q in unit_quat(), r in unit_dq(), s in unit_dq(), t in 0.0f64..=1.0
    ) {
        use chasles::blend::sclerp::sclerp;
        use chasles::interp::slerp::slerp_shortest;
        // Quat::slerp is slerp_shortest, bit for bit, in f32 and f64; and a pair on opposite
        // hemispheres (half of these) goes as glam's and nalgebra's slerp go.
        let (p32, q32) = (quat_of::<f32>(p), quat_of::<f32>(q));
        prop_assert_eq!(p32.slerp(q32, t as f32), slerp_shortest(p32, q32, t as f32));
        let g = Quat::from(glam::Quat::from(p32).slerp(glam::Quat::from(q32), t as f32));
        prop_assert!((p32.slerp(q32, t as f32) - g).norm() < 2e-6, "glam {:?}", g);
        let (p64, q64) = (quat_of::<f64>(p), quat_of::<f64>(q));
        prop_assert_eq!(p64.slerp(q64, t), slerp_shortest(p64, q64, t));
        // The shorter rotation: −q gives the same blend.
        prop_assert!((p64.slerp(-q64, t) - p64.slerp(q64, t)).norm() < 1e-15);
        let np: nalgebra::UnitQuaternion<f64> = p64.try_into().unwrap();
        let nq: nalgebra::UnitQuaternion<f64> = q64.try_into().unwrap();
        if let Some(n) = np.try_slerp(&nq, t, 1e-9) {
            let n = Quat::from(n);
            prop_assert!((p64.slerp(q64, t) - n).norm() < 1e-12, "nalgebra {:?}", n);
        }
        // DualQuat::sclerp is sclerp, and as nalgebra's sclerp away from a half turn.
        let (a, b) = (dq_of::<f64>(r), dq_of::<f64>(s));
        prop_assert_eq!(a.sclerp(b, t).unwrap(), sclerp(a, b, t).unwrap());
        if a.real.dot(b.real).abs() > 1e-3 {
            let na: nalgebra::UnitDualQuaternion<f64> = a.try_into().unwrap();
            let nb: nalgebra::UnitDualQuaternion<f64> = b.try_into().unwrap();
            let n = DualQuat::from(na.sclerp(&nb, t));
            prop_assert!(
                a.sclerp(b, t).unwrap().to_matrix4().max_abs_diff(&n.to_matrix4()) < 1e-9,
                "nalgebra {:?}", n
            );
        }
    }
}
