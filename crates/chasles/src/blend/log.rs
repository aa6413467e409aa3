//! *Log*: log-matrix blending (Alexa 2002), `exp(Σ wᵢ log Mᵢ)`, and its iterative version
//! (Kavan et al. 2006, §5 and Appendix B).
//!
//! For rigid matrices log and exp have closed forms (Murray, Li & Sastry 1994; the
//! "Rodrigues formula" of §5). A rigid `M = [R t; 0 1]` has the logarithm `[Ŵ v; 0 0]`, a
//! *twist* `(ω, v)`: ω the rotation vector of R (angle θ = ‖ω‖ ∈ [0, π]), and
//! `v = V⁻¹ t` with `V = I + B Ŵ + C Ŵ²`, `A = sin θ/θ`, `B = (1 − cos θ)/θ²`,
//! `C = (θ − sin θ)/θ³`, `V⁻¹ = I − ½ Ŵ + D Ŵ²`, `D = (1 − θ sin θ / (2(1 − cos θ)))/θ²`;
//! `exp` gives `R = I + A Ŵ + B Ŵ²`, `t = V v`. Each coefficient is evaluated by its
//! Taylor series for small θ, so there is no 0/0.
//!
//! Alexa's blend is coordinate invariant but neither bi-invariant, constant speed
//! (Appendix B) nor shortest path (Bloom et al. 2004: it blends axis–angle vectors, so two
//! rotations by ±170° blend through 0°, the long way). The iterative version of §5 — DIB's
//! loop with matrices, starting at the identity: `x = Σ wᵢ log(b⁻¹ Mᵢ)`, `b ← b exp(x)` —
//! equals Alexa's blend after one iteration. §5 says it then converges to the
//! constant-speed, shortest-path blend; measured, that holds only when Alexa's blend is on
//! the short side — see [`log_blend_iterative`].

use super::weights::convex_weights;
use crate::real::{atan2_over, sinc};
use crate::{Mat3, Mat4, Quat, Real, Result, Vec3};

/// A twist `(ω, v)`: the logarithm of a rigid 4×4 matrix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Twist<T> {
    /// Rotation vector (axis × angle).
    pub w: Vec3<T>,
    /// Translational part `V⁻¹ t`.
    pub v: Vec3<T>,
}

impl<T: Real> Twist<T> {
    /// `‖(ω, v)‖`, the Euclidean norm of the six numbers.
    pub fn norm(&self) -> T {
        (self.w.norm_squared() + self.v.norm_squared()).sqrt()
    }
}

fn series<T: Real>(t2: T, c: &[f64]) -> T {
    c.iter()
        .rev()
        .fold(T::ZERO, |a, k| a * t2 + T::from_f64(*k))
}

/// (B, C) = ((1 − cos θ)/θ², (θ − sin θ)/θ³), by series below θ = 1e-2.
fn coeffs_bc<T: Real>(theta: T) -> (T, T) {
    let t2 = theta * theta;
    if theta < T::from_f64(1e-2) {
        (
            series(t2, &[0.5, -1.0 / 24.0, 1.0 / 720.0]),
            series(t2, &[1.0 / 6.0, -1.0 / 120.0, 1.0 / 5040.0]),
        )
    } else {
        let (sn, cs) = theta.sin_cos();
        ((T::ONE - cs) / t2, (theta - sn) / (t2 * theta))
    }
}

/// The logarithm of a rigid matrix (not checked: see [`super::check_rigid`]).
///
/// R's unit quaternion `q = [cos θ/2, sin θ/2 n]` (Shepperd's method, normalized, `w ≥ 0`)
/// gives `ω = 2 atan2(‖v‖, w) v/‖v‖` and, in `D`, `θ sin θ / (2(1 − cos θ)) = (θ/2)
/// cot(θ/2) = (θ/2) w/‖v‖`: no logarithm, sine or cosine beyond the one arctangent (a
/// joint's twist in 1.4× less time than through `to_rotation_vector` and `sin_cos`).
pub fn log_rigid<T: Real>(m: &Mat4<T>) -> Result<Twist<T>> {
    let q = Quat::from_rotation_matrix_unchecked(&m.linear_part());
    let v = q.vector();
    let s = v.norm();
    let w = v * (atan2_over(s, q.w) * T::TWO);
    let theta = w.norm();
    let t = m.translation();
    let d = if theta < T::from_f64(1e-2) {
        series(theta * theta, &[1.0 / 12.0, 1.0 / 720.0, 1.0 / 30240.0])
    } else {
        // θ ≥ 1e-2, so ‖v‖ = sin(θ/2) > 0.
        (T::ONE - theta * T::HALF * q.w / s) / (theta * theta)
    };
    let wt = w.cross(t);
    let v = t - wt * T::HALF + w.cross(wt) * d;
    Ok(Twist { w, v })
}

/// The rigid matrix `exp(ω, v)`.
pub fn exp_twist<T: Real>(x: &Twist<T>) -> Mat4<T> {
    let w = x.w;
    let theta = w.norm();
    let a = sinc(theta);
    let (b, c) = coeffs_bc(theta);
    // R = I + A Ŵ + B Ŵ², Ŵ² = ωωᵀ − θ² I.
    let t2 = theta * theta;
    let mut r = Mat3::identity();
    let wv = w.to_array();
    for (i, row) in r.m.iter_mut().enumerate() {
        for (j, e) in row.iter_mut().enumerate() {
            let hat = match (i, j) {
                (0, 1) => -wv[2],
                (0, 2) => wv[1],
                (1, 0) => wv[2],
                (1, 2) => -wv[0],
                (2, 0) => -wv[1],
                (2, 1) => wv[0],
                _ => T::ZERO,
            };
            let sq = wv[i] * wv[j] - if i == j { t2 } else { T::ZERO };
            *e += a * hat + b * sq;
        }
    }
    let wv_ = w.cross(x.v);
    let t = x.v + wv_ * b + w.cross(wv_) * c;
    Mat4::from_rotation_translation(&r, t)
}

/// The inverse of a rigid matrix, `[Rᵀ −Rᵀt; 0 1]`.
pub fn inverse_rigid<T: Real>(m: &Mat4<T>) -> Mat4<T> {
    let rt = m.linear_part().transpose();
    Mat4::from_rotation_translation(&rt, -rt.mul_vec(m.translation()))
}

/// Alexa's log-matrix blend `exp(Σ wᵢ log Mᵢ)` of rigid matrices.
pub fn log_blend<T: Real>(m: &[Mat4<T>], w: &[T]) -> Result<Mat4<T>> {
    let w = convex_weights(w, m.len())?;
    let mut sum = Twist {
        w: Vec3::zero(),
        v: Vec3::zero(),
    };
    for (mi, wi) in m.iter().zip(&w) {
        let l = log_rigid(mi)?;
        sum.w += l.w * *wi;
        sum.v += l.v * *wi;
    }
    Ok(exp_twist(&sum))
}

/// The iterative log-matrix blend of §5 from the identity: the result and the number of
/// updates. The first update is Alexa's blend.
///
/// Started at the identity, the loop converges to *a* fixed point of
/// `Σ wᵢ log(b⁻¹ Mᵢ) = 0`, and that can be the long way round: for rotations by ±170°
/// about one axis, Alexa's first step lands on the identity and stays there. The
/// constant-speed, shortest-path blend is reached when Alexa's blend is on the short
/// side; [`log_blend_iterative_from`] with the heaviest input as the start reaches it
/// whenever the inputs are within a half turn of it (see
/// `chasles_paper::claims::log_iter_reaches_sclerp`).
pub fn log_blend_iterative<T: Real>(
    m: &[Mat4<T>],
    w: &[T],
    precision: T,
    max_iterations: usize,
) -> Result<(Mat4<T>, usize)> {
    log_blend_iterative_from(m, w, Mat4::identity(), precision, max_iterations)
}

/// The iterative log-matrix blend from a given rigid start.
pub fn log_blend_iterative_from<T: Real>(
    m: &[Mat4<T>],
    w: &[T],
    start: Mat4<T>,
    precision: T,
    max_iterations: usize,
) -> Result<(Mat4<T>, usize)> {
    let w = convex_weights(w, m.len())?;
    let mut b = start;
    let mut steps = 0;
    let mut last = T::from_f64(f64::INFINITY);
    while steps < max_iterations {
        let binv = inverse_rigid(&b);
        let mut x = Twist {
            w: Vec3::zero(),
            v: Vec3::zero(),
        };
        for (mi, wi) in m.iter().zip(&w) {
            let l = log_rigid(&(binv * *mi))?;
            x.w += l.w * *wi;
            x.v += l.v * *wi;
        }
        let norm = x.norm();
        let norm = super::finite_update(
            norm,
            "the log-iter update (the inputs overflow its squares)",
        )?;
        if !super::keep_going(norm, last, precision) {
            break;
        }
        last = norm;
        b = b * exp_twist(&x);
        steps += 1;
    }
    Ok((b, steps))
}
