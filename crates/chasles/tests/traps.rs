//! The numerical traps of the core algebra (log/exp/pow near the identity and 2π, the dual
//! quaternion log of a pure translation, q̂ against −q̂, dual-quaternion normalization), each checked
//! in f32 and f64 (tolerances of `common::Tol`: 1e-12 f64, 1e-5 f32, relative).
//! (Matrix → quaternion near 180° is in convert.rs: `half_turns_convert_exactly` and
//! `trace_only_formula_fails_near_half_turn_and_shepperd_does_not`.)

mod common;
use chasles::{DualQuat, Quat, Real, Vec3};
use common::*;
use proptest::prelude::*;

/// Angles from exactly 0 through the series threshold to ordinary sizes.
const SMALL: [f64; 9] = [0.0, 1e-300, 1e-30, 1e-15, 1e-9, 1e-6, 1e-4, 1e-2, 0.3];

fn unit_axis<T: Real>() -> Vec3<T> {
    vec_of::<T>([1.0, -2.0, 2.0]) / T::from_f64(3.0)
}

fn quat_near_identity_and_2pi<T: Tol>() -> Result<(), TestCaseError> {
    let tol = T::TOL;
    let n = unit_axis::<T>();
    for d in SMALL {
        let (s, c) = (T::from_f64((d / 2.0).sin()), T::from_f64((d / 2.0).cos()));
        // Rotation by d: [cos d/2, sin d/2 n]; by 2π − d: [−cos d/2, sin d/2 n].
        for (q, half) in [
            (Quat::from_scalar_vector(c, n * s), d / 2.0),
            (
                Quat::from_scalar_vector(-c, n * s),
                std::f64::consts::PI - d / 2.0,
            ),
        ] {
            let l = q.log().map_err(|e| TestCaseError::fail(e.to_string()))?;
            prop_assert!(l.is_finite(), "log not finite at d = {d}");
            close(&[l.vector().norm()], &[T::from_f64(half)], tol)?;
            close(&l.exp().to_array(), &q.to_array(), tol)?;
            let h = q.powf(T::HALF).unwrap();
            prop_assert!(h.is_finite());
            close(&(h * h).to_array(), &q.to_array(), tol)?;
            close(
                &[h.log().unwrap().vector().norm()],
                &[T::from_f64(half / 2.0)],
                tol,
            )?;
        }
        // exp of a tiny pure quaternion: no 0/0.
        let e = Quat::pure(n * T::from_f64(d)).exp();
        close(
            &e.to_array(),
            &[
                T::from_f64(d.cos()),
                n.x * T::from_f64(d.sin()),
                n.y * T::from_f64(d.sin()),
                n.z * T::from_f64(d.sin()),
            ],
            tol,
        )?;
    }
    // Exactly −1 (2π, no axis left): the x axis, and exp maps back.
    let l = Quat::<T>::new(-T::ONE, T::ZERO, T::ZERO, T::ZERO)
        .log()
        .unwrap();
    close(&l.to_array(), &[T::ZERO, T::PI, T::ZERO, T::ZERO], tol)?;
    close(
        &l.exp().to_array(),
        &[-T::ONE, T::ZERO, T::ZERO, T::ZERO],
        tol,
    )
}

#[test]
fn quaternion_exp_log_pow_near_identity_and_near_2pi() {
    quat_near_identity_and_2pi::<f64>().unwrap();
    quat_near_identity_and_2pi::<f32>().unwrap();
}

fn dq_pure_translation<T: Tol>((t,): ([f64; 3],), tol: f64) -> Result<(), TestCaseError> {
    let tv = vec_of::<T>(t);
    prop_assume!(tv.norm().to_f64() > 1e-3);
    let dq = DualQuat::from_translation(tv);
    // log(1 + ε t/2) = ε [0, t/2]: the screw axis is the translation direction.
    let l = dq.log().unwrap();
    close(&l.real.to_array(), &[T::ZERO; 4], 0.0)?;
    close(
        &l.dual.to_array(),
        &Quat::pure(tv * T::HALF).to_array(),
        tol,
    )?;
    let s = dq.to_screw().unwrap();
    close(&s.axis.to_array(), &tv.normalize().unwrap().to_array(), tol)?;
    close(&[s.angle, s.translation], &[T::ZERO, tv.norm()], tol)?;
    close(&s.moment.to_array(), &[T::ZERO; 3], 0.0)?;
    prop_assert!(s.pitch().is_none());
    // Powers slide along it; exp(log) is exact.
    close(
        &dq.powf(T::from_f64(0.25)).unwrap().translation().to_array(),
        &(tv * T::from_f64(0.25)).to_array(),
        tol,
    )?;
    close(&l.exp().to_array(), &dq.to_array(), tol)?;
    close_dq(DualQuat::from_screw(&s).unwrap(), dq, tol)
}
both_precisions!(
    dual_quaternion_log_of_pure_translation,
    dq_pure_translation,
    any_vec()
);

fn dq_near_identity_and_2pi<T: Tol>((t,): ([f64; 3],), tol: f64) -> Result<(), TestCaseError> {
    let tv = vec_of::<T>(t);
    let n = unit_axis::<T>();
    for d in SMALL {
        let q = Quat::from_scalar_vector(
            T::from_f64((d / 2.0).cos()),
            n * T::from_f64((d / 2.0).sin()),
        );
        let dq = DualQuat::from_rotation_translation(q, tv);
        // Rotation by d: log and exp exact.
        let l = dq.log().map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assert!(l.is_finite(), "log not finite at d = {d}");
        close(&l.exp().to_array(), &dq.to_array(), tol * 10.0)?;
        // −q̂ turns by 2π − d. Its screw axis lies |t⊥|/d from the origin (as it must: a
        // tiny turn plus a sideways slide is a screw about a far-away axis), so log −q̂ has
        // size ~1/d and exp(log) is good to ε/d: the condition number, not a defect.
        let x = -dq;
        let l = x.log().map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assert!(l.is_finite(), "log not finite at d = {d}");
        if d > 0.0 {
            close(
                &l.exp().to_array(),
                &x.to_array(),
                tol * 10.0 * (1.0 / d).max(1.0),
            )?;
        }
        // With the translation along the axis the moment is 0: the screw parameters are
        // exact near 2π too (exp(log) is again good to ε/d, the input's own rounding).
        let along = -DualQuat::from_rotation_translation(q, n * tv.norm());
        let l = along.log().unwrap();
        prop_assert!(l.is_finite());
        if d > 0.0 {
            close(
                &l.exp().to_array(),
                &along.to_array(),
                tol * 10.0 * (1.0 / d).max(1.0),
            )?;
        }
        let s = along.to_screw().unwrap();
        close(
            &[s.angle],
            &[T::from_f64(2.0 * std::f64::consts::PI - d)],
            tol,
        )?;
        close(
            &(s.axis * s.translation).to_array(),
            &(n * tv.norm()).to_array(),
            tol,
        )?;
        // The moment is |qε rounding| / angle: its conditioning is 1/d at tiny angles.
        close(
            &s.moment.to_array(),
            &[T::ZERO; 3],
            tol * (1.0 / d).max(1.0),
        )?;
        // The short way: finite for every d, and q̂^½ squared is q̂.
        let h = dq.powf(T::HALF).unwrap();
        prop_assert!(h.is_finite(), "d = {d}");
        close(&(h * h).to_array(), &dq.to_array(), tol * 10.0)?;
        close(
            &h.translation().to_array(),
            &DualQuat::from_rotation_translation(q, tv)
                .powf(T::HALF)
                .unwrap()
                .translation()
                .to_array(),
            tol,
        )?;
    }
    // Exactly 2π with a translation: −(1 + ε t/2). Finite log; exp maps back.
    let x = -DualQuat::from_translation(tv);
    let l = x.log().unwrap();
    prop_assert!(l.is_finite());
    close(&l.exp().to_array(), &x.to_array(), tol)?;
    let minus_one = -DualQuat::<T>::identity();
    close(
        &minus_one.log().unwrap().exp().to_array(),
        &minus_one.to_array(),
        tol,
    )
}
both_precisions!(
    dual_quaternion_exp_log_pow_near_identity_and_2pi,
    dq_near_identity_and_2pi,
    any_vec()
);

fn q_versus_minus_q<T: Tol>((r, p): (Rigid, [f64; 3]), tol: f64) -> Result<(), TestCaseError> {
    let dq = dq_of::<T>(r);
    let p = vec_of::<T>(p);
    // Same transformation …
    close(
        &(-dq).transform_point(p).to_array(),
        &dq.transform_point(p).to_array(),
        tol,
    )?;
    close(
        &(-dq).to_matrix4().to_row_major(),
        &dq.to_matrix4().to_row_major(),
        tol,
    )?;
    // … but the other way round the screw: angles add to 2π, axes opposite.
    let (a, b) = (dq.to_screw().unwrap(), (-dq).to_screw().unwrap());
    prop_assume!(a.angle.to_f64() > 1e-3 && b.angle.to_f64() > 1e-3);
    close(&[a.angle + b.angle], &[T::TWO * T::PI], tol * 10.0)?;
    close(&(a.axis + b.axis).to_array(), &[T::ZERO; 3], tol * 10.0)?;
    // Matrix → dual quaternion always returns the w ≥ 0 representative.
    let back = DualQuat::from_matrix4(&(-dq).to_matrix4()).unwrap();
    prop_assert!(back.real.w >= T::ZERO);
    close(
        &back.to_array(),
        &dq.to_positive_hemisphere().to_array(),
        tol,
    )
}
both_precisions!(
    q_and_minus_q_same_motion_other_screw,
    q_versus_minus_q,
    unit_dq(),
    any_vec()
);

fn normalization_trap<T: Tol>((r, k, e): (Rigid, f64, f64), tol: f64) -> Result<(), TestCaseError> {
    // Scale by k and push the dual part along q0 by e: normalizing must undo both (divide
    // by |q0| and remove from qε its part along q0), not just divide by |q0|.
    let dq = dq_of::<T>(r);
    let (k, e) = (T::from_f64(k), T::from_f64(e));
    let bad = DualQuat::new(dq.real * k, (dq.dual + dq.real * e) * k);
    prop_assert!(!bad.is_unit(T::from_f64(1e-3)) || (k - T::ONE).abs() < T::from_f64(1e-3));
    let n = bad.normalize().unwrap();
    close(&n.to_array(), &dq.to_array(), tol * 10.0)?;
    // Dividing by |q0| alone leaves ⟨q0, qε⟩ = e ≠ 0.
    let naive = bad * (T::ONE / bad.real.norm());
    close(&[naive.real.dot(naive.dual)], &[e], tol * 10.0)
}
both_precisions!(
    normalization_removes_dual_part_along_real_part,
    normalization_trap,
    unit_dq(),
    0.2f64..5.0,
    -2.0f64..2.0
);
