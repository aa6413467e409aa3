//! Discrete local curvature and curvature energy of a quaternion frame sequence (Dam et
//! al. 1998, §6.3.4 Definition 20 and §6.3.7, eq. 6.23–6.26, 6.43).
//!
//! * Second difference `q''_i = (q_{i−1} − 2q_i + q_{i+1}) / l_i²` (eq. 6.26).
//! * Local curvature `κ̃_i = q''_i − (q''_i · q_i / q_i · q_i) q_i` (eq. 6.25): the part of
//!   q'' tangent to the sphere (a great arc has none).
//! * Energy `E = Σ_i l_i ‖κ̃_i‖²` over the interior frames (eq. 6.23), with the parameter
//!   width `l_i` either 1 (eq. 6.43, what the report's Spring uses), the centred chord
//!   average `(‖q_i − q_{i−1}‖ + ‖q_i − q_{i+1}‖)/2` (eq. 6.24), or the same average of
//!   the angles `θ` between neighbours, `cos θ = q_i · q_{i+1} / (‖q_i‖ ‖q_{i+1}‖)` (the
//!   note after eq. 6.24), taken as `atan2(‖p‖, cos θ)` with `p` the part of one unit
//!   frame orthogonal to the other, so that near-equal frames keep their digits; its
//!   derivative in `b` is `−p / (‖p‖ ‖b‖)` (zero for equal frames).
//!
//! [`term_gradient`] gives the gradient of one energy term with respect to its three
//! frames, the building block of the report's eq. 6.29–6.39. It is organized by term
//! rather than by frame, which is the same sum: writing `u = q_{i−1} − 2q_i + q_{i+1}` and
//! `S = ‖u‖² − (u·q_i)²/(q_i·q_i)`, the term is `S / l³`, so
//! `∂/∂u = 2Pu / l³` (P the projection off q_i), `∂/∂q_i` gains
//! `(−2(u·q_i) u/(q_i·q_i) + 2(u·q_i)² q_i/(q_i·q_i)²) / l³`, and `∂l` contributes
//! `−3S/l⁴ ∂l` (eq. 6.31–6.33; zero for l = 1).

use crate::{Quat, Real};

/// The parameter width `l_i` of eq. 6.23.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Width {
    /// `l = 1` (eq. 6.43): the report's final choice.
    #[default]
    Unit,
    /// The centred chord average (eq. 6.24).
    Centered,
    /// The centred average of the angles between neighbours (the note after eq. 6.24).
    Angle,
}

/// The angle between `a` and `b` as 4-vectors, and its gradient with respect to `b`
/// (zero where the frames are parallel or one is zero).
fn angle_between<T: Real>(a: Quat<T>, b: Quat<T>) -> (T, Quat<T>) {
    let (na, nb) = (a.norm(), b.norm());
    if na == T::ZERO || nb == T::ZERO {
        return (T::ZERO, Quat::zero());
    }
    let (ua, ub) = (a / na, b / nb);
    let c = ua.dot(ub);
    let p = ua - ub * c;
    let s = p.norm();
    let g = if s > T::ZERO {
        -p / (s * nb)
    } else {
        Quat::zero()
    };
    (s.atan2(c), g)
}

fn width<T: Real>(a: Quat<T>, b: Quat<T>, c: Quat<T>, w: Width) -> T {
    match w {
        Width::Unit => T::ONE,
        Width::Centered => ((b - a).norm() + (b - c).norm()) * T::HALF,
        Width::Angle => (angle_between(a, b).0 + angle_between(c, b).0) * T::HALF,
    }
}

/// κ̃ at the middle frame b of (a, b, c) (eq. 6.25–6.26). Zero for zero width or zero b.
pub fn local_curvature<T: Real>(a: Quat<T>, b: Quat<T>, c: Quat<T>, w: Width) -> Quat<T> {
    let l = width(a, b, c, w);
    let bb = b.dot(b);
    if l == T::ZERO || bb == T::ZERO {
        return Quat::zero();
    }
    let dd = (a - b * T::TWO + c) / (l * l);
    dd - b * (dd.dot(b) / bb)
}

/// The local curvature ‖κ̃_i‖ of every interior frame.
pub fn curvatures<T: Real>(frames: &[Quat<T>], w: Width) -> Vec<T> {
    frames
        .windows(3)
        .map(|f| local_curvature(f[0], f[1], f[2], w).norm())
        .collect()
}

/// The total curvature energy `E = Σ l_i ‖κ̃_i‖²` (eq. 6.23) over the interior frames.
pub fn curvature_energy<T: Real>(frames: &[Quat<T>], w: Width) -> T {
    frames.windows(3).fold(T::ZERO, |acc, f| {
        let k = local_curvature(f[0], f[1], f[2], w);
        acc + width(f[0], f[1], f[2], w) * k.dot(k)
    })
}

/// One energy term `l ‖κ̃‖²` at b and its gradient with respect to (a, b, c).
pub fn term_gradient<T: Real>(a: Quat<T>, b: Quat<T>, c: Quat<T>, w: Width) -> (T, [Quat<T>; 3]) {
    let zero = Quat::zero();
    let bb = b.dot(b);
    let (d1, d2) = (b - a, b - c);
    let (n1, n2) = (d1.norm(), d2.norm());
    let l = match w {
        Width::Unit => T::ONE,
        Width::Centered => (n1 + n2) * T::HALF,
        Width::Angle => width(a, b, c, w),
    };
    if l == T::ZERO || bb == T::ZERO {
        return (T::ZERO, [zero; 3]);
    }
    let u = a - b * T::TWO + c;
    let ub = u.dot(b);
    let s = u.dot(u) - ub * ub / bb;
    let l3 = l * l * l;
    let pu = (u - b * (ub / bb)) * T::TWO; // ∂S/∂u
    let ds_db = u * (-T::TWO * ub / bb) + b * (T::TWO * ub * ub / (bb * bb));
    let mut ga = pu / l3;
    let mut gb = (pu * (-T::TWO) + ds_db) / l3;
    let mut gc = pu / l3;
    if w == Width::Angle {
        // ∂l = (∂θ(a, b) + ∂θ(c, b)) / 2 in each of a, b, c.
        let f = -T::from_i32(3) * s / (l3 * l) * T::HALF;
        let (_, ab_b) = angle_between(a, b);
        let (_, ab_a) = angle_between(b, a);
        let (_, cb_b) = angle_between(c, b);
        let (_, cb_c) = angle_between(b, c);
        ga += ab_a * f;
        gb += (ab_b + cb_b) * f;
        gc += cb_c * f;
    }
    if w == Width::Centered {
        let f = -T::from_i32(3) * s / (l3 * l);
        let e1 = if n1 > T::ZERO {
            d1 / (n1 * T::TWO)
        } else {
            zero
        };
        let e2 = if n2 > T::ZERO {
            d2 / (n2 * T::TWO)
        } else {
            zero
        };
        ga += -e1 * f;
        gb += (e1 + e2) * f;
        gc += -e2 * f;
    }
    (s / l3, [ga, gb, gc])
}
