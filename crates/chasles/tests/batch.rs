//! The batch functions against their per-item functions: `quats_to_euler` against
//! `Quat::to_euler` (a few ulp; exactly at gimbal lock and wherever it defers to it),
//! `quats_to_rotation_matrices` against `Quat::to_rotation_matrix`,
//! `quats_from_rotation_matrices` against `Quat::from_rotation_matrix` and `dlb_batch`
//! against `dlb` (bit for bit), over random inputs and the special cases, in f32 and f64;
//! their errors name the first failing item.

use chasles::blend::dlb::{dlb, dlb_batch, dlb_in_lanes, LANES};
use chasles::convert::euler::quats_to_euler;
use chasles::convert::matrix::{quats_from_rotation_matrices, quats_to_rotation_matrices};
use chasles::convert::BatchError;
use chasles::{DualQuat, Error, EulerOrder, Mat3, Quat, Real, Vec3};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use std::f64::consts::{FRAC_PI_2, PI};

fn rng(seed: u64) -> StdRng {
    StdRng::seed_from_u64(seed)
}

/// A random quaternion, any sign, of norm between 1e-3 and 1e3 (its scale does not matter
/// to the rotation).
fn any_quat<T: Real>(r: &mut StdRng) -> Quat<T> {
    let s = 10f64.powf(r.random_range(-3.0..3.0));
    let mut v = [0.0; 4];
    for x in &mut v {
        *x = r.random_range(-1.0..1.0) * s;
    }
    Quat::new(
        T::from_f64(v[0]),
        T::from_f64(v[1]),
        T::from_f64(v[2]),
        T::from_f64(v[3]),
    )
}

/// Special quaternions: rotations about one axis and about none (components exactly 0,
/// either sign), half turns, Euler angles at and next to gimbal lock in `order`, and the
/// tiny and huge scales the normalization must rescale.
fn special<T: Real>(order: EulerOrder) -> Vec<Quat<T>> {
    let f = T::from_f64;
    let mut v = vec![Quat::identity(), -Quat::identity()];
    for axis in 0..3 {
        for a in [0.3, -2.0, PI, -PI, FRAC_PI_2] {
            let q = Quat::from_axis_index(axis, f(a));
            v.extend([q, -q]);
        }
    }
    let mid = if order.is_proper_euler() {
        [0.0, PI]
    } else {
        [FRAC_PI_2, -FRAC_PI_2]
    };
    for m in mid {
        for near in [0.0, 1e-15, -1e-15, 1e-12, 1e-9, 1e-6, 1e-3] {
            for (a, c) in [(0.4, -1.1), (2.9, 3.0), (-3.1, 0.2)] {
                v.push(Quat::from_euler(order, [f(a), f(m + near), f(c)]));
            }
        }
    }
    // Squared norms past the ends of T's range: normalize rescales first.
    let base: Quat<f64> = Quat::new(0.5, -0.1, 0.7, 0.2);
    let scales = if T::EPSILON.to_f64() > 1e-10 {
        [1e-30, 1e-20, 1e20, 1e30]
    } else {
        [1e-200, 1e-160, 1e160, 1e200]
    };
    for s in scales {
        v.push((base * s).cast());
    }
    v.push(Quat::new(f(-0.0), f(0.6), f(-0.0), f(0.8)));
    v.push(Quat::new(f(0.0), f(-0.0), f(0.0), f(1.0)));
    v
}

/// Difference of two angles, through the wrap at ±π (π and −π are the same angle).
fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).abs();
    d.min((d - 2.0 * PI).abs())
}

/// `quats_to_euler` against `Quat::to_euler` in every order: within 8 ε·π of each angle;
/// bit for bit where gimbal lock was met (the batch defers to `to_euler` there).
fn euler_agrees<T: Real>(seed: u64) -> f64 {
    let mut r = rng(seed);
    let mut worst: f64 = 0.0;
    for order in EulerOrder::all() {
        let mut q: Vec<Quat<T>> = (0..1000).map(|_| any_quat(&mut r)).collect();
        q.extend(special::<T>(order));
        let mut out = vec![[T::ZERO; 3]; q.len()];
        quats_to_euler(&q, order, &mut out).unwrap();
        for (qi, got) in q.iter().zip(&out) {
            let want = qi.to_euler(order).unwrap();
            if want.gimbal_lock {
                assert_eq!(*got, want.angles, "{order} at gimbal lock: {qi:?}");
                continue;
            }
            for (g, w) in got.iter().zip(&want.angles) {
                let d = angle_diff(g.to_f64(), w.to_f64()) / (T::EPSILON.to_f64() * PI);
                assert!(d <= 4.0, "{order}: {qi:?}: {got:?} vs {:?}", want.angles);
                worst = worst.max(d);
            }
        }
    }
    worst
}

#[test]
fn quats_to_euler_agrees_with_to_euler_in_every_order() {
    let w64 = euler_agrees::<f64>(1);
    let w32 = euler_agrees::<f32>(2);
    // Most items agree far better than the bound: not every angle is exact by accident.
    assert!(w64 > 0.0 && w32 > 0.0, "{w64} {w32}");
}

#[test]
fn quats_to_euler_gives_the_angles_back() {
    // Closed form: the angles a rotation was made of, in the canonical ranges.
    for order in EulerOrder::all() {
        let mid = if order.is_proper_euler() { 1.2 } else { -0.7 };
        let angles = [[0.3, mid, -2.5], [-3.0, mid * 0.5, 3.0], [1.0, -mid, 0.0]].map(|a| {
            if order.is_proper_euler() {
                [a[0], a[1].abs(), a[2]]
            } else {
                a
            }
        });
        let q: Vec<Quat<f64>> = angles.iter().map(|a| Quat::from_euler(order, *a)).collect();
        let mut out = vec![[0.0; 3]; 3];
        quats_to_euler(&q, order, &mut out).unwrap();
        for (got, want) in out.iter().zip(&angles) {
            for (g, w) in got.iter().zip(want) {
                assert!((g - w).abs() < 1e-14, "{order}: {got:?} vs {want:?}");
            }
        }
    }
    // Gimbal lock, as Dam et al. App. B.2 has it: the third angle is 0.
    let q = [Quat::from_euler(
        EulerOrder::DAM,
        [0.4f32, std::f32::consts::FRAC_PI_2, -1.1],
    )];
    let mut out = [[0.0f32; 3]];
    quats_to_euler(&q, EulerOrder::DAM, &mut out).unwrap();
    assert_eq!(out[0][2], 0.0);
    assert!((out[0][0] - 1.5).abs() < 1e-6, "{out:?}");
}

#[test]
fn quats_to_euler_reports_the_first_bad_item() {
    let mut q = vec![Quat::<f64>::new(1.0, 0.2, 0.3, 0.4); 300];
    q[200] = Quat::zero();
    q[250] = Quat::new(f64::NAN, 0.0, 0.0, 1.0);
    let mut out = vec![[9.0; 3]; 300];
    let e = quats_to_euler(&q, EulerOrder::DAM, &mut out).unwrap_err();
    assert_eq!(e.index, 200);
    assert!(matches!(e.error, Error::ZeroNorm { .. }), "{e}");
    let want = q[199].to_euler(EulerOrder::DAM).unwrap().angles;
    assert!(
        (0..3).all(|k| (out[199][k] - want[k]).abs() < 1e-15),
        "{out:?}"
    );
    q[200] = Quat::identity();
    let e = quats_to_euler(&q, EulerOrder::DAM, &mut out).unwrap_err();
    assert_eq!(e.index, 250);
    assert!(matches!(e.error, Error::NonFinite { .. }), "{e}");
    assert!(e.to_string().starts_with("item 250: "), "{e}");
    let e = quats_to_euler(&q, EulerOrder::DAM, &mut out[..10]).unwrap_err();
    assert!(
        matches!(e.error, Error::BatchLengths { a: 300, b: 10, .. }),
        "{e}"
    );
    assert_eq!(quats_to_euler::<f32>(&[], EulerOrder::DAM, &mut []), Ok(()));
}

/// Rotation matrices of random rotations and of each of Shepperd's four pivots' ranges
/// (half turns about each axis and between them), identity, and rotations rounded to f32.
fn rotations<T: Real>(seed: u64) -> Vec<Mat3<T>> {
    let mut r = rng(seed);
    let mut m: Vec<Mat3<T>> = (0..2000)
        .map(|_| any_quat::<T>(&mut r).to_rotation_matrix())
        .collect();
    m.push(Mat3::identity());
    for axis in [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 1.0, 0.0],
        [1.0, -2.0, 3.0],
    ] {
        for angle in [PI, PI - 1e-7, 3.0, 1.0, 1e-9] {
            let q = Quat::from_axis_angle(Vec3::from_array(axis), angle).unwrap();
            m.push(q.cast::<T>().to_rotation_matrix());
        }
    }
    m
}

#[test]
fn quats_from_rotation_matrices_is_from_rotation_matrix_bit_for_bit() {
    fn check<T: Real>(seed: u64) {
        let m = rotations::<T>(seed);
        let mut out = vec![Quat::zero(); m.len()];
        quats_from_rotation_matrices(&m, &mut out).unwrap();
        for (mi, q) in m.iter().zip(&out) {
            assert_eq!(*q, Quat::from_rotation_matrix(mi).unwrap(), "{mi:?}");
        }
    }
    check::<f64>(3);
    check::<f32>(4);
    // Closed form: a half turn about z.
    let m = [Mat3::from_rows([
        [-1.0f64, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
    ])];
    let mut q = [Quat::zero()];
    quats_from_rotation_matrices(&m, &mut q).unwrap();
    assert_eq!(q[0], Quat::new(0.0, 0.0, 0.0, 1.0));
}

#[test]
fn quats_from_rotation_matrices_reports_the_first_bad_item() {
    let mut m = rotations::<f64>(5);
    let mut out = vec![Quat::zero(); m.len()];
    let good = m.clone();
    m[700] = Mat3::from_rows([[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    m[900].m[1][1] = f64::INFINITY;
    m[1000].m[0][0] = 3.0;
    let e = quats_from_rotation_matrices(&m, &mut out).unwrap_err();
    assert_eq!(e.index, 700);
    assert!(e.error.to_string().contains("reflection"), "{e}");
    assert_eq!(out[699], Quat::from_rotation_matrix(&good[699]).unwrap());
    m[700] = good[700];
    let e = quats_from_rotation_matrices(&m, &mut out).unwrap_err();
    assert_eq!(
        e,
        BatchError {
            index: 900,
            error: Quat::from_rotation_matrix(&m[900]).unwrap_err()
        }
    );
    m[900] = good[900];
    let e = quats_from_rotation_matrices(&m, &mut out).unwrap_err();
    assert_eq!(e.index, 1000);
    assert!(matches!(e.error, Error::NotRotation { .. }), "{e}");
    // A matrix a hair off a rotation is accepted, as the per-item function does.
    let mut near = [good[5]];
    near[0].m[0][1] += 1e-10;
    let mut q = [Quat::zero()];
    quats_from_rotation_matrices(&near, &mut q).unwrap();
    assert_eq!(q[0], Quat::from_rotation_matrix(&near[0]).unwrap());
}

#[test]
fn quats_to_rotation_matrices_is_to_rotation_matrix_bit_for_bit() {
    fn check<T: Real>(seed: u64) {
        let mut r = rng(seed);
        let mut q: Vec<Quat<T>> = (0..1003).map(|_| any_quat(&mut r)).collect();
        q.extend(special::<T>(EulerOrder::DAM));
        let mut out = vec![[T::ZERO; 9]; q.len()];
        quats_to_rotation_matrices(&q, &mut out).unwrap();
        for (qi, m) in q.iter().zip(&out) {
            let n2 = qi.norm_squared();
            let want = if n2.is_finite() && n2 >= T::MIN_POSITIVE {
                qi.to_rotation_matrix()
            } else {
                // Squared norms past the ends of the normal range: normalized first.
                qi.normalize().unwrap().to_rotation_matrix()
            };
            assert_eq!(*m, want.to_row_major(), "{qi:?}");
            let back = Mat3::from_row_major(*m);
            assert!(back.rotation_deviation().to_f64() < 1e3 * T::EPSILON.to_f64());
        }
    }
    check::<f64>(6);
    check::<f32>(7);
    // Closed form: a half turn about z, from a quaternion of length 2.
    let mut m = [[0.0; 9]];
    quats_to_rotation_matrices(&[Quat::new(0.0f64, 0.0, 0.0, 2.0)], &mut m).unwrap();
    assert_eq!(m[0], [-1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 1.0]);
}

#[test]
fn quats_to_rotation_matrices_reports_the_first_bad_item() {
    let mut q = vec![Quat::<f32>::new(1.0, 0.2, 0.3, 0.4); 21];
    q[13] = Quat::zero();
    q[19] = Quat::new(0.0, f32::INFINITY, 0.0, 0.0);
    let mut out = vec![[0.0; 9]; 21];
    let e = quats_to_rotation_matrices(&q, &mut out).unwrap_err();
    assert!(
        matches!(
            e,
            BatchError {
                index: 13,
                error: Error::ZeroNorm { .. }
            }
        ),
        "{e}"
    );
    assert_eq!(out[12], q[12].to_rotation_matrix().to_row_major());
    q[13] = Quat::identity();
    let e = quats_to_rotation_matrices(&q, &mut out).unwrap_err();
    assert!(
        matches!(
            e,
            BatchError {
                index: 19,
                error: Error::NonFinite { .. }
            }
        ),
        "{e}"
    );
    let e = quats_to_rotation_matrices(&q, &mut out[..3]).unwrap_err();
    assert!(
        matches!(e.error, Error::BatchLengths { a: 21, b: 3, .. }),
        "{e}"
    );
}

fn random_dq<T: Real>(r: &mut StdRng) -> [T; 8] {
    let q = any_quat::<f64>(r).normalize().unwrap();
    let t = Vec3::new(
        r.random_range(-5.0..5.0),
        r.random_range(-5.0..5.0),
        r.random_range(-5.0..5.0),
    );
    DualQuat::from_rotation_translation(q, t)
        .cast::<T>()
        .to_array()
}

/// `dlb_batch` against `dlb` for blends of N: random unit dual quaternions of both signs,
/// random weights (some zero, sums not 1), 1003 blends (a tail after the groups of eight).
fn dlb_agrees<T: Real, const N: usize>(seed: u64) {
    let mut r = rng(seed);
    let count = 1003;
    let q: Vec<[[T; 8]; N]> = (0..count)
        .map(|_| {
            core::array::from_fn(|_| {
                let d = random_dq::<T>(&mut r);
                if r.random_bool(0.5) {
                    d.map(|v| -v)
                } else {
                    d
                }
            })
        })
        .collect();
    let w: Vec<[T; N]> = (0..count)
        .map(|_| {
            core::array::from_fn(|_| {
                if r.random_bool(0.1) {
                    T::ZERO
                } else {
                    T::from_f64(r.random_range(0.01..3.0))
                }
            })
        })
        .map(|mut w: [T; N]| {
            if w.iter().all(|v| *v == T::ZERO) {
                w[0] = T::ONE;
            }
            w
        })
        .collect();
    let mut out = vec![[T::ZERO; 8]; count];
    dlb_batch(&q, &w, &mut out).unwrap();
    for ((qi, wi), got) in q.iter().zip(&w).zip(&out) {
        let want = dlb(&qi.map(DualQuat::from_array), wi).unwrap().to_array();
        assert_eq!(*got, want, "N = {N}: {qi:?} {wi:?}");
    }
}

#[test]
fn dlb_batch_is_dlb_bit_for_bit() {
    dlb_agrees::<f64, 1>(10);
    dlb_agrees::<f64, 2>(11);
    dlb_agrees::<f64, 3>(12);
    dlb_agrees::<f64, 4>(13);
    dlb_agrees::<f64, 7>(14);
    dlb_agrees::<f32, 2>(15);
    dlb_agrees::<f32, 4>(16);
    dlb_agrees::<f32, 8>(17);
}

#[test]
fn dlb_batch_blends_translations_and_keeps_the_hemisphere() {
    // Closed form: pure translations blend to the weighted mean of the translations; the
    // lighter one is flipped into the hemisphere of the heavier, negated one (the same
    // motion), not cancelled.
    let t = |x: f64, y: f64| {
        DualQuat::from_rotation_translation(Quat::identity(), Vec3::new(x, y, 0.0))
    };
    let q = [[t(1.0, 0.0).to_array(), (-t(0.0, 2.0)).to_array()]; 9];
    let w = [[1.0, 3.0]; 9];
    let mut out = [[0.0; 8]; 9];
    dlb_batch(&q, &w, &mut out).unwrap();
    for o in out {
        let d = DualQuat::from_array(o);
        assert!(
            (d.translation() - Vec3::new(0.25, 1.5, 0.0)).norm() < 1e-15,
            "{d:?}"
        );
        assert_eq!(d.real, -Quat::identity());
    }
}

#[test]
fn dlb_batch_reports_the_first_bad_item() {
    let mut r = rng(20);
    let mut q: Vec<[[f64; 8]; 3]> = (0..43)
        .map(|_| core::array::from_fn(|_| random_dq(&mut r)))
        .collect();
    let mut w = vec![[0.2, 0.3, 0.5]; 43];
    let mut out = vec![[0.0; 8]; 43];
    w[17] = [0.2, -0.3, 0.5];
    w[30] = [0.0, 0.0, 0.0];
    q[35][1][2] = f64::NAN;
    let e = dlb_batch(&q, &w, &mut out).unwrap_err();
    assert_eq!(
        e,
        BatchError {
            index: 17,
            error: Error::BadWeight {
                index: 1,
                value: -0.3
            }
        }
    );
    assert_eq!(
        out[16],
        dlb(&q[16].map(DualQuat::from_array), &w[16])
            .unwrap()
            .to_array()
    );
    w[17] = [0.2, 0.3, 0.5];
    let e = dlb_batch(&q, &w, &mut out).unwrap_err();
    assert_eq!(
        e,
        BatchError {
            index: 30,
            error: Error::WeightSum { sum: 0.0 }
        }
    );
    w[30] = [1.0, f64::INFINITY, 0.0];
    assert!(matches!(
        dlb_batch(&q, &w, &mut out).unwrap_err().error,
        Error::BadWeight { index: 1, .. }
    ));
    w[30] = [1.0, 0.0, 0.0];
    let e = dlb_batch(&q, &w, &mut out).unwrap_err();
    assert_eq!(e.index, 35);
    assert!(matches!(e.error, Error::NonFinite { .. }), "{e}");
    // In the last, partial group too.
    q[35][1][2] = 0.5;
    w[41] = [0.0, f64::NAN, 1.0];
    let e = dlb_batch(&q, &w, &mut out).unwrap_err();
    assert!(
        matches!(
            e,
            BatchError {
                index: 41,
                error: Error::BadWeight { index: 1, .. }
            }
        ),
        "{e}"
    );
    let want = dlb(&q[40].map(DualQuat::from_array), &w[40])
        .unwrap()
        .to_array();
    assert_eq!(out[40], want);
    // Real parts of zero (not rigid motions) sum to zero: dlb's ZeroNorm.
    let z = [0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0];
    let e = dlb_batch(&[[z, z]], &[[1.0, 1.0]], &mut [[0.0; 8]]).unwrap_err();
    assert!(matches!(e.error, Error::ZeroNorm { .. }), "{e}");
    let e = dlb_batch::<f64, 0>(&[[]], &[[]], &mut [[0.0; 8]]).unwrap_err();
    assert!(matches!(e.error, Error::BlendInput { .. }), "{e}");
    let e = dlb_batch(&q[..3], &w[..2], &mut out[..3]).unwrap_err();
    assert!(
        matches!(e.error, Error::BatchLengths { a: 3, b: 2, .. }),
        "{e}"
    );
}

#[test]
fn dlb_in_lanes_is_dlb_where_it_says_so() {
    // Eight blends of three held in lanes: x[k][j][l], w[k][l].
    let mut r = rng(30);
    let q: Vec<[[f64; 8]; 3]> = (0..LANES)
        .map(|_| core::array::from_fn(|_| random_dq(&mut r)))
        .collect();
    let mut w: Vec<[f64; 3]> = (0..LANES)
        .map(|_| core::array::from_fn(|_| r.random_range(0.0..2.0)))
        .collect();
    w[3] = [1.0, -1.0, 1.0];
    w[6] = [0.0; 3];
    let x: [[[f64; LANES]; 8]; 3] =
        core::array::from_fn(|k| core::array::from_fn(|j| core::array::from_fn(|l| q[l][k][j])));
    let wl: [[f64; LANES]; 3] = core::array::from_fn(|k| core::array::from_fn(|l| w[l][k]));
    let (out, ok) = dlb_in_lanes(&x, &wl);
    for l in 0..LANES {
        let want = dlb(&q[l].map(DualQuat::from_array), &w[l]);
        assert_eq!(ok[l], l != 3 && l != 6, "lane {l}");
        if ok[l] {
            let got: [f64; 8] = core::array::from_fn(|j| out[j][l]);
            assert_eq!(got, want.unwrap().to_array(), "lane {l}");
        } else {
            assert!(want.is_err());
        }
    }
}
