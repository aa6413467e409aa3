//! Screw motion: exp, log and powers of dual quaternions, and screw parameters
//! (Kavan et al. 2006, §3, eq. 2 and Figure 2; Chasles' theorem).
//!
//! Every unit dual quaternion is `q̂ = cos(θ̂/2) + ŝ sin(θ̂/2)` (eq. 2), with the dual angle
//! `θ̂ = θ0 + ε θε` and the unit dual vector `ŝ = s0 + ε sε`: a rotation by θ0 about the
//! axis of direction s0 and moment `sε = p × s0` (p any point on the axis), and a
//! translation by θε along it. (The paper's Figure 2 caption says "angle θ0/2" and
//! "translation θε/2"; those are the half quantities the dual quaternion stores — the
//! motion itself turns by θ0 and slides by θε, which is what [`Screw`] reports.)
//!
//! `log q̂ = ŝ θ̂/2`, `exp(ŝ θ̂/2) = q̂`, `q̂^û = exp(û log q̂)` for a real or dual exponent.
//!
//! The functions here work for *any* dual quaternion with a non-zero real part, not only
//! unit ones: the scalar part is a dual number that commutes with everything, so
//! `exp[ŵ, V̂] = e^ŵ [cos‖V̂‖, sinc‖V̂‖ V̂]` and `log q̂ = [ln‖q̂‖, atan2(‖V̂‖, ŵ)/‖V̂‖ · V̂]`
//! are evaluated as dual-number functions of `‖V̂‖² = A·A + 2ε A·B` (V̂ = A + εB). Written
//! in terms of the *squared* dual length, both stay exact for a pure translation (A = 0,
//! where ‖V̂‖ itself has no dual derivative): the derivatives of `sinc√s` and
//! `atan2(√s, w)/√s` in s are evaluated by series near s = 0. Near the rotation angle 2π
//! (q0 ≈ −1) the logarithm is taken of `−q̂` (angle near 0, well conditioned) and turned
//! round: `log q̂ = V̂ − π ŝ` with `V̂ = ŝ φ̂` the vector part of `log(−q̂)`; at exactly
//! q0 = −‖q0‖ the screw axis is taken along the translation (or x when there is none),
//! which `exp` maps back exactly. (Near 2π with a translation *across* the axis the screw
//! axis is genuinely far away — at distance |t⊥|/(2π − θ0) — and so is the log.)

use crate::real::{atan2_over, sinc};
use crate::{Dual, DualQuat, Error, Quat, Real, Result, Vec3};

/// The screw parameters of a rigid motion (Chasles' theorem; Kavan et al. Figure 2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Screw<T> {
    /// Unit direction `s0` of the screw axis.
    pub axis: Vec3<T>,
    /// Moment `sε = p × s0` of the axis (perpendicular to it; zero when the axis passes
    /// through the origin).
    pub moment: Vec3<T>,
    /// Rotation angle θ0 about the axis (radians, counter-clockwise).
    pub angle: T,
    /// Translation θε along the axis.
    pub translation: T,
}

impl<T: Real> Screw<T> {
    /// A screw from its axis direction (normalized here), a point on the axis, the angle and
    /// the translation along the axis. Errors: zero or non-finite axis, non-finite values.
    pub fn from_point(axis: Vec3<T>, point: Vec3<T>, angle: T, translation: T) -> Result<Self> {
        crate::error::check_finite("screw point", &point.to_array())?;
        crate::error::check_finite("screw angle and translation", &[angle, translation])?;
        let axis = axis
            .normalize()
            .map_err(|_| Error::ZeroNorm { what: "screw axis" })?;
        Ok(Self {
            axis,
            moment: point.cross(axis),
            angle,
            translation,
        })
    }
    /// The point of the axis closest to the origin, `s0 × sε`.
    #[inline]
    pub fn point(&self) -> Vec3<T> {
        self.axis.cross(self.moment)
    }
    /// The pitch `θε / θ0` (translation per radian); `None` for a pure translation.
    pub fn pitch(&self) -> Option<T> {
        if self.angle == T::ZERO {
            None
        } else {
            Some(self.translation / self.angle)
        }
    }
}

impl<T: Real> DualQuat<T> {
    /// The exponential of any dual quaternion (for a pure one `ŝ θ̂/2`, eq. 2 gives
    /// `cos(θ̂/2) + ŝ sin(θ̂/2)`). Exact for zero rotation.
    pub fn exp(self) -> Self {
        let a = self.real.vector();
        let b = self.dual.vector();
        let s = a.norm_squared();
        let s_du = T::TWO * a.dot(b);
        let x = s.sqrt();
        let k = sinc(x);
        let cos = Dual::new(x.cos(), -k * T::HALF * s_du);
        let k_hat = Dual::new(k, d_sinc_sqrt(s) * s_du);
        let e = Dual::new(self.real.w, self.dual.w).exp();
        // [cos, k̂ V̂] with V̂ = a + εb, then times the dual scalar e^ŵ.
        let unit = DualQuat::new(
            Quat::from_scalar_vector(cos.re, a * k_hat.re),
            Quat::from_scalar_vector(cos.du, a * k_hat.du + b * k_hat.re),
        );
        unit * e
    }

    /// The logarithm of any dual quaternion with a non-zero real part: for a unit one the
    /// pure dual quaternion `ŝ θ̂/2` with θ0 ∈ [0, 2π] (the principal value for the sign
    /// given; `−q̂` gives the other way round). Errors: zero or non-finite real part, or
    /// non-finite dual part.
    pub fn log(self) -> Result<Self> {
        crate::error::check_finite("dual quaternion", &self.to_array())?;
        let n2 = self.norm_squared();
        if n2.re == T::ZERO {
            return Err(Error::ZeroNorm {
                what: "dual quaternion (real part)",
            });
        }
        if !n2.re.is_finite() {
            // Rescale by a real factor: log(c q̂) = ln c + log q̂.
            let m = self
                .real
                .to_array()
                .iter()
                .fold(T::ZERO, |m, v| m.max(v.abs()));
            let l = (self * (T::ONE / m)).log()?;
            return Ok(DualQuat::new(
                l.real + Quat::new(m.ln(), T::ZERO, T::ZERO, T::ZERO),
                l.dual,
            ));
        }
        let ln_norm = Dual::new(T::HALF * n2.re.ln(), T::HALF * n2.du / n2.re);
        let (w, w_du) = (self.real.w, self.dual.w);
        let a = self.real.vector();
        let b = self.dual.vector();
        let s = a.norm_squared();
        let s_du = T::TWO * a.dot(b);
        let n = s.sqrt();
        if w < T::ZERO {
            // q̂ = −p̂ with p̂ on the w > 0 side, where log p̂ = [ln‖q̂‖, ŝ φ̂] is well
            // conditioned. Since −1 = exp(π ŝ) commutes with exp(ŝ φ̂):
            // log q̂ = [ln‖q̂‖, −ŝ (π − φ̂)] = [ln‖q̂‖, V̂ − π ŝ], ŝ = V̂/‖V̂‖ (dual unit).
            let l = (-self).log()?;
            let (a, b) = (l.real.vector(), l.dual.vector());
            let n = a.norm();
            let (s_re, s_du) = if n > T::ZERO {
                let dir = a / n;
                (dir, (b - dir * dir.dot(b)) / n)
            } else {
                // p̂ is a pure translation: rotation by 2π about any axis; take the
                // translation's direction (or x), with no moment.
                (b.normalize().unwrap_or(Vec3::unit(0)), Vec3::zero())
            };
            return Ok(DualQuat::new(
                Quat::from_scalar_vector(l.real.w, a - s_re * T::PI),
                Quat::from_scalar_vector(l.dual.w, b - s_du * T::PI),
            ));
        }
        let h = atan2_over(n, w);
        let h_s = d_atan2_over_ds(s, w);
        let h_w = -T::ONE / (s + w * w);
        let h_du = h_s * s_du + h_w * w_du;
        let (vr, vd) = (a * h, b * h + a * h_du);
        Ok(DualQuat::new(
            Quat::from_scalar_vector(ln_norm.re, vr),
            Quat::from_scalar_vector(ln_norm.du, vd),
        ))
    }

    /// `q̂^t = exp(t log q̂)`: the screw motion scaled by t (angle and translation × t,
    /// same axis). Errors as for [`DualQuat::log`].
    pub fn powf(self, t: T) -> Result<Self> {
        crate::error::check_finite("exponent", &[t])?;
        Ok((self.log()? * t).exp())
    }

    /// `q̂^û = exp(û log q̂)` with a dual exponent `û = u0 + ε uε`: angle × u0 and
    /// translation × u0 plus uε·angle (Kavan et al. §3). Errors as for [`DualQuat::log`].
    pub fn pow_dual(self, u: Dual<T>) -> Result<Self> {
        crate::error::check_finite("exponent", &[u.re, u.du])?;
        Ok((self.log()? * u).exp())
    }

    /// The screw parameters of a unit dual quaternion (it is normalized first). For a pure
    /// translation the axis is the translation direction (moment 0); for the identity, the
    /// x axis with zero angle and translation. The angle is in [0, 2π] for the sign given;
    /// call [`DualQuat::to_positive_hemisphere`] first for the one in [0, π].
    /// Errors: zero or non-finite input.
    pub fn to_screw(self) -> Result<Screw<T>> {
        let unit = self.normalize()?;
        if unit.real.w < T::ZERO {
            // −q̂ = exp(−ŝ(π − θ̂/2)): the same axis reversed, dual angle 2π − θ̂. Taken from
            // the w > 0 side, this stays exact near 2π.
            let s = (-unit).to_screw()?;
            return Ok(Screw {
                axis: -s.axis,
                moment: -s.moment,
                angle: T::TWO * T::PI - s.angle,
                translation: -s.translation,
            });
        }
        let l = unit.log()?;
        let (lr, ld) = (l.real.vector(), l.dual.vector());
        let half = lr.norm();
        if half == T::ZERO {
            let half_t = ld.norm();
            let axis = if half_t == T::ZERO {
                Vec3::unit(0)
            } else {
                ld / half_t
            };
            return Ok(Screw {
                axis,
                moment: Vec3::zero(),
                angle: T::ZERO,
                translation: T::TWO * half_t,
            });
        }
        let axis = lr / half;
        let along = axis.dot(ld);
        Ok(Screw {
            axis,
            moment: (ld - axis * along) / half,
            angle: T::TWO * half,
            translation: T::TWO * along,
        })
    }

    /// The unit dual quaternion `cos(θ̂/2) + ŝ sin(θ̂/2)` of screw parameters (eq. 2). The
    /// axis is normalized and the moment's component along it removed. Errors: zero or
    /// non-finite axis, non-finite values.
    pub fn from_screw(screw: &Screw<T>) -> Result<Self> {
        let axis = screw
            .axis
            .normalize()
            .map_err(|_| Error::ZeroNorm { what: "screw axis" })?;
        crate::error::check_finite("screw moment", &screw.moment.to_array())?;
        crate::error::check_finite(
            "screw angle and translation",
            &[screw.angle, screw.translation],
        )?;
        let moment = screw.moment - axis * axis.dot(screw.moment);
        let half = Dual::new(screw.angle, screw.translation) * T::HALF;
        let (sin, cos) = half.sin_cos();
        Ok(DualQuat::new(
            Quat::from_scalar_vector(cos.re, axis * sin.re),
            Quat::from_scalar_vector(cos.du, moment * sin.re + axis * sin.du),
        ))
    }
}

/// `d/ds [sin√s / √s]`: `(cos x − sinc x) / (2s)` with x = √s, by its Taylor series
/// `Σ_{n≥1} (−1)^n n s^(n−1) / (2n+1)!` below s = 0.1 (six terms, error < 1e-17).
fn d_sinc_sqrt<T: Real>(s: T) -> T {
    if s < T::from_f64(0.1) {
        // −1/6 + s/60 − s²/1680 + s³/90720 − s⁴/7983360 + s⁵/1037836800
        let c = [
            -1.0 / 6.0,
            1.0 / 60.0,
            -1.0 / 1680.0,
            1.0 / 90720.0,
            -1.0 / 7983360.0,
            1.0 / 1037836800.0,
        ];
        horner(s, &c)
    } else {
        let x = s.sqrt();
        (x.cos() - sinc(x)) / (T::TWO * s)
    }
}

/// `∂/∂s [atan2(√s, w)/√s]` for `w ≥ 0` (log reduces `w < 0` to that case). With
/// r = √s/w, small r uses the series of
/// `G(r) = (atan r − r/(1+r²))/r³ = Σ (−1)^k 2(k+1)/(2k+3) r^(2k)`: the result is
/// `−G(r)/(2w³)`. Elsewhere the closed form `(w n/(n²+w²) − atan2(n, w)) / (2n³)`.
fn d_atan2_over_ds<T: Real>(s: T, w: T) -> T {
    if w > T::ZERO {
        let r2 = s / (w * w);
        if r2 < T::from_f64(0.03) {
            let mut c = [0.0; 10];
            for (k, ck) in c.iter_mut().enumerate() {
                let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
                *ck = sign * 2.0 * (k as f64 + 1.0) / (2.0 * k as f64 + 3.0);
            }
            return -horner(r2, &c) / (T::TWO * w * w * w);
        }
    }
    let n = s.sqrt();
    (w * n / (s + w * w) - n.atan2(w)) / (T::TWO * n * s)
}

/// Evaluates `Σ c[k] x^k` by Horner's rule.
fn horner<T: Real>(x: T, c: &[f64]) -> T {
    c.iter()
        .rev()
        .fold(T::ZERO, |acc, ck| acc * x + T::from_f64(*ck))
}
