//! Nothing panics, whatever the input: every public operation is fed NaN, ±∞, zero,
//! subnormal, huge and ordinary values in f32 and f64. Fallible operations must return a
//! typed error or a finite value for finite, sensible input; none may panic.

use chasles::{Dual, DualQuat, EulerOrder, Mat3, Mat4, Quat, Real, Screw, Vec3};
use proptest::prelude::*;

fn nasty() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(1e-310),
        Just(1e300),
        Just(-1e300),
        Just(1.0),
        Just(-1.0),
        -10.0f64..10.0,
    ]
}

fn exercise<T: Real>(v: &[f64]) {
    let c = |i: usize| T::from_f64(v[i % v.len()]);
    let q = Quat::new(c(0), c(1), c(2), c(3));
    let p = Quat::new(c(4), c(5), c(6), c(7));
    let t = Vec3::new(c(8), c(9), c(10));
    let _ = (
        q.normalize(),
        q.inverse(),
        q.log(),
        q.powf(c(11)),
        q.exp(),
        q * p,
    );
    let _ = (
        q.to_axis_angle(),
        q.to_rotation_vector(),
        q.angle_to(p),
        q.sandwich(t),
        q.rotate(t),
    );
    let _ = (
        Quat::from_axis_angle(t, c(12)),
        Quat::from_rotation_vector(t),
        t.normalize(),
    );
    for order in EulerOrder::all() {
        let _ = q.to_euler(order);
        let _ = Quat::from_euler(order, [c(0), c(1), c(2)]);
    }
    let m3 = Mat3::from_row_major(core::array::from_fn(&c));
    let _ = (
        Quat::from_rotation_matrix(&m3),
        Quat::from_rotation_matrix_unchecked(&m3),
        m3.to_euler(EulerOrder::DAM),
    );
    let m4 = Mat4::from_row_major(core::array::from_fn(|i| c(i + 3)));
    let _ = (DualQuat::from_matrix4(&m4), Quat::from_matrix4(&m4));
    let d = Dual::new(c(0), c(1));
    let _ = (
        d.inverse(),
        d.sqrt(),
        d.ln(),
        d.sin_cos(),
        d.exp(),
        d.atan2(Dual::new(c(2), c(3))),
    );
    let dq = DualQuat::new(q, p);
    let _ = (
        dq.normalize(),
        dq.inverse(),
        dq.norm(),
        dq.log(),
        dq.exp(),
        dq.powf(c(12)),
    );
    let _ = (
        dq.pow_dual(d),
        dq.to_screw(),
        dq.check_unit(),
        dq.to_matrix4(),
        dq.transform_point(t),
    );
    let s = Screw {
        axis: t,
        moment: Vec3::new(c(1), c(2), c(3)),
        angle: c(4),
        translation: c(5),
    };
    let _ = (
        DualQuat::from_screw(&s),
        Screw::from_point(t, t, c(1), c(2)),
        s.pitch(),
        s.point(),
    );
    // Finite, non-degenerate input gives finite output.
    if let Ok(u) = q.normalize() {
        if let Ok(l) = u.log() {
            assert!(l.is_finite(), "log of unit {u:?} not finite");
        }
    }
}

proptest! {
    #[test]
    fn nothing_panics_on_any_input(v in prop::collection::vec(nasty(), 16)) {
        exercise::<f64>(&v);
        exercise::<f32>(&v);
    }
}
