//! *ScLERP*: screw linear interpolation, `ScLERP(t; p̂, q̂) = p̂ (p̂* q̂)^t` (Kavan et al. 2006,
//! §4). The generalization of Slerp to rigid motions: a screw motion about a fixed axis
//! (shortest path) turning and sliding linearly in t (constant speed), bi-invariant
//! (Lemma 2). Only for two transforms.
//!
//! The shorter screw is taken: when `⟨p0, q0⟩ < 0`, −q̂ (the same transformation) is used,
//! so the rotation never exceeds π. At exactly π the two screws are equally short and the
//! one of q̂ as given is used: the result is defined on every input (nalgebra's `sclerp`
//! returns `None` there).
//!
//! Evaluation ([`sclerp`]): by the principle of transference, Slerp's identity
//! `p (p* q)^t = p sin((1 − t)Ω)/sin Ω + q sin(tΩ)/sin Ω` holds for unit dual quaternions
//! with the dual angle `cos Ω̂ = ⟨p̂, q̂⟩ = x + ε xε`, `xε = ⟨p0, qε⟩ + ⟨pε, q0⟩`. Writing
//! the weights as dual numbers `a(Ω̂) = a(Ω) + ε a'(Ω) Ωε` with `Ωε = −xε / sin Ω`, the blend is
//! `real = a p0 + b q0`, `dual = a pε + b qε + Ωε (a' p0 + b' q0)` — two dot products and
//! a handful of scalars, no dual-quaternion products, one inverse trigonometric function and
//! one `sin_cos`. Below Ω = 0.01 the weights and their derivatives come from their Taylor
//! series in Ω (`sin(tΩ)/sin Ω = t(1 + c₁Ω² + c₂Ω⁴ + c₃Ω⁶)`), so a pure translation (Ω = 0)
//! is exact. [`sclerp_pow`] is the definition itself, through the dual power.

use crate::{DualQuat, Real, Result};

/// ScLERP through the definition `p̂ (p̂* q̂)^t` (the general dual-quaternion power).
pub fn sclerp_pow<T: Real>(p: DualQuat<T>, q: DualQuat<T>, t: T) -> Result<DualQuat<T>> {
    let rel = (p.conjugate() * q).to_positive_hemisphere();
    Ok(p * rel.powf(t)?)
}

/// `sin(tΩ)/sin Ω` and its derivative in Ω, by series (Ω < 0.01).
fn weight_series<T: Real>(t: T, omega: T) -> (T, T) {
    let t2 = t * t;
    let t4 = t2 * t2;
    let c1 = (T::ONE - t2) / T::from_i32(6);
    let c2 = (T::from_i32(7) - T::from_i32(10) * t2 + T::from_i32(3) * t4) / T::from_i32(360);
    let c3 = (T::from_i32(31) - T::from_i32(49) * t2 + T::from_i32(21) * t4
        - T::from_i32(3) * t4 * t2)
        / T::from_i32(15120);
    let o2 = omega * omega;
    let w = t * (T::ONE + o2 * (c1 + o2 * (c2 + o2 * c3)));
    let dw = t * omega * (T::TWO * c1 + o2 * (T::from_i32(4) * c2 + o2 * T::from_i32(6) * c3));
    (w, dw)
}

/// ScLERP from `p` to `q` (unit dual quaternions) at `t`, the shorter way; exact at t = 0
/// and t = 1. Errors: non-finite input.
pub fn sclerp<T: Real>(p: DualQuat<T>, q: DualQuat<T>, t: T) -> Result<DualQuat<T>> {
    // v − v is exactly 0 for every finite v and NaN otherwise: one branch for 17 values;
    // the detailed check, which names the input, runs only when it fails.
    #[allow(clippy::eq_op)] // deliberate: the NaN/∞ probe
    let z = (p.real - p.real) + (p.dual - p.dual) + (q.real - q.real) + (q.dual - q.dual);
    #[allow(clippy::eq_op)]
    let zt = t - t;
    if z.w + z.x + z.y + z.z + zt != T::ZERO {
        crate::error::check_finite("dual quaternion", &p.to_array())?;
        crate::error::check_finite("dual quaternion", &q.to_array())?;
        crate::error::check_finite("interpolation parameter", &[t])?;
    }
    if t == T::ZERO {
        return Ok(p);
    }
    let mut x = p.real.dot(q.real);
    let q = if x < T::ZERO {
        x = -x;
        -q
    } else {
        q
    };
    if t == T::ONE {
        return Ok(q);
    }
    let (p0, pe, q0, qe) = (p.real, p.dual, q.real, q.dual);
    let xe = p0.dot(qe) + pe.dot(q0);
    let g = T::ONE - t;
    // The angle: acos where well conditioned (Ω > 18°), else from the chord
    // ‖p0 − q0‖ = 2 sin(Ω/2).
    let (omega, sin_omega) = if x < T::from_f64(0.95) {
        (x.acos(), (T::ONE - x * x).sqrt())
    } else {
        let d = (p0 - q0).norm();
        let h = (d * T::HALF).min(T::ONE);
        (T::TWO * h.asin(), d * (T::ONE - h * h).max(T::ZERO).sqrt())
    };
    let (a, b, da, db, omega_e);
    if omega < T::from_f64(0.01) {
        let (wa, dwa) = weight_series(g, omega);
        let (wb, dwb) = weight_series(t, omega);
        (a, b, da, db) = (wa, wb, dwa, dwb);
        // At Ω = 0 exactly the derivatives vanish, so Ωε (0/0 there) does not matter.
        omega_e = if sin_omega > T::ZERO {
            -xe / sin_omega
        } else {
            T::ZERO
        };
    } else {
        let inv = T::ONE / sin_omega;
        let (s2, c2) = (t * omega).sin_cos();
        // sin((1 − t)Ω), cos((1 − t)Ω) by the angle difference from Ω and tΩ.
        let s1 = sin_omega * c2 - x * s2;
        let c1 = x * c2 + sin_omega * s2;
        a = s1 * inv;
        b = s2 * inv;
        // d/dΩ [sin(kΩ)/sin Ω] = (k cos(kΩ) − (sin(kΩ)/sin Ω) cos Ω)/sin Ω.
        da = (g * c1 - a * x) * inv;
        db = (t * c2 - b * x) * inv;
        omega_e = -xe * inv;
    }
    let real = p0 * a + q0 * b;
    let dual = pe * a + qe * b + (p0 * da + q0 * db) * omega_e;
    Ok(DualQuat::new(real, dual))
}
