//! Dual quaternions (Kavan et al. 2006, §3): algebra, rigid transformations (eq. 1),
//! matrices, screw parameters (eq. 2), exp/log/powers and Lemma 1, on random inputs in f32
//! and f64 (tolerances of `common::Tol`: 1e-12 f64, 1e-5 f32, relative).

mod common;
use chasles::{Dual, DualQuat, Error, Mat4, Quat, Real, Screw, Vec3};
use common::*;
use proptest::prelude::*;

fn any_dq() -> impl Strategy<Value = Raw8> {
    (any_quat(), prop::array::uniform4(-3.0f64..3.0))
}
fn gdq<T: Real>(a: Raw8) -> DualQuat<T> {
    DualQuat::new(quat_of(a.0), quat_of(a.1))
}

fn norm_multiplicative<T: Tol>((p, q): (Raw8, Raw8), tol: f64) -> Result<(), TestCaseError> {
    let (p, q) = (gdq::<T>(p), gdq::<T>(q));
    let lhs = (p * q).norm().unwrap();
    let rhs = p.norm().unwrap() * q.norm().unwrap();
    close(&[lhs.re, lhs.du], &[rhs.re, rhs.du], tol * 10.0)
}
both_precisions!(
    dual_norm_is_multiplicative,
    norm_multiplicative,
    any_dq(),
    any_dq()
);

fn conj_product<T: Tol>((p, q): (Raw8, Raw8), tol: f64) -> Result<(), TestCaseError> {
    let (p, q) = (gdq::<T>(p), gdq::<T>(q));
    close(
        &(p * q).conjugate().to_array(),
        &(q.conjugate() * p.conjugate()).to_array(),
        tol,
    )?;
    close(
        &(p * q).full_conjugate().to_array(),
        &(q.full_conjugate() * p.full_conjugate()).to_array(),
        tol,
    )?;
    close(
        &(p * q).dual_conjugate().to_array(),
        &(p.dual_conjugate() * q.dual_conjugate()).to_array(),
        tol,
    )
}
both_precisions!(conjugations_of_products, conj_product, any_dq(), any_dq());

fn inverse<T: Tol>((p,): (Raw8,), tol: f64) -> Result<(), TestCaseError> {
    let p = gdq::<T>(p);
    let i = p.inverse().unwrap();
    close(
        &(p * i).to_array(),
        &DualQuat::<T>::identity().to_array(),
        tol * 10.0,
    )?;
    close(
        &(i * p).to_array(),
        &DualQuat::<T>::identity().to_array(),
        tol * 10.0,
    )
}
both_precisions!(inverse_gives_identity, inverse, any_dq());

fn rigid<T: Tol>((r, p): (Rigid, [f64; 3]), tol: f64) -> Result<(), TestCaseError> {
    let dq = dq_of::<T>(r);
    let p = vec_of::<T>(p);
    prop_assert!(dq.is_unit(T::from_f64(tol * 10.0)));
    // The point transform equals the 4×4 matrix transform.
    let m = dq.to_matrix4();
    close(
        &dq.transform_point(p).to_array(),
        &m.transform_point(p).to_array(),
        tol,
    )?;
    // … and the sandwich q̂ (1 + εp) q̂ (both conjugations) of §3.
    let v = DualQuat::new(Quat::identity(), Quat::pure(p));
    let s = dq * v * dq.full_conjugate();
    close(
        &s.dual.vector().to_array(),
        &m.transform_point(p).to_array(),
        tol,
    )?;
    // Eq. (1) and its inverse t = 2 qε q0*.
    close(
        &dq.translation().to_array(),
        &vec_of::<T>(r.1).to_array(),
        tol,
    )?;
    // Matrix → dual quaternion → matrix.
    let back = DualQuat::from_matrix4(&m).unwrap();
    close_dq(back, dq, tol)?;
    close(&back.to_matrix4().to_row_major(), &m.to_row_major(), tol)
}
both_precisions!(
    dual_quaternion_transform_equals_matrix_transform,
    rigid,
    unit_dq(),
    any_vec()
);

fn composition<T: Tol>((a, b, p): (Rigid, Rigid, [f64; 3]), tol: f64) -> Result<(), TestCaseError> {
    let (a, b) = (dq_of::<T>(a), dq_of::<T>(b));
    let p = vec_of::<T>(p);
    // (a b) applies b first, like matrices.
    close(
        &(a * b).transform_point(p).to_array(),
        &a.transform_point(b.transform_point(p)).to_array(),
        tol * 10.0,
    )?;
    close(
        &(a * b).to_matrix4().to_row_major(),
        &(a.to_matrix4() * b.to_matrix4()).to_row_major(),
        tol * 10.0,
    )
}
both_precisions!(
    composition_is_multiplication,
    composition,
    unit_dq(),
    unit_dq(),
    any_vec()
);

fn screw_round_trip<T: Tol>((r,): (Rigid,), tol: f64) -> Result<(), TestCaseError> {
    let dq = dq_of::<T>(r);
    let s = dq.to_screw().unwrap();
    close(&[s.axis.norm()], &[T::ONE], tol)?;
    close(&[s.axis.dot(s.moment)], &[T::ZERO], tol * 10.0)?;
    let back = DualQuat::from_screw(&s).unwrap();
    // The moment blows up like 1/angle for nearly pure rotations far from the origin, so
    // compare relative to the transformation's size.
    close(&back.to_array(), &dq.to_array(), tol * 10.0)?;
    // The screw's point is on the axis: it is moved only along the axis.
    let p = s.point();
    let moved = dq.transform_point(p) - p;
    close(
        &moved.to_array(),
        &(s.axis * s.translation).to_array(),
        tol * 100.0,
    )
}
both_precisions!(screw_parameters_round_trip, screw_round_trip, unit_dq());

fn exp_log<T: Tol>((p,): (Raw8,), tol: f64) -> Result<(), TestCaseError> {
    let p = gdq::<T>(p);
    prop_assume!(p.real.vector().norm().to_f64() > 1e-3 || p.real.w.to_f64() > 0.0);
    close(
        &p.log().unwrap().exp().to_array(),
        &p.to_array(),
        tol * 10.0,
    )
}
both_precisions!(exp_of_log_for_any_dual_quaternion, exp_log, any_dq());

fn exp_log_unit<T: Tol>((r,): (Rigid,), tol: f64) -> Result<(), TestCaseError> {
    let dq = dq_of::<T>(r);
    let l = dq.log().unwrap();
    // log of a unit dual quaternion is pure: ŝ θ̂/2.
    close(&[l.real.w, l.dual.w], &[T::ZERO, T::ZERO], tol * 10.0)?;
    close(&l.exp().to_array(), &dq.to_array(), tol * 10.0)
}
both_precisions!(
    exp_of_log_for_unit_dual_quaternions,
    exp_log_unit,
    unit_dq()
);

fn log_power<T: Tol>((r, t): (Rigid, f64), tol: f64) -> Result<(), TestCaseError> {
    let dq = dq_of::<T>(r).to_positive_hemisphere();
    let t = T::from_f64(t);
    let lhs = dq.powf(t).unwrap().log().unwrap();
    close(
        &lhs.to_array(),
        &(dq.log().unwrap() * t).to_array(),
        tol * 100.0,
    )
}
both_precisions!(
    log_of_power_is_scaled_log,
    log_power,
    unit_dq(),
    -1.9f64..1.9
);

fn powers_add<T: Tol>((r, a, b): (Rigid, f64, f64), tol: f64) -> Result<(), TestCaseError> {
    let dq = dq_of::<T>(r);
    let (a, b) = (T::from_f64(a), T::from_f64(b));
    let lhs = dq.powf(a).unwrap() * dq.powf(b).unwrap();
    close(
        &lhs.to_array(),
        &dq.powf(a + b).unwrap().to_array(),
        tol * 100.0,
    )
}
both_precisions!(
    dual_powers_add_exponents,
    powers_add,
    unit_dq(),
    -2.0f64..2.0,
    -2.0f64..2.0
);

fn dual_exponent<T: Tol>((r, u0, ue): (Rigid, f64, f64), tol: f64) -> Result<(), TestCaseError> {
    // q̂^(u0 + εuε) = cos(û θ̂/2) + ŝ sin(û θ̂/2): angle × u0, translation u0 θε + uε θ0.
    let dq = dq_of::<T>(r).to_positive_hemisphere();
    let s = dq.to_screw().unwrap();
    prop_assume!(s.angle.to_f64() > 1e-2);
    let u = Dual::new(T::from_f64(u0), T::from_f64(ue));
    let want = Screw {
        angle: s.angle * u.re,
        translation: s.translation * u.re + s.angle * u.du,
        ..s
    };
    let got = dq.pow_dual(u).unwrap();
    close_dq(got, DualQuat::from_screw(&want).unwrap(), tol * 100.0)
}
both_precisions!(
    dual_exponent_scales_angle_and_slides,
    dual_exponent,
    unit_dq(),
    -1.5f64..1.5,
    -1.0f64..1.0
);

fn lemma1<T: Tol>((m, q): (Rigid, Rigid), tol: f64) -> Result<(), TestCaseError> {
    let (m, q) = (dq_of::<T>(m), dq_of::<T>(q));
    // Lemma 1 (Kavan et al. App. A): log(m q m*) = m log(q) m*, exp likewise.
    let lhs = (m * q * m.conjugate()).log().unwrap();
    let rhs = m * q.log().unwrap() * m.conjugate();
    close(&lhs.to_array(), &rhs.to_array(), tol * 100.0)?;
    let l = q.log().unwrap();
    close(
        &(m * l * m.conjugate()).exp().to_array(),
        &(m * l.exp() * m.conjugate()).to_array(),
        tol * 100.0,
    )
}
both_precisions!(
    lemma_1_log_commutes_with_conjugation,
    lemma1,
    unit_dq(),
    unit_dq()
);

fn normalize<T: Tol>((p,): (Raw8,), tol: f64) -> Result<(), TestCaseError> {
    let p = gdq::<T>(p);
    let n = p.normalize().unwrap();
    prop_assert!(n.is_unit(T::from_f64(tol * 10.0)));
    close(&[n.real.dot(n.dual)], &[T::ZERO], tol * 10.0)?;
    // A unit dual quaternion is its own normalization; so is a scaled one.
    close(
        &n.normalize().unwrap().to_array(),
        &n.to_array(),
        tol * 10.0,
    )?;
    close(
        &(n * T::from_f64(3.7)).normalize().unwrap().to_array(),
        &n.to_array(),
        tol * 10.0,
    )?;
    // The rotation is p's rotation.
    close(
        &n.real.to_array(),
        &p.real.normalize().unwrap().to_array(),
        tol,
    )
}
both_precisions!(
    normalization_gives_a_unit_dual_quaternion,
    normalize,
    any_dq()
);

#[test]
fn eq1_closed_form_and_screw_of_a_known_motion() {
    // A 90° turn about the vertical line through (1, 0, 0) with a 2-unit slide up it.
    let s = Screw::from_point(
        Vec3::new(0.0, 0.0, 5.0),
        Vec3::new(1.0, 0.0, 7.0),
        std::f64::consts::FRAC_PI_2,
        2.0,
    )
    .unwrap();
    assert_eq!(s.pitch(), Some(2.0 / std::f64::consts::FRAC_PI_2));
    let dq = DualQuat::from_screw(&s).unwrap();
    // The origin goes to (1, −1, 2).
    let p = dq.transform_point(Vec3::zero());
    assert!((p - Vec3::new(1.0, -1.0, 2.0)).norm() < 1e-15, "{p:?}");
    let back = dq.to_screw().unwrap();
    assert!((back.point() - Vec3::new(1.0, 0.0, 0.0)).norm() < 1e-15);
    assert!(
        (back.translation - 2.0).abs() < 1e-15
            && (back.angle - std::f64::consts::FRAC_PI_2).abs() < 1e-15
    );
    // Eq. (1): q0 + ε ½ t q0.
    let q = Quat::from_axis_index(2, 0.3f64);
    let t = Vec3::new(1.0, 2.0, 3.0);
    let d = DualQuat::from_rotation_translation(q, t);
    assert_eq!(d.dual, Quat::pure(t * 0.5) * q);
    assert!((d.translation() - t).norm() < 1e-15);
}

#[test]
fn bad_dual_quaternions_get_typed_errors() {
    let zero_real = DualQuat::<f64>::new(Quat::zero(), Quat::identity());
    assert!(matches!(zero_real.inverse(), Err(Error::ZeroNorm { .. })));
    assert!(matches!(zero_real.normalize(), Err(Error::ZeroNorm { .. })));
    assert!(matches!(zero_real.log(), Err(Error::ZeroNorm { .. })));
    assert!(matches!(zero_real.norm(), Err(Error::ZeroNorm { .. })));
    assert!(matches!(zero_real.to_screw(), Err(Error::ZeroNorm { .. })));
    let nan = DualQuat::<f64>::new(Quat::identity(), Quat::new(0.0, f64::NAN, 0.0, 0.0));
    assert!(matches!(nan.log(), Err(Error::NonFinite { .. })));
    assert!(matches!(nan.normalize(), Err(Error::NonFinite { .. })));
    assert!(matches!(
        DualQuat::identity().powf(f64::NAN),
        Err(Error::NonFinite { .. })
    ));
    let not_unit = DualQuat::<f64>::new(Quat::new(2.0, 0.0, 0.0, 0.0), Quat::zero());
    assert!(matches!(not_unit.check_unit(), Err(Error::NotUnit { .. })));
    let mut m = Mat4::<f64>::identity();
    m.m[3][0] = 0.5;
    assert!(matches!(
        DualQuat::from_matrix4(&m),
        Err(Error::NotRigid { .. })
    ));
    let mut m = Mat4::<f64>::identity();
    m.m[0][0] = 2.0;
    let e = DualQuat::from_matrix4(&m).unwrap_err();
    assert!(
        matches!(e, Error::NotRigid { .. }) && e.to_string().contains("rigid"),
        "{e}"
    );
    m.m[0][0] = f64::INFINITY;
    assert!(matches!(
        DualQuat::from_matrix4(&m),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        Screw::from_point(Vec3::zero(), Vec3::zero(), 1.0f64, 0.0),
        Err(Error::ZeroNorm { .. })
    ));
}
