//! The curves past the report (issue 21, item 4), each with its paper's properties by
//! number: spherical Catmull–Rom (Schlag 1991: through the keys, C¹ with the closed-form
//! tangent), Kochanek–Bartels (1984: all zero is Catmull–Rom; tension, continuity and bias
//! give the tangents of their eq. 8–9; local control), Shoemake's Bézier (1985: C¹ in the
//! parameter, G¹ with uneven times) and the C² spline (continuous angular acceleration,
//! SciPy's `RotationSpline`; `scipy.rs` compares with SciPy itself).
//!
//! Derivatives are one-sided finite differences of the rotation vector relative to the
//! key, `g(s) = 2 log(q_k* q(t_k + s))`, whose first and second derivatives at 0 are the
//! body angular velocity and acceleration: second-order formulas with step 1e-4 (velocity)
//! and 1e-3 (acceleration).

mod c2;
mod scipy;
mod tcb;

use chasles::interp::{
    interpolate, Bezier, C2Spline, CatmullRom, Hemisphere, KeyFrames, KochanekBartels, Method, Tcb,
    Timing,
};
use chasles::{EulerOrder, Quat, Real, Vec3};

/// A curve evaluated at `h` into an interval.
pub trait Eval<T: Real> {
    fn at(&self, interval: usize, h: T) -> Quat<T>;
}
impl<T: Real> Eval<T> for CatmullRom<T> {
    fn at(&self, i: usize, h: T) -> Quat<T> {
        self.eval(i, h)
    }
}
impl<T: Real> Eval<T> for KochanekBartels<T> {
    fn at(&self, i: usize, h: T) -> Quat<T> {
        self.eval(i, h)
    }
}
impl<T: Real> Eval<T> for Bezier<T> {
    fn at(&self, i: usize, h: T) -> Quat<T> {
        self.eval(i, h)
    }
}
impl<T: Real> Eval<T> for C2Spline<T> {
    fn at(&self, i: usize, h: T) -> Quat<T> {
        self.eval(i, h)
    }
}
/// Slerp interval by interval, the control that is not C¹.
pub struct Piecewise(pub Vec<Quat<f64>>);
impl Eval<f64> for Piecewise {
    fn at(&self, i: usize, h: f64) -> Quat<f64> {
        chasles::interp::slerp::slerp(self.0[i], self.0[i + 1], h)
    }
}

/// Table 5.1 (Dam et al.), the report's six keys.
pub fn table<T: Real>() -> Vec<Quat<T>> {
    chasles::interp::examples::table_5_1().keys()
}

/// Seven keys off any one plane, from Euler angles.
pub fn wild<T: Real>() -> Vec<Quat<T>> {
    [
        [0.1, 0.2, 0.3],
        [0.9, -0.4, 1.2],
        [1.7, 0.3, 0.2],
        [2.0, 1.1, -0.7],
        [1.2, 1.4, -1.9],
        [0.3, 0.6, -2.6],
        [-0.4, 0.1, -2.0],
    ]
    .iter()
    .map(|a| Quat::from_euler(EulerOrder::DAM, a.map(T::from_f64)))
    .collect()
}

/// Uneven key times for `n` keys.
pub fn uneven(n: usize) -> Vec<f64> {
    let steps = [1.0, 2.5, 0.6, 1.7, 0.9, 3.0, 1.2];
    let mut t = vec![0.3];
    for i in 1..n {
        t.push(t[i - 1] + steps[(i - 1) % steps.len()]);
    }
    t
}

pub fn keys<T: Real>(q: &[Quat<T>], times: Option<&[f64]>) -> KeyFrames<T> {
    let t: Option<Vec<T>> = times.map(|t| t.iter().map(|v| T::from_f64(*v)).collect());
    KeyFrames::new(q, t.as_deref(), Hemisphere::Chain).unwrap()
}

pub fn spans(kf: &KeyFrames<f64>) -> Vec<f64> {
    (0..kf.len() - 1).map(|i| kf.span(i)).collect()
}

/// `2 log(p* q)`: the rotation vector from p to q (body frame of p).
pub fn rotvec(p: Quat<f64>, q: Quat<f64>) -> Vec3<f64> {
    let d = p.conjugate() * q;
    let d = if d.w < 0.0 { -d } else { d };
    d.log().unwrap().vector() * 2.0
}

/// The curve at `s` from key `k` (s < 0: in interval k − 1).
fn near(c: &impl Eval<f64>, span: &[f64], k: usize, s: f64) -> Quat<f64> {
    if s < 0.0 {
        c.at(k - 1, 1.0 + s / span[k - 1])
    } else {
        c.at(k, s / span[k])
    }
}

/// The body angular velocity at key `k` from the left and from the right.
pub fn velocity_sides(c: &impl Eval<f64>, span: &[f64], k: usize) -> (Vec3<f64>, Vec3<f64>) {
    let d = 1e-4;
    let q = near(c, span, k, 0.0);
    let g = |s: f64| rotvec(q, near(c, span, k, s));
    let left = (g(-d) * -4.0 + g(-2.0 * d)) / (2.0 * d);
    let right = (g(d) * 4.0 - g(2.0 * d)) / (2.0 * d);
    (left, right)
}

/// The body angular acceleration at key `k` from the left and from the right.
pub fn acceleration_sides(c: &impl Eval<f64>, span: &[f64], k: usize) -> (Vec3<f64>, Vec3<f64>) {
    let d = 1e-3;
    let q = near(c, span, k, 0.0);
    let g = |s: f64| rotvec(q, near(c, span, k, s));
    let side = |e: f64| (g(e) * -5.0 + g(2.0 * e) * 4.0 - g(3.0 * e)) / (d * d);
    (side(-d), side(d))
}

/// The largest velocity jump over the inner keys.
pub fn largest_velocity_jump(c: &impl Eval<f64>, span: &[f64]) -> f64 {
    (1..span.len())
        .map(|k| {
            let (l, r) = velocity_sides(c, span, k);
            (l - r).norm()
        })
        .fold(0.0, f64::max)
}

/// The largest acceleration jump over the inner keys.
pub fn largest_acceleration_jump(c: &impl Eval<f64>, span: &[f64]) -> f64 {
    (1..span.len())
        .map(|k| {
            let (l, r) = acceleration_sides(c, span, k);
            (l - r).norm()
        })
        .fold(0.0, f64::max)
}

/// `|p ∓ q|∞`, the sign that is closer.
pub fn diff<T: Real>(p: Quat<T>, q: Quat<T>) -> f64 {
    let a = (p - q).to_array().map(|v| v.to_f64().abs());
    let b = (p + q).to_array().map(|v| v.to_f64().abs());
    a.iter()
        .fold(0.0f64, |m, v| m.max(*v))
        .min(b.iter().fold(0.0f64, |m, v| m.max(*v)))
}

/// The curve passes through every key: `eval(i, 0) = q_i`, `eval(i, 1) = q_{i+1}`.
pub fn through_keys<T: Real>(c: &impl Eval<T>, q: &[Quat<T>], tol: f64) {
    for i in 0..q.len() - 1 {
        assert!(diff(c.at(i, T::ZERO), q[i]) <= tol, "key {i}");
        assert!(diff(c.at(i, T::ONE), q[i + 1]) <= tol, "key {}", i + 1);
    }
}

/// Keys about one axis `n` with these angles (radians).
pub fn about_axis(angles: &[f64]) -> (Vec<Quat<f64>>, Vec3<f64>) {
    let n = Vec3::new(1.0, -2.0, 2.0) / 3.0;
    (
        angles
            .iter()
            .map(|a| Quat::from_axis_angle(n, *a).unwrap())
            .collect(),
        n,
    )
}

/// The cubic Hermite segment `p(h)` with end values and tangents per unit of h.
pub fn hermite(p0: f64, m0: f64, p1: f64, m1: f64, h: f64) -> f64 {
    let (h2, h3) = (h * h, h * h * h);
    (2.0 * h3 - 3.0 * h2 + 1.0) * p0
        + (h3 - 2.0 * h2 + h) * m0
        + (-2.0 * h3 + 3.0 * h2) * p1
        + (h3 - h2) * m1
}

#[test]
fn catmull_rom_passes_through_the_keys_and_is_c1() {
    for times in [None, Some(uneven(6))] {
        let kf = keys(&table::<f64>(), times.as_deref());
        let cr = CatmullRom::new(&kf).unwrap();
        through_keys(&cr, kf.quats(), 1e-15);
        let span = spans(&kf);
        let jump = largest_velocity_jump(&cr, &span);
        // The tangent of the module docs, from both sides.
        let (leave, arrive) = (cr.leaving(), cr.arriving());
        let mut off = 0.0f64;
        for k in 1..kf.len() - 1 {
            let (l, r) = velocity_sides(&cr, &span, k);
            off = off.max((l - arrive[k]).norm()).max((r - leave[k]).norm());
            assert!((leave[k] - arrive[k]).norm() < 1e-14);
        }
        let slerp = largest_velocity_jump(&Piecewise(kf.quats().to_vec()), &span);
        println!(
            "Catmull-Rom, times {:?}: velocity jump at the keys {jump:.1e} (Slerp {slerp:.2}), closed-form tangent within {off:.1e}",
            times.is_some()
        );
        assert!(jump < 1e-6, "{jump}");
        assert!(off < 1e-6, "{off}");
        assert!(slerp > 0.5);
    }
}

#[test]
fn catmull_rom_about_one_axis_is_the_scalar_spline() {
    let angles = [0.2, 1.1, 0.7, 2.9, 3.6, 3.1];
    // Spans within a factor 2 of their neighbours: the construction's outer points stay
    // within a half turn (in 4D) of A₂ (see the module docs' limits).
    for times in [None, Some(vec![0.0, 1.0, 1.8, 3.0, 3.7, 5.0])] {
        let (q, n) = about_axis(&angles);
        let kf = keys(&q, times.as_deref());
        let cr = CatmullRom::new(&kf).unwrap();
        let span = spans(&kf);
        // Barry–Goldman's tangent: the parabola through three keys; chords at the ends.
        let chord = |i: usize| (angles[i + 1] - angles[i]) / span[i];
        let m = |k: usize| {
            if k == 0 {
                return chord(0);
            }
            if k == angles.len() - 1 {
                return chord(k - 1);
            }
            let (a, b) = (span[k - 1], span[k]);
            (b * chord(k - 1) + a * chord(k)) / (a + b)
        };
        let mut worst = 0.0f64;
        for i in 0..span.len() {
            for j in 0..=10 {
                let h = j as f64 / 10.0;
                let a = hermite(
                    angles[i],
                    m(i) * span[i],
                    angles[i + 1],
                    m(i + 1) * span[i],
                    h,
                );
                worst = worst.max(diff(cr.eval(i, h), Quat::from_axis_angle(n, a).unwrap()));
            }
        }
        assert!(worst < 1e-12, "{times:?} {worst}");
        let bz = Bezier::new(&kf).unwrap();
        if times.is_none() {
            // Shoemake's Bézier is the same curve on one great circle (uniform knots).
            let mut b = 0.0f64;
            for i in 0..span.len() {
                for j in 0..=10 {
                    let h = j as f64 / 10.0;
                    b = b.max(diff(bz.eval(i, h), cr.eval(i, h)));
                }
            }
            assert!(b < 1e-12, "{b}");
        }
    }
}

#[test]
fn two_keys_give_slerp() {
    let q = [
        Quat::from_euler(EulerOrder::DAM, [0.1, 0.2, 0.3]),
        Quat::from_euler(EulerOrder::DAM, [1.4, -0.5, 2.0]),
    ];
    let kf = keys(&q, Some(&[0.0, 2.5]));
    let slerp = |h| chasles::interp::slerp::slerp(kf.quats()[0], kf.quats()[1], h);
    let curves: Vec<Box<dyn Fn(f64) -> Quat<f64>>> = vec![
        Box::new({
            let c = CatmullRom::new(&kf).unwrap();
            move |h| c.eval(0, h)
        }),
        Box::new({
            let c = KochanekBartels::new(&kf, Tcb::CATMULL_ROM).unwrap();
            move |h| c.eval(0, h)
        }),
        Box::new({
            let c = Bezier::new(&kf).unwrap();
            move |h| c.eval(0, h)
        }),
        Box::new({
            let c = C2Spline::new(&kf).unwrap();
            move |h| c.eval(0, h)
        }),
    ];
    for (k, c) in curves.iter().enumerate() {
        for j in 0..=20 {
            let h = j as f64 / 20.0;
            assert!(diff(c(h), slerp(h)) < 1e-12, "curve {k} at {h}");
        }
    }
}

#[test]
fn bezier_is_c1_in_the_parameter_and_g1_with_uneven_times() {
    let kf = keys(&wild::<f64>(), None);
    let bz = Bezier::new(&kf).unwrap();
    through_keys(&bz, kf.quats(), 1e-15);
    let span = spans(&kf);
    let jump = largest_velocity_jump(&bz, &span);
    // The closed form: 6 log(q_n* a_n).
    let mut off = 0.0f64;
    for k in 1..kf.len() - 1 {
        let (l, r) = velocity_sides(&bz, &span, k);
        let want = rotvec(kf.quats()[k], bz.after()[k]) * 3.0;
        off = off.max((l - want).norm()).max((r - want).norm());
    }
    let cr = CatmullRom::new(&kf).unwrap();
    let mut apart = 0.0f64;
    for i in 0..span.len() {
        for j in 0..=20 {
            let h = j as f64 / 20.0;
            apart = apart.max(bz.eval(i, h).angle_to(cr.eval(i, h)).unwrap());
        }
    }
    println!(
        "Bezier: velocity jump {jump:.1e}, closed form within {off:.1e}; largest angle from Catmull-Rom {apart:.2e} rad"
    );
    assert!(jump < 1e-6 && off < 1e-6);
    // Not the same curve as Catmull–Rom off one great circle, but close.
    assert!(apart > 1e-4 && apart < 0.1, "{apart}");
    // Uneven times: the direction is continuous, the speed jumps by the spans' ratio.
    let t = uneven(kf.len());
    let kt = keys(&wild::<f64>(), Some(&t));
    let bt = Bezier::new(&kt).unwrap();
    let st = spans(&kt);
    for k in 1..kt.len() - 1 {
        let (l, r) = velocity_sides(&bt, &st, k);
        assert!((l * st[k - 1] - r * st[k]).norm() < 1e-6, "key {k}");
    }
}

#[test]
fn every_curve_in_f32_follows_f64() {
    let methods = [
        Method::CatmullRom,
        Method::KochanekBartels(Tcb {
            tension: 0.3,
            continuity: -0.2,
            bias: 0.5,
        }),
        Method::Bezier,
        Method::C2,
    ];
    for m in methods {
        for times in [None, Some(uneven(7))] {
            let k64 = keys(&wild::<f64>(), times.as_deref());
            let k32 = keys(&wild::<f32>(), times.as_deref());
            let a = interpolate(m, &k64, 120, Timing::Angle).unwrap();
            let b = interpolate(m, &k32, 120, Timing::Angle).unwrap();
            let worst = a
                .iter()
                .zip(&b)
                .map(|(x, y)| diff(x.q, y.q.cast::<f64>()))
                .fold(0.0, f64::max);
            assert!(worst < 2e-5, "{m:?}: {worst}");
            for (f, k) in b.iter().filter_map(|f| f.key.map(|k| (f, k))) {
                assert!(diff(f.q, k32.quats()[k]) == 0.0);
            }
        }
    }
}

#[test]
fn no_panics_on_awkward_keys() {
    let q = Quat::from_euler(EulerOrder::DAM, [0.3, -0.2, 0.9]);
    let turn = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), core::f64::consts::PI).unwrap();
    let near_turn =
        Quat::from_axis_angle(Vec3::new(0.0, 1.0, 1.0), core::f64::consts::PI - 1e-5).unwrap();
    type Set = (Vec<Quat<f64>>, Option<Vec<f64>>, Hemisphere);
    let sets: Vec<Set> = vec![
        (vec![q, q, q, q], None, Hemisphere::Chain),
        (vec![q, -q, q], None, Hemisphere::AsGiven),
        (
            vec![Quat::identity(), turn, Quat::identity(), turn],
            None,
            Hemisphere::Chain,
        ),
        (
            vec![Quat::identity(), near_turn, turn * near_turn],
            None,
            Hemisphere::AsGiven,
        ),
        (
            table(),
            Some(vec![0.0, 1e-300, 2e-300, 1.0, 1e300, 2e300]),
            Hemisphere::Chain,
        ),
        (
            table(),
            Some(vec![0.0, 1e-9, 1.0, 2.0, 3.0, 1e9]),
            Hemisphere::Chain,
        ),
    ];
    let methods = [
        Method::CatmullRom,
        Method::KochanekBartels(Tcb {
            tension: -1.0,
            continuity: 1.0,
            bias: -1.0,
        }),
        Method::Bezier,
        Method::C2,
    ];
    for (q, t, hemi) in &sets {
        let kf = KeyFrames::new(q, t.as_deref(), *hemi).unwrap();
        for m in methods {
            match interpolate(m, &kf, 40, Timing::Uniform) {
                Ok(f) => assert!(f.iter().all(|f| f.q.is_finite())),
                Err(e) => println!("{m:?} on {} keys: {e}", q.len()),
            }
        }
    }
    // Coincident keys stay put.
    let kf = KeyFrames::new(&[q, q, q], None, Hemisphere::Chain).unwrap();
    for m in methods {
        for f in interpolate(m, &kf, 30, Timing::Uniform).unwrap() {
            assert!(diff(f.q, q) < 1e-15, "{m:?}");
        }
    }
}
