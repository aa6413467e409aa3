//! Conversions (Dam et al. 1998, App. B): matrix ↔ quaternion ↔ Euler angles in all 12
//! sequences, extrinsic and intrinsic, including 180° rotations and gimbal lock. Tolerances
//! from `common::Tol` (1e-12 f64, 1e-5 f32, relative).

mod common;
use chasles::{Error, EulerOrder, Mat3, Mat4, Quat, Real, Vec3};
use common::*;
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

fn orders() -> impl Strategy<Value = EulerOrder> {
    prop::sample::select(EulerOrder::all())
}

fn matrix_quat_round_trip<T: Tol>((q,): ([f64; 4],), tol: f64) -> Result<(), TestCaseError> {
    let q = quat_of::<T>(q);
    let m = q.to_rotation_matrix();
    prop_assert!(m.rotation_deviation().to_f64() < tol * 10.0);
    let back = Quat::from_rotation_matrix(&m).unwrap();
    prop_assert!(back.w >= T::ZERO);
    close_rot(back, q, tol)
}
both_precisions!(
    matrix_to_quaternion_round_trip,
    matrix_quat_round_trip,
    unit_quat()
);

fn half_turn_round_trip<T: Tol>((axis,): ([f64; 3],), tol: f64) -> Result<(), TestCaseError> {
    let axis = vec_of::<T>(axis);
    prop_assume!(axis.norm().to_f64() > 0.1);
    // Exactly 180° and just below: Shepperd's method stays exact.
    for angle in [PI, PI - 1e-9, PI - 1e-4] {
        let q = Quat::from_axis_angle(axis, T::from_f64(angle)).unwrap();
        let back = Quat::from_rotation_matrix(&q.to_rotation_matrix()).unwrap();
        close_rot(back, q, tol)?;
    }
    Ok(())
}
both_precisions!(half_turns_convert_exactly, half_turn_round_trip, any_vec());

fn euler_round_trip<T: Tol>(
    (order, a, b, c): (EulerOrder, f64, f64, f64),
    tol: f64,
) -> Result<(), TestCaseError> {
    // Angles in the canonical ranges come back unchanged; any angles give the same rotation.
    let mid = if order.is_proper_euler() {
        (b.abs() * 0.999).max(0.01)
    } else {
        b * 0.499
    };
    let angles = [T::from_f64(a), T::from_f64(mid), T::from_f64(c)];
    let q = Quat::from_euler(order, angles);
    let e = q.to_euler(order).unwrap();
    prop_assert!(!e.gimbal_lock);
    close(&e.angles, &angles, tol * 10.0)?;
    // Via the matrix too (B.5: "go via matrices").
    let m = Mat3::from_euler(order, angles);
    let e2 = m.to_euler(order).unwrap();
    close(
        &Mat3::from_euler(order, e2.angles).to_row_major(),
        &m.to_row_major(),
        tol,
    )?;
    close_rot(Quat::from_rotation_matrix(&m).unwrap(), q, tol)
}
both_precisions!(
    euler_round_trip_all_24_conventions,
    euler_round_trip,
    orders(),
    -3.1f64..3.1,
    -3.1f64..3.1,
    -3.1f64..3.1
);

fn euler_any_rotation<T: Tol>(
    (order, q): (EulerOrder, [f64; 4]),
    tol: f64,
) -> Result<(), TestCaseError> {
    let q = quat_of::<T>(q);
    let e = q.to_euler(order).unwrap();
    close_rot(Quat::from_euler(order, e.angles), q, tol * 4.0)
}
both_precisions!(
    every_rotation_has_euler_angles_in_every_convention,
    euler_any_rotation,
    orders(),
    unit_quat()
);

fn gimbal_lock<T: Tol>(
    (order, a, c, up): (EulerOrder, f64, f64, bool),
    tol: f64,
) -> Result<(), TestCaseError> {
    // The middle angle at its singular value: ±π/2 (Tait–Bryan) or 0/π (proper Euler).
    let mid = match (order.is_proper_euler(), up) {
        (false, true) => FRAC_PI_2,
        (false, false) => -FRAC_PI_2,
        (true, true) => PI,
        (true, false) => 0.0,
    };
    let angles = [T::from_f64(a), T::from_f64(mid), T::from_f64(c)];
    let m = Mat3::from_euler(order, angles);
    let e = m.to_euler(order).unwrap();
    prop_assert!(e.gimbal_lock, "{order}: {:?}", e);
    // Dam et al. B.2: the third angle is defined to be 0.
    prop_assert_eq!(e.angles[2], T::ZERO);
    close(&[e.angles[1]], &[T::from_f64(mid)], tol * 10.0)?;
    close(
        &Mat3::from_euler(order, e.angles).to_row_major(),
        &m.to_row_major(),
        tol * 4.0,
    )
}
both_precisions!(
    gimbal_lock_sets_third_angle_to_zero,
    gimbal_lock,
    orders(),
    -3.1f64..3.1,
    -3.1f64..3.1,
    any::<bool>()
);

fn matrix4_round_trip<T: Tol>((r,): (Rigid,), tol: f64) -> Result<(), TestCaseError> {
    let q = quat_of::<T>(r.0);
    let m4 = q.to_matrix4();
    close(
        &m4.linear_part().to_row_major(),
        &q.to_rotation_matrix().to_row_major(),
        0.0,
    )?;
    close(&m4.translation().to_array(), &[T::ZERO; 3], 0.0)?;
    close(&m4.m[3], &[T::ZERO, T::ZERO, T::ZERO, T::ONE], 0.0)?;
    let _ = tol;
    Ok(())
}
both_precisions!(homogeneous_rotation_matrix, matrix4_round_trip, unit_dq());

fn axis_angle_round_trip<T: Tol>(
    (axis, angle): ([f64; 3], f64),
    tol: f64,
) -> Result<(), TestCaseError> {
    let axis = vec_of::<T>(axis);
    prop_assume!(axis.norm().to_f64() > 0.1);
    let angle = T::from_f64(angle);
    let q = Quat::from_axis_angle(axis, angle).unwrap();
    let (a2, ang2) = q.to_axis_angle().unwrap();
    close(&[ang2], &[angle], tol * 4.0)?;
    close(
        &a2.to_array(),
        &axis.normalize().unwrap().to_array(),
        tol * 10.0,
    )
}
both_precisions!(
    axis_angle_round_trip_over_0_to_2pi,
    axis_angle_round_trip,
    any_vec(),
    0.01f64..6.27
);

#[test]
fn dam_b1_closed_form() {
    // App. B.1: R(α, β, γ) = Rz(γ) Ry(β) Rx(α), entry by entry.
    let (a, b, g) = (0.3f64, -0.7, 1.9);
    let (ca, sa, cb, sb, cg, sg) = (a.cos(), a.sin(), b.cos(), b.sin(), g.cos(), g.sin());
    let want = [
        [cb * cg, cg * sa * sb - ca * sg, ca * cg * sb + sa * sg],
        [cb * sg, ca * cg + sa * sb * sg, -(cg * sa) + ca * sb * sg],
        [-sb, cb * sa, ca * cb],
    ];
    let got = Mat3::from_euler(EulerOrder::DAM, [a, b, g]);
    let err = got.max_abs_diff(&Mat3::from_rows(want));
    assert!(err < 1e-15, "error {err}");
    assert_eq!("xyz".parse::<EulerOrder>().unwrap(), EulerOrder::DAM);
}

#[test]
fn dam_b2_gimbal_lock_formula() {
    // App. B.2 at β = π/2: γ ≡ 0, cos α = R22, sin α = −R23 (1-based indices).
    let m = Mat3::from_euler(EulerOrder::DAM, [0.4f64, FRAC_PI_2, -1.1]);
    let e = m.to_euler(EulerOrder::DAM).unwrap();
    assert!(e.gimbal_lock);
    assert_eq!(e.angles[2], 0.0);
    let alpha = (-m.m[1][2]).atan2(m.m[1][1]);
    assert!(
        (e.angles[0] - alpha).abs() < 1e-12,
        "{:?} vs {alpha}",
        e.angles
    );
    // Here α − γ is what is determined: 0.4 − (−1.1) = 1.5.
    assert!((e.angles[0] - 1.5).abs() < 1e-12);
}

#[test]
fn intrinsic_is_extrinsic_reversed() {
    let angles = [0.3f64, 0.5, -0.8];
    let intrinsic = Quat::from_euler("XYZ".parse().unwrap(), angles);
    let extrinsic = Quat::from_euler("zyx".parse().unwrap(), [angles[2], angles[1], angles[0]]);
    assert!((intrinsic - extrinsic).norm() < 1e-15);
    // R = Rx(α) Ry(β) Rz(γ) for intrinsic XYZ.
    let r = |axis, a| {
        Mat3::from_euler(EulerOrder::DAM, {
            let mut v = [0.0; 3];
            v[axis] = a;
            v
        })
    };
    let want = r(0, angles[0]) * r(1, angles[1]) * r(2, angles[2]);
    let got = Mat3::from_euler("XYZ".parse().unwrap(), angles);
    assert!(got.max_abs_diff(&want) < 1e-15);
    assert!(EulerOrder::new([0, 0, 1], false).is_err());
}

#[test]
fn trace_only_formula_fails_near_half_turn_and_shepperd_does_not() {
    // The numerical trap of Dam et al. App. B.4: it divides by 4s with s → 0 at 180°.
    let axis = Vec3::new(1.0f64, 2.0, 3.0);
    let q = Quat::from_axis_angle(axis, PI - 1e-7).unwrap();
    let m = q.to_rotation_matrix();
    let shepperd = Quat::from_rotation_matrix(&m).unwrap();
    let trace = Quat::from_rotation_matrix_trace_only(&m);
    let err_s = (shepperd - q).norm().min((shepperd + q).norm());
    let err_t = (trace - q).norm().min((trace + q).norm());
    assert!(err_s < 1e-15, "Shepperd error {err_s}");
    assert!(err_t > 1e-3, "trace-only error only {err_t}");
    // At exactly 180° about x the trace formula divides 0 by 0.
    let m = Quat::<f64>::from_axis_index(0, PI).to_rotation_matrix();
    assert!(!Quat::from_rotation_matrix_trace_only(&m).is_finite());
    let q = Quat::from_rotation_matrix(&m).unwrap();
    assert!((q.x.abs() - 1.0).abs() < 1e-15);
}

#[test]
fn bad_matrices_and_orders_get_typed_errors() {
    let mut m = Mat3::<f64>::identity();
    m.m[0][0] = f64::NAN;
    assert!(matches!(
        Quat::from_rotation_matrix(&m),
        Err(Error::NonFinite { .. })
    ));
    let reflection = Mat3::from_rows([[-1.0f64, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    let e = Quat::from_rotation_matrix(&reflection).unwrap_err();
    assert!(e.to_string().contains("reflection"), "{e}");
    let sheared = Mat3::from_rows([[1.0f64, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    assert!(matches!(
        Quat::from_rotation_matrix(&sheared),
        Err(Error::NotRotation { .. })
    ));
    assert!(matches!(
        sheared.to_euler(EulerOrder::DAM),
        Err(Error::NotRotation { .. })
    ));
    for bad in ["xxy", "xyzz", "xYz", "abc", "", "zzz"] {
        assert!(
            matches!(bad.parse::<EulerOrder>(), Err(Error::UnknownEulerOrder(_))),
            "{bad}"
        );
    }
    assert_eq!(EulerOrder::all().len(), 24);
    let names: Vec<String> = EulerOrder::all().iter().map(|o| o.to_string()).collect();
    assert!(names.contains(&"zyz".to_string()) && names.contains(&"ZXY".to_string()));
    let m4 = Mat4::<f32>::identity();
    assert_eq!(m4.linear_part(), Mat3::identity());
}
