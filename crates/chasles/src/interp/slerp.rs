//! *Slerp*: spherical linear interpolation (Dam et al. 1998, §6.1.5).
//!
//! * [`slerp_pow`]: eq. 6.4, `Slerp(p, q, h) = p (p* q)^h`, through the quaternion power.
//! * [`slerp`]: eq. 6.13, `(p sin((1 − h)Ω) + q sin(hΩ)) / sin Ω` with `cos Ω = p·q`,
//!   the form without exponentiation. Ω is computed as `2 atan2(‖p − q‖, ‖p + q‖)`, which is
//!   accurate at every angle (unlike `acos(p·q)` near 0), and `sin(hΩ)/sin Ω` is evaluated
//!   as `h · sinc(hΩ)/sinc(Ω)`, so Ω → 0 has no 0/0 (the report's patch
//!   `Slerp(q, q, h) ≡ q` is the limit, not a special case).
//!
//! Both follow the great arc between p and q *as given* (Proposition 29: the shorter arc
//! between the two 4D points). Footnote 7: q and −q are the same rotation, so the shorter
//! *rotation* may be the arc to −q; [`slerp_shortest`] flips q when `p·q < 0`. Antipodal
//! keys (q = −p) have no unique arc: [`slerp`] then turns about an axis perpendicular to p
//! in 4D (any great circle through p and −p is as short), still with unit speed.

use crate::real::sinc;
use crate::{Quat, Real, Result};

/// Eq. 6.4: `p (p* q)^h`. Errors: zero or non-finite inputs.
pub fn slerp_pow<T: Real>(p: Quat<T>, q: Quat<T>, h: T) -> Result<Quat<T>> {
    Ok(p * (p.conjugate() * q).powf(h)?)
}

/// Eq. 6.13 for unit p and q, exact for Ω → 0 and defined for q = −p (see module docs).
#[inline]
pub fn slerp<T: Real>(p: Quat<T>, q: Quat<T>, h: T) -> Quat<T> {
    let d = (p - q).norm();
    let s = (p + q).norm();
    let omega = T::TWO * d.atan2(s);
    if s == T::ZERO {
        // q = −p: every great circle through p and −p has the same length π; turn in the
        // plane of p and a 4D vector perpendicular to it.
        let perp = Quat::new(-p.x, p.w, -p.z, p.y);
        let (sn, cs) = (h * T::PI).sin_cos();
        return p * cs + perp * sn;
    }
    // Divided (not multiplied by a reciprocal) so that h = 0 and h = 1 give p and q exactly.
    let s_omega = sinc(omega);
    let a = (T::ONE - h) * sinc((T::ONE - h) * omega) / s_omega;
    let b = h * sinc(h * omega) / s_omega;
    p * a + q * b
}

/// Slerp along the shorter rotation (footnote 7): uses −q when `p·q < 0`.
#[inline]
pub fn slerp_shortest<T: Real>(p: Quat<T>, q: Quat<T>, h: T) -> Quat<T> {
    let q = if p.dot(q) < T::ZERO { -q } else { q };
    slerp(p, q, h)
}
