//! Quaternion algebra (Dam et al. 1998, §3.3): identities checked on random inputs in f32
//! and f64, with the tolerances of `common::Tol` (1e-12 f64, 1e-5 f32, relative).

mod common;
use chasles::{Error, Quat, Vec3};
use common::*;
use proptest::prelude::*;

fn norm_multiplicative<T: Tol>(
    (p, q): ([f64; 4], [f64; 4]),
    tol: f64,
) -> Result<(), TestCaseError> {
    let (p, q) = (quat_of::<T>(p), quat_of::<T>(q));
    close(&[(p * q).norm()], &[p.norm() * q.norm()], tol)
}
both_precisions!(
    norm_of_product_is_product_of_norms,
    norm_multiplicative,
    any_quat(),
    any_quat()
);

fn conj_of_product<T: Tol>((p, q): ([f64; 4], [f64; 4]), tol: f64) -> Result<(), TestCaseError> {
    let (p, q) = (quat_of::<T>(p), quat_of::<T>(q));
    close(
        &(p * q).conjugate().to_array(),
        &(q.conjugate() * p.conjugate()).to_array(),
        tol,
    )
}
both_precisions!(
    conjugate_of_product_reverses,
    conj_of_product,
    any_quat(),
    any_quat()
);

fn inverse_is_inverse<T: Tol>((q,): ([f64; 4],), tol: f64) -> Result<(), TestCaseError> {
    let q = quat_of::<T>(q);
    let i = q.inverse().unwrap();
    close(&(q * i).to_array(), &Quat::<T>::identity().to_array(), tol)?;
    close(&(i * q).to_array(), &Quat::<T>::identity().to_array(), tol)
}
both_precisions!(inverse_gives_identity, inverse_is_inverse, any_quat());

fn exp_log<T: Tol>((q,): ([f64; 4],), tol: f64) -> Result<(), TestCaseError> {
    let q = quat_of::<T>(q);
    let l = q.log().unwrap();
    prop_assert!(l.vector().norm().to_f64() <= std::f64::consts::PI * (1.0 + tol));
    close(&l.exp().to_array(), &q.to_array(), tol)
}
both_precisions!(
    exp_of_log_is_identity_for_any_quaternion,
    exp_log,
    any_quat()
);

fn log_of_power<T: Tol>((q, t): ([f64; 4], f64), tol: f64) -> Result<(), TestCaseError> {
    let q = quat_of::<T>(q);
    let t = T::from_f64(t);
    let lhs = q.powf(t).unwrap().log().unwrap();
    close(&lhs.to_array(), &(q.log().unwrap() * t).to_array(), tol)
}
// |t| < 1 keeps t·log q on the principal branch (Proposition 15 needs that).
both_precisions!(
    log_of_power_is_scaled_log,
    log_of_power,
    any_quat(),
    -0.99f64..0.99
);

fn power_adds<T: Tol>((q, a, b): ([f64; 4], f64, f64), tol: f64) -> Result<(), TestCaseError> {
    let q = quat_of::<T>(q).normalize().unwrap();
    let (a, b) = (T::from_f64(a), T::from_f64(b));
    let lhs = q.powf(a).unwrap() * q.powf(b).unwrap();
    close(
        &lhs.to_array(),
        &q.powf(a + b).unwrap().to_array(),
        tol * 4.0,
    )
}
both_precisions!(
    powers_add_exponents,
    power_adds,
    any_quat(),
    -2.0f64..2.0,
    -2.0f64..2.0
);

fn rotate_matches_matrix<T: Tol>(
    (q, v): ([f64; 4], [f64; 3]),
    tol: f64,
) -> Result<(), TestCaseError> {
    let q = quat_of::<T>(q);
    let v = vec_of::<T>(v);
    let by_matrix = q.to_rotation_matrix().mul_vec(v);
    let by_sandwich = q.sandwich(v).unwrap();
    let by_product = (q * Quat::pure(v) * q.inverse().unwrap()).vector();
    close(&by_sandwich.to_array(), &by_matrix.to_array(), tol)?;
    close(&by_product.to_array(), &by_matrix.to_array(), tol)?;
    // Rotation keeps lengths (Proposition 19).
    close(&[by_sandwich.norm()], &[v.norm()], tol)
}
both_precisions!(
    rotation_by_quaternion_and_by_matrix_agree,
    rotate_matches_matrix,
    any_quat(),
    any_vec()
);

fn angle_between<T: Tol>(
    (q, axis, angle): ([f64; 4], [f64; 3], f64),
    tol: f64,
) -> Result<(), TestCaseError> {
    let axis = vec_of::<T>(axis);
    prop_assume!(axis.norm().to_f64() > 0.1);
    let p = quat_of::<T>(q).normalize().unwrap();
    let r = Quat::from_axis_angle(axis, T::from_f64(angle)).unwrap();
    let got = p.angle_to(p * r).unwrap();
    // q and −q are the same rotation: the angle is the same.
    let got_neg = p.angle_to(-(p * r)).unwrap();
    close(&[got, got_neg], &[T::from_f64(angle.abs()); 2], tol * 10.0)
}
both_precisions!(
    angle_between_rotations_is_the_relative_angle,
    angle_between,
    unit_quat(),
    any_vec(),
    -3.1f64..3.1
);

#[test]
fn hamilton_units() {
    let i = Quat::<f64>::new(0.0, 1.0, 0.0, 0.0);
    let j = Quat::<f64>::new(0.0, 0.0, 1.0, 0.0);
    let k = Quat::<f64>::new(0.0, 0.0, 0.0, 1.0);
    let m1 = Quat::<f64>::new(-1.0, 0.0, 0.0, 0.0);
    assert_eq!(i * i, m1);
    assert_eq!(j * j, m1);
    assert_eq!(k * k, m1);
    assert_eq!(i * j * k, m1);
    assert_eq!(i * j, k);
    assert_eq!(j * i, -k);
}

#[test]
fn rotation_is_counter_clockwise_right_handed() {
    // Dam et al. App. A: rotation about z brings x into y, about y brings z into x, about
    // x brings y into z.
    let h = std::f64::consts::FRAC_PI_2;
    let cases = [(2, 0, 1), (1, 2, 0), (0, 1, 2)];
    for (axis, from, to) in cases {
        let q = Quat::<f64>::from_axis_index(axis, h);
        let r = q.rotate(Vec3::unit(from));
        assert!((r - Vec3::unit(to)).norm() < 1e-15, "axis {axis}: {r:?}");
    }
}

#[test]
fn log_has_the_reports_half_angle_convention() {
    // Definition 14: q = [cos θ, sin θ v] → log q = [0, θ v]; the rotation angle is 2θ.
    let q = Quat::<f64>::from_axis_angle(Vec3::new(0.0, 0.0, 2.0), 1.2).unwrap();
    let l = q.log().unwrap();
    assert!((l.z - 0.6).abs() < 1e-15 && l.w.abs() < 1e-15 && l.x == 0.0 && l.y == 0.0);
    let (axis, angle) = q.to_axis_angle().unwrap();
    assert!((angle - 1.2).abs() < 1e-15 && (axis.z - 1.0).abs() < 1e-15);
    // −q: the same rotation the long way, 2π − angle about the opposite axis.
    let (axis, angle) = (-q).to_axis_angle().unwrap();
    assert!((angle - (2.0 * std::f64::consts::PI - 1.2)).abs() < 1e-14);
    assert!((axis.z + 1.0).abs() < 1e-15);
    // Rotation vector: shortest way, for both signs.
    let r = (-q).to_rotation_vector().unwrap();
    assert!((r.z - 1.2).abs() < 1e-14);
    let back = Quat::from_rotation_vector(r).unwrap();
    assert!((back - q).norm() < 1e-15);
}

#[test]
fn exp_and_log_of_non_unit_quaternions_closed_form() {
    // exp[1, (0, 0, π/2)] = e [0, (0, 0, 1)]
    let e = Quat::<f64>::new(1.0, 0.0, 0.0, std::f64::consts::FRAC_PI_2).exp();
    let want = [0.0, 0.0, 0.0, std::f64::consts::E];
    for (g, w) in e.to_array().iter().zip(want) {
        assert!((g - w).abs() < 1e-15);
    }
    // log[0, (0, 3, 0)] = [ln 3, (0, π/2, 0)]
    let l = Quat::<f64>::new(0.0, 0.0, 3.0, 0.0).log().unwrap();
    assert!((l.w - 3f64.ln()).abs() < 1e-15 && (l.y - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    // log of a negative real: [ln 2, π x̂] (x axis chosen), and exp maps it back.
    let l = Quat::<f64>::new(-2.0, 0.0, 0.0, 0.0).log().unwrap();
    assert!((l.x - std::f64::consts::PI).abs() < 1e-15);
    assert!((l.exp() - Quat::new(-2.0, 0.0, 0.0, 0.0)).norm() < 1e-15);
}

#[test]
fn bad_quaternions_get_typed_errors() {
    let zero = Quat::<f64>::zero();
    assert_eq!(
        zero.normalize(),
        Err(Error::ZeroNorm { what: "quaternion" })
    );
    assert_eq!(zero.inverse(), Err(Error::ZeroNorm { what: "quaternion" }));
    assert!(matches!(zero.log(), Err(Error::ZeroNorm { .. })));
    assert!(matches!(zero.powf(0.5), Err(Error::ZeroNorm { .. })));
    let nan = Quat::<f64>::new(f64::NAN, 0.0, 0.0, 1.0);
    assert!(matches!(nan.normalize(), Err(Error::NonFinite { .. })));
    assert!(matches!(nan.log(), Err(Error::NonFinite { .. })));
    assert!(matches!(nan.to_axis_angle(), Err(Error::NonFinite { .. })));
    let inf = Quat::<f32>::new(f32::INFINITY, 0.0, 0.0, 0.0);
    assert!(matches!(inf.inverse(), Err(Error::NonFinite { .. })));
    assert!(matches!(
        Quat::<f64>::from_axis_angle(Vec3::zero(), 1.0),
        Err(Error::ZeroNorm {
            what: "rotation axis"
        })
    ));
    assert!(matches!(
        Quat::<f64>::from_axis_angle(Vec3::unit(0), f64::NAN),
        Err(Error::NonFinite { .. })
    ));
    // Huge but finite components: normalizing rescales instead of overflowing.
    let big = Quat::<f64>::new(1e300, 1e300, 0.0, 0.0)
        .normalize()
        .unwrap();
    assert!((big.w - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-15);
    let big = Quat::<f64>::new(1e300, 1e300, 0.0, 0.0).log().unwrap();
    assert!(big.is_finite() && (big.x - std::f64::consts::FRAC_PI_4).abs() < 1e-15);
}
