//! A C² rotation spline: cubics in the rotation vectors of the relative rotations, with
//! continuous angular velocity *and* angular acceleration — the construction of SciPy's
//! `RotationSpline` (N. Mayorov, "Smooth attitude interpolation", 2019, the note SciPy's
//! documentation cites), written here from the equations.
//!
//! On interval i (keys `q_i`, `q_{i+1}`, span `Δ_i`) the rotation is
//! `q(t_i + s) = q_i exp(r_i(s)/2)` with the cubic rotation vector
//! `r_i(s) = a_i s³ + b_i s² + ω_i s`, `r_i(Δ_i) = θ_i`, where `θ_i = 2 log(q_i* q_{i+1})` is
//! the rotation vector from key to key (body frame, the keys' signs as given). The body
//! angular velocity of `q_i exp(r/2)` is `ω = B(r) ṙ` with
//! `B(r) = I − (1 − cos ρ)/ρ² [r]× + (ρ − sin ρ)/ρ³ [r]×²` (ρ = ‖r‖) and its inverse
//! `A(r) = I + ½ [r]× + (1 − (ρ/2) cot(ρ/2))/ρ² [r]×²`; the angular acceleration is
//! `α = B(r) r̈ + N(r, ṙ)` with the quadratic term
//! `N = (r·ṙ) (k₁ r × ṙ + k₂ r × (r × ṙ)) + k₃ ṙ × (r × ṙ)`,
//! `k₁ = (2 (1 − cos ρ) − ρ sin ρ)/ρ⁴`, `k₂ = (3 sin ρ − 2ρ − ρ cos ρ)/ρ⁵`,
//! `k₃ = (ρ − sin ρ)/ρ³` (the time derivative of `B(r)` applied to ṙ).
//!
//! The unknowns are the angular velocities `ω_k` at the keys. The segment's Hermite form,
//! `r_i(0) = 0`, `ṙ_i(0) = ω_i`, `r_i(Δ_i) = θ_i`, `ṙ_i(Δ_i) = A(θ_i) ω_{i+1}`, makes ω
//! continuous; continuity of α at each inner key k (from `r̈_{k−1}(Δ_{k−1})` on the left and
//! `r̈_k(0) = 2 b_k` on the right, with `B(θ) θ = θ` and `B A = I`) is the block-tridiagonal
//! system
//!
//! ```text
//! 2 B(θ_{k−1})/Δ_{k−1} ω_{k−1} + 4 (1/Δ_{k−1} + 1/Δ_k) ω_k + 2 A(θ_k)/Δ_k ω_{k+1}
//!     = 6 (θ_{k−1}/Δ_{k−1}² + θ_k/Δ_k²) − N(θ_{k−1}, A(θ_{k−1}) ω_k),
//! ```
//!
//! solved by the block Thomas algorithm (the matrix is block diagonally dominant: ‖A‖ < 1.6
//! and ‖B‖ ≤ 1 for turns up to π) and iterated on the quadratic term until the velocities
//! change by less than 16 ε (relative), at most [`MAX_ITERATIONS`] times. The ends are
//! clamped as SciPy's are: `ω_0 = θ_0/Δ_0`, `ω_N = θ_{N−1}/Δ_{N−1}` (the chords' rates).
//! Then `a_i = (Δ_i (ω_i + ṙ_e) − 2θ_i)/Δ_i³`, `b_i = (3θ_i − Δ_i (2ω_i + ṙ_e))/Δ_i²` with
//! `ṙ_e = A(θ_i) ω_{i+1}`. Two keys give Slerp; keys about one axis give the clamped
//! scalar cubic spline of the angles (A, B and N act as 1, 1 and 0 along the axis).
//!
//! Knots are the key times, or 0, 1, 2, … without them. Keys a full turn apart the long
//! way (q and −q kept as given, [`super::Hemisphere::AsGiven`]) have no rotation vector
//! between them and are an error, as is a system whose iteration does not settle.

use super::KeyFrames;
use crate::real::sinc;
use crate::{Error, Mat3, Quat, Real, Result, Vec3};

/// The most iterations on the quadratic term (SciPy stops at 10 and 1e-9; we go on to
/// rounding, which took 13 and 14 on the tests' seven keys).
pub const MAX_ITERATIONS: usize = 200;

/// A C² spline through key frames (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct C2Spline<T> {
    q: Vec<Quat<T>>,
    span: Vec<T>,
    /// Per interval: `[a, b, ω]` of `r(s) = ((a s + b) s + ω) s`.
    coef: Vec<[Vec3<T>; 3]>,
    /// Angular velocities at the keys.
    omega: Vec<Vec3<T>>,
    iterations: usize,
}

/// `Σ c_k x^k` for `x = ρ²` by Horner, the coefficients from f64.
fn poly<T: Real>(x: T, c: &[f64]) -> T {
    c.iter()
        .rev()
        .fold(T::ZERO, |acc, ck| acc * x + T::from_f64(*ck))
}

fn factorial(n: usize) -> f64 {
    (1..=n).fold(1.0, |a, k| a * k as f64)
}

/// Below this ρ the coefficients come from their series (12 terms: exact to rounding),
/// above it from the closed forms (which lose at most two digits to cancellation there).
const SERIES_BELOW: f64 = 1.0;
const TERMS: usize = 12;

/// The coefficients of the small-ρ series of the functions below, in powers of ρ².
fn series(f: impl Fn(usize) -> f64) -> [f64; TERMS] {
    core::array::from_fn(f)
}

/// `(ρ − sin ρ)/ρ³` = Σ (−1)^k ρ^{2k}/(2k+3)!.
fn k_sin<T: Real>(rho: T) -> T {
    if rho.to_f64() < SERIES_BELOW {
        let c = series(|k| sign(k) / factorial(2 * k + 3));
        poly(rho * rho, &c)
    } else {
        (rho - rho.sin()) / (rho * rho * rho)
    }
}

/// `(1 − cos ρ)/ρ² = ½ sinc²(ρ/2)`.
fn k_cos<T: Real>(rho: T) -> T {
    let s = sinc(rho * T::HALF);
    s * s * T::HALF
}

/// `(1 − (ρ/2) cot(ρ/2))/ρ² = g(ρ/2) / (4 sinc(ρ/2))` with `g(x) = (sin x − x cos x)/x³`
/// = Σ_{k≥1} (−1)^{k+1} 2k x^{2k−2}/(2k+1)!.
fn k_cot<T: Real>(rho: T) -> T {
    let x = rho * T::HALF;
    let g = if x.to_f64() < SERIES_BELOW {
        let c = series(|k| -sign(k + 1) * 2.0 * (k + 1) as f64 / factorial(2 * k + 3));
        poly(x * x, &c)
    } else {
        (x.sin() - x * x.cos()) / (x * x * x)
    };
    g / (T::from_i32(4) * sinc(x))
}

/// `(2 (1 − cos ρ) − ρ sin ρ)/ρ⁴` = Σ_{k≥2} (−1)^k (2k − 2)/(2k)! ρ^{2k−4}.
fn k_n1<T: Real>(rho: T) -> T {
    if rho.to_f64() < SERIES_BELOW {
        let c = series(|j| {
            let k = j + 2;
            sign(k) * (2 * k - 2) as f64 / factorial(2 * k)
        });
        poly(rho * rho, &c)
    } else {
        let r2 = rho * rho;
        (T::TWO * (T::ONE - rho.cos()) - rho * rho.sin()) / (r2 * r2)
    }
}

/// `(3 sin ρ − 2ρ − ρ cos ρ)/ρ⁵` = Σ_{k≥2} (−1)^k (2 − 2k)/(2k+1)! ρ^{2k−4}.
fn k_n2<T: Real>(rho: T) -> T {
    if rho.to_f64() < SERIES_BELOW {
        let c = series(|j| {
            let k = j + 2;
            sign(k) * (2.0 - 2.0 * k as f64) / factorial(2 * k + 1)
        });
        poly(rho * rho, &c)
    } else {
        let r2 = rho * rho;
        (T::from_i32(3) * rho.sin() - T::TWO * rho - rho * rho.cos()) / (r2 * r2 * rho)
    }
}

fn sign(k: usize) -> f64 {
    if k.is_multiple_of(2) {
        1.0
    } else {
        -1.0
    }
}

fn skew<T: Real>(r: Vec3<T>) -> Mat3<T> {
    let z = T::ZERO;
    Mat3::from_rows([[z, -r.z, r.y], [r.z, z, -r.x], [-r.y, r.x, z]])
}

/// `x I + y S + z S²` for `S = [r]×`.
fn combine<T: Real>(r: Vec3<T>, x: T, y: T, z: T) -> Mat3<T> {
    let s = skew(r);
    let s2 = s * s;
    Mat3::from_rows(core::array::from_fn(|i| {
        core::array::from_fn(|j| {
            let id = if i == j { x } else { T::ZERO };
            id + s.m[i][j] * y + s2.m[i][j] * z
        })
    }))
}

/// `B(r)`: rotation-vector rate → body angular velocity.
pub fn rate_to_velocity<T: Real>(r: Vec3<T>) -> Mat3<T> {
    let rho = r.norm();
    combine(r, T::ONE, -k_cos(rho), k_sin(rho))
}

/// `A(r) = B(r)⁻¹`: body angular velocity → rotation-vector rate.
pub fn velocity_to_rate<T: Real>(r: Vec3<T>) -> Mat3<T> {
    let rho = r.norm();
    combine(r, T::ONE, T::HALF, k_cot(rho))
}

/// `N(r, ṙ)`: the quadratic part of the angular acceleration, `α = B(r) r̈ + N(r, ṙ)`.
pub fn quadratic_term<T: Real>(r: Vec3<T>, rd: Vec3<T>) -> Vec3<T> {
    let rho = r.norm();
    let dp = r.dot(rd);
    let cp = r.cross(rd);
    let ccp = r.cross(cp);
    let dccp = rd.cross(cp);
    (cp * k_n1(rho) + ccp * k_n2(rho)) * dp + dccp * k_sin(rho)
}

fn add<T: Real>(a: &Mat3<T>, b: &Mat3<T>, sb: T) -> Mat3<T> {
    Mat3::from_rows(core::array::from_fn(|i| {
        core::array::from_fn(|j| a.m[i][j] + b.m[i][j] * sb)
    }))
}

fn scaled<T: Real>(a: &Mat3<T>, s: T) -> Mat3<T> {
    Mat3::from_rows(a.m.map(|r| r.map(|v| v * s)))
}

fn not_converged(iterations: usize) -> Error {
    Error::NotConverged {
        what: "the C² spline's angular velocities at the keys",
        iterations,
    }
}

impl<T: Real> C2Spline<T> {
    /// The spline through `keys` (module docs). Errors: neighbouring keys a full turn
    /// apart ([`Error::BadKey`] naming the second), an iteration that does not settle
    /// ([`Error::NotConverged`]).
    pub fn new(keys: &KeyFrames<T>) -> Result<Self> {
        let q = keys.quats().to_vec();
        let n = q.len();
        let m = n - 1;
        let span: Vec<T> = (0..m).map(|i| keys.span(i)).collect();
        let mut theta = Vec::with_capacity(m);
        for i in 0..m {
            let t = (q[i].conjugate() * q[i + 1]).log()?.vector() * T::TWO;
            // A(θ) is singular at ‖θ‖ = 2π; a hair short of it the spline is meaningless.
            let rho = t.norm();
            if rho.to_f64() >= 2.0 * core::f64::consts::PI - 1e-6 {
                return Err(Error::BadKey {
                    index: i + 1,
                    source: Box::new(Error::BadParameter {
                        what: "the C² spline's turn from the previous key",
                        rule: "less than a full turn (q and −q kept as given have no rotation vector between them)",
                        value: rho.to_f64(),
                    }),
                });
            }
            theta.push(t);
        }
        let a_mat: Vec<Mat3<T>> = theta.iter().map(|t| velocity_to_rate(*t)).collect();
        let b_mat: Vec<Mat3<T>> = theta.iter().map(|t| rate_to_velocity(*t)).collect();
        let mut omega: Vec<Vec3<T>> = (0..n)
            .map(|k| theta[k.min(m - 1)] / span[k.min(m - 1)])
            .collect();
        omega[n - 1] = theta[m - 1] / span[m - 1];
        let mut iterations = 0;
        if n > 2 {
            iterations = solve(&theta, &span, &a_mat, &b_mat, &mut omega)?;
        }
        let coef = (0..m)
            .map(|i| {
                let d = span[i];
                let re = a_mat[i].mul_vec(omega[i + 1]);
                let a = ((omega[i] + re) * d - theta[i] * T::TWO) / (d * d * d);
                let b = (theta[i] * T::from_i32(3) - (omega[i] * T::TWO + re) * d) / (d * d);
                [a, b, omega[i]]
            })
            .collect();
        Ok(Self {
            q,
            span,
            coef,
            omega,
            iterations,
        })
    }
    /// The keys.
    pub fn keys(&self) -> &[Quat<T>] {
        &self.q
    }
    /// The angular velocities at the keys (body frame, radians per unit of the parameter).
    pub fn key_velocities(&self) -> &[Vec3<T>] {
        &self.omega
    }
    /// How many times the quadratic term was iterated (0 for two keys).
    pub fn iterations(&self) -> usize {
        self.iterations
    }
    fn at(&self, interval: usize, h: T) -> (usize, T) {
        let i = interval.min(self.q.len() - 2);
        (i, h * self.span[i])
    }
    /// `(r, ṙ, r̈)` at `h` into interval i.
    fn rotvec(&self, interval: usize, h: T) -> (usize, Vec3<T>, Vec3<T>, Vec3<T>) {
        let (i, s) = self.at(interval, h);
        let [a, b, w] = self.coef[i];
        let r = ((a * s + b) * s + w) * s;
        let rd = (a * (T::from_i32(3) * s) + b * T::TWO) * s + w;
        let rdd = a * (T::from_i32(6) * s) + b * T::TWO;
        (i, r, rd, rdd)
    }
    /// The curve at `h ∈ [0, 1]` into interval `i` (clamped to the last interval).
    pub fn eval(&self, interval: usize, h: T) -> Quat<T> {
        let (i, r, _, _) = self.rotvec(interval, h);
        self.q[i] * Quat::pure(r * T::HALF).exp()
    }
    /// The angular velocity `B(r) ṙ` (body frame, radians per unit of the parameter).
    pub fn angular_velocity(&self, interval: usize, h: T) -> Vec3<T> {
        let (_, r, rd, _) = self.rotvec(interval, h);
        rate_to_velocity(r).mul_vec(rd)
    }
    /// The angular acceleration `B(r) r̈ + N(r, ṙ)` (body frame).
    pub fn angular_acceleration(&self, interval: usize, h: T) -> Vec3<T> {
        let (_, r, rd, rdd) = self.rotvec(interval, h);
        rate_to_velocity(r).mul_vec(rdd) + quadratic_term(r, rd)
    }
}

/// Iterates the block-tridiagonal system of the module docs for the inner keys' velocities
/// (`omega[0]` and `omega[n−1]` fixed); returns the iterations taken.
fn solve<T: Real>(
    theta: &[Vec3<T>],
    span: &[T],
    a_mat: &[Mat3<T>],
    b_mat: &[Mat3<T>],
    omega: &mut [Vec3<T>],
) -> Result<usize> {
    let n = omega.len();
    let inner = n - 2;
    let two = T::TWO;
    // Row r is key k = r + 1: lower block on ω_{k−1}, diagonal d_k I, upper on ω_{k+1}.
    let lower: Vec<Mat3<T>> = (0..inner)
        .map(|r| scaled(&b_mat[r], two / span[r]))
        .collect();
    let upper: Vec<Mat3<T>> = (0..inner)
        .map(|r| scaled(&a_mat[r + 1], two / span[r + 1]))
        .collect();
    let diag: Vec<T> = (0..inner)
        .map(|r| T::from_i32(4) * (T::ONE / span[r] + T::ONE / span[r + 1]))
        .collect();
    let base: Vec<Vec3<T>> = (0..inner)
        .map(|r| {
            let (d0, d1) = (span[r], span[r + 1]);
            (theta[r] / (d0 * d0) + theta[r + 1] / (d1 * d1)) * T::from_i32(6)
        })
        .collect();
    // Block LU once: m_r = D_r − L_r C_{r−1}, C_r = m_r⁻¹ U_r.
    let mut inv: Vec<Mat3<T>> = Vec::with_capacity(inner);
    let mut c: Vec<Mat3<T>> = Vec::with_capacity(inner);
    for r in 0..inner {
        let d = scaled(&Mat3::identity(), diag[r]);
        let mr = if r == 0 {
            d
        } else {
            add(&d, &(lower[r] * c[r - 1]), -T::ONE)
        };
        let mi = mr.inverse().ok_or(Error::NonFinite {
            what: "the C² spline's system (key times too far apart in scale)",
        })?;
        c.push(mi * upper[r]);
        inv.push(mi);
    }
    let tol = T::EPSILON * T::from_i32(16);
    let mut rhs = vec![Vec3::zero(); inner];
    for iteration in 1..=MAX_ITERATIONS {
        for r in 0..inner {
            let k = r + 1;
            let mut v = base[r] - quadratic_term(theta[r], a_mat[r].mul_vec(omega[k]));
            if r == 0 {
                v -= lower[0].mul_vec(omega[0]);
            }
            if r + 1 == inner {
                v -= upper[r].mul_vec(omega[n - 1]);
            }
            rhs[r] = v;
        }
        // Forward: y_r = m_r⁻¹ (rhs_r − L_r y_{r−1}); back: x_r = y_r − C_r x_{r+1}.
        let mut y: Vec<Vec3<T>> = Vec::with_capacity(inner);
        for r in 0..inner {
            let v = if r == 0 {
                rhs[0]
            } else {
                rhs[r] - lower[r].mul_vec(y[r - 1])
            };
            y.push(inv[r].mul_vec(v));
        }
        let mut change = T::ZERO;
        let mut next = y[inner - 1];
        for r in (0..inner).rev() {
            let x = if r + 1 == inner {
                next
            } else {
                y[r] - c[r].mul_vec(next)
            };
            let old = omega[r + 1];
            let scale = T::ONE + x.x.abs().max(x.y.abs()).max(x.z.abs());
            let d = x - old;
            change = change.max(d.x.abs().max(d.y.abs()).max(d.z.abs()) / scale);
            omega[r + 1] = x;
            next = x;
        }
        if !change.is_finite() || omega.iter().any(|w| !w.is_finite()) {
            return Err(not_converged(iteration));
        }
        if change <= tol {
            return Ok(iteration);
        }
    }
    Err(not_converged(MAX_ITERATIONS))
}
