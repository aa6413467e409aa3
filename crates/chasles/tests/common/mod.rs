//! Shared test helpers: tolerances per precision, relative comparison, random inputs.
#![allow(dead_code)]

use chasles::{DualQuat, Quat, Real, Vec3};
use proptest::prelude::*;
use rand::rngs::StdRng;
use rand::Rng;

/// The relative tolerance a round trip must meet: 1e-12 in f64, 1e-5 in f32 (issue #2).
pub trait Tol: Real {
    const TOL: f64;
}
impl Tol for f64 {
    const TOL: f64 = 1e-12;
}
impl Tol for f32 {
    const TOL: f64 = 1e-5;
}

/// `|a − b|∞ ≤ tol · max(1, |b|∞)`, with a message naming both.
pub fn close<T: Real>(a: &[T], b: &[T], tol: f64) -> Result<(), TestCaseError> {
    let scale = b.iter().fold(1.0f64, |m, v| m.max(v.to_f64().abs()));
    let err = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x.to_f64() - y.to_f64()).abs()));
    if err <= tol * scale && a.len() == b.len() {
        Ok(())
    } else {
        Err(TestCaseError::fail(format!(
            "{a:?} != {b:?}: error {err:e} > {tol:e} x {scale}"
        )))
    }
}

/// `close` for quaternions up to sign (q and −q are the same rotation).
pub fn close_rot<T: Real>(a: Quat<T>, b: Quat<T>, tol: f64) -> Result<(), TestCaseError> {
    let a = if a.dot(b) < T::ZERO { -a } else { a };
    close(&a.to_array(), &b.to_array(), tol)
}

/// `close` for dual quaternions up to sign.
pub fn close_dq<T: Real>(a: DualQuat<T>, b: DualQuat<T>, tol: f64) -> Result<(), TestCaseError> {
    let a = if a.real.dot(b.real) < T::ZERO { -a } else { a };
    close(&a.to_array(), &b.to_array(), tol)
}

pub fn quat_of<T: Real>(a: [f64; 4]) -> Quat<T> {
    Quat::new(
        T::from_f64(a[0]),
        T::from_f64(a[1]),
        T::from_f64(a[2]),
        T::from_f64(a[3]),
    )
}
pub fn vec_of<T: Real>(a: [f64; 3]) -> Vec3<T> {
    Vec3::new(T::from_f64(a[0]), T::from_f64(a[1]), T::from_f64(a[2]))
}

/// Any quaternion with components in [−2, 2] and norm ≥ 0.1.
pub fn any_quat() -> impl Strategy<Value = [f64; 4]> {
    prop::array::uniform4(-2.0f64..2.0).prop_filter("not too small", |q| {
        q.iter().map(|v| v * v).sum::<f64>() >= 0.01
    })
}
/// A unit quaternion (uniform on the sphere after normalization, both hemispheres).
pub fn unit_quat() -> impl Strategy<Value = [f64; 4]> {
    any_quat().prop_map(|q| {
        let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
        q.map(|v| v / n)
    })
}
/// A vector with components in [−5, 5].
pub fn any_vec() -> impl Strategy<Value = [f64; 3]> {
    prop::array::uniform3(-5.0f64..5.0)
}
/// A rigid motion as raw test input: unit quaternion `[w, x, y, z]` and translation.
pub type Rigid = ([f64; 4], [f64; 3]);
/// Any dual quaternion as raw test input: real and dual part.
pub type Raw8 = ([f64; 4], [f64; 4]);

/// A unit dual quaternion: unit rotation and translation in [−5, 5]³.
pub fn unit_dq() -> impl Strategy<Value = Rigid> {
    (unit_quat(), any_vec())
}
pub fn dq_of<T: Real>(r: Rigid) -> DualQuat<T> {
    // Built in f64 and rounded once, so that f32 inputs are as unit as f32 allows.
    let d = DualQuat::from_rotation_translation(quat_of::<f64>(r.0), vec_of::<f64>(r.1));
    d.cast()
}

/// Runs a generic property for f32 and f64 with their tolerances.
#[macro_export]
macro_rules! both_precisions {
    ($name:ident, $body:ident, $($strategy:expr),+) => {
        proptest::proptest! {
            #[test]
            fn $name(args in ($($strategy),+,)) {
                $body::<f64>(args.clone(), <f64 as common::Tol>::TOL)?;
                $body::<f32>(args, <f32 as common::Tol>::TOL)?;
            }
        }
    };
}

/// A random rigid transformation: uniform rotation, translation in [−2, 2]³.
pub fn random_rigid(rng: &mut StdRng) -> DualQuat<f64> {
    let q = loop {
        let q = Quat::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        let n = q.norm();
        if n > 0.1 && n <= 1.0 {
            break q / n;
        }
    };
    let t = Vec3::new(
        rng.random_range(-2.0..2.0),
        rng.random_range(-2.0..2.0),
        rng.random_range(-2.0..2.0),
    );
    DualQuat::from_rotation_translation(q, t)
}
