//! Kochanek–Bartels splines on quaternions: tension, continuity and bias per key
//! (D. Kochanek & R. Bartels, "Interpolating splines with local tension, continuity, and
//! bias control", SIGGRAPH 1984, eq. 8–9 and their §4 step-size adjustment), in the log
//! space of the relative rotations as the quaternion form usually takes them (Shoemake
//! 1987; Dam et al. §6.2.1 write Squad's tangents the same way).
//!
//! At key `i`, with the log-space chord velocities `u_{i−1} = log(q_{i−1}* q_i)/Δ_{i−1}`
//! and `u_i = log(q_i* q_{i+1})/Δ_i` (the body-frame steps, per unit of the parameter; see
//! [`super::catmull_rom`] for the spans Δ and the weights `α_i = Δ_i/(Δ_{i−1} + Δ_i)`,
//! `β_i = 1 − α_i`), tension `t`, continuity `c` and bias `b` give the outgoing ("source")
//! and incoming ("destination") tangents
//!
//! ```text
//! TS_i = (1 − t) [(1 + c)(1 + b) α_i u_{i−1} + (1 − c)(1 − b) β_i u_i]
//! TD_i = (1 − t) [(1 − c)(1 + b) α_i u_{i−1} + (1 + c)(1 − b) β_i u_i]
//! ```
//!
//! — Kochanek & Bartels' eq. 8–9 for equal spans (α = β = ½). For unequal spans their §4
//! scales the tangents so that `t = c = b = 0` gives the secant `(P_{i+1} − P_{i−1})/(Δ_{i−1} + Δ_i)`;
//! we weight the two chords by α and β instead, the derivative of the parabola through the
//! three keys, so that zero parameters give exactly the Catmull–Rom spline of Barry &
//! Goldman and Schlag ([`super::catmull_rom`]) for any key times.
//!
//! The segment from `q_i` to `q_{i+1}` is Schlag's construction with the outer geodesics
//! chosen to leave `q_i` with `TS_i` and reach `q_{i+1}` with `TD_{i+1}`: A₁ through `q_i`
//! with velocity `(TS_i − β_i u_i)/α_i` and A₃ through `q_{i+1}` with velocity
//! `(TD_{i+1} − α_{i+1} u_i)/β_{i+1}`. In flat space this is exactly the cubic Hermite segment
//! with those tangents, Kochanek & Bartels' curve; with `t = c = b = 0` the velocities are the
//! chords and the curve is the spherical Catmull–Rom spline.
//!
//! **Properties** (tested by number): the curve passes through the keys; it leaves key `i`
//! with angular velocity `2 TS_i` and arrives with `2 TD_i` (body frame), so it is C¹ at
//! every key with `c = 0` and has the corner `2 (TS_i − TD_i)` otherwise; `t = 1` stops at
//! the key, `t = −1` doubles the Catmull–Rom tangent; `b = 1` takes the incoming chord's
//! velocity, `b = −1` the outgoing one's. Changing one key's parameters changes only the two
//! intervals that meet there. End keys use the reflected phantom key of
//! [`super::catmull_rom`] (`u_{−1} = u_0`), so their parameters scale the chord.
//!
//! **Limits.** The outer velocity `(TS_i − β_i u_i)/α_i` grows to 9 chords at
//! `t = −1, c = b = 1`; with key steps that large, the construction's outer point can pass
//! a half turn (in 4D) from the chord's point (see [`super::catmull_rom`]'s limits), and
//! the curve swings there: keep `Δ_i |(TS_i − β_i u_i)/α_i| + |log(q_i* q_{i+1})|` below π.

use super::catmull_rom::{chords, weights, CatmullRom};
use super::KeyFrames;
use crate::{Error, Quat, Real, Result, Vec3};

/// Tension, continuity and bias (each in [−1, 1]; all 0 is the Catmull–Rom spline).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Tcb {
    /// Tension: 1 stops at the key, −1 doubles the tangent.
    pub tension: f64,
    /// Continuity: 0 is C¹; −1 makes a corner (each side its own chord), 1 the inverted
    /// corner.
    pub continuity: f64,
    /// Bias: 1 takes the incoming chord (overshoot), −1 the outgoing one (undershoot).
    pub bias: f64,
}

/// A key's own parameters: those it leaves out come from the curve's [`Tcb`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TcbKey {
    /// The key's tension, if its own.
    pub tension: Option<f64>,
    /// The key's continuity, if its own.
    pub continuity: Option<f64>,
    /// The key's bias, if its own.
    pub bias: Option<f64>,
}

/// The range rule of every parameter, in words.
const RULE: &str = "a finite number in [-1, 1]";

/// `Ok(value)` when `value` is finite and in [−1, 1], else [`Error::BadParameter`] naming
/// `what` (`"tension"`, `"continuity"` or `"bias"`).
pub fn check_parameter(what: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && (-1.0..=1.0).contains(&value) {
        Ok(value)
    } else {
        Err(Error::BadParameter {
            what,
            rule: RULE,
            value,
        })
    }
}

impl Tcb {
    /// All three 0: the Catmull–Rom spline.
    pub const CATMULL_ROM: Tcb = Tcb {
        tension: 0.0,
        continuity: 0.0,
        bias: 0.0,
    };
    /// Checked parameters. Errors: one that is not finite or outside [−1, 1]
    /// ([`Error::BadParameter`] naming it).
    pub fn new(tension: f64, continuity: f64, bias: f64) -> Result<Self> {
        let t = Tcb {
            tension,
            continuity,
            bias,
        };
        t.check()?;
        Ok(t)
    }
    /// Checks the three parameters ([`check_parameter`]).
    pub fn check(&self) -> Result<()> {
        check_parameter("tension", self.tension)?;
        check_parameter("continuity", self.continuity)?;
        check_parameter("bias", self.bias)?;
        Ok(())
    }
}

impl TcbKey {
    /// Checks the parameters given ([`check_parameter`]).
    pub fn check(&self) -> Result<()> {
        for (what, v) in [
            ("tension", self.tension),
            ("continuity", self.continuity),
            ("bias", self.bias),
        ] {
            if let Some(v) = v {
                check_parameter(what, v)?;
            }
        }
        Ok(())
    }
    /// The key's parameters, `default`'s where it has none.
    pub fn resolve(&self, default: Tcb) -> Tcb {
        Tcb {
            tension: self.tension.unwrap_or(default.tension),
            continuity: self.continuity.unwrap_or(default.continuity),
            bias: self.bias.unwrap_or(default.bias),
        }
    }
}

/// A Kochanek–Bartels spline through key frames (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct KochanekBartels<T> {
    curve: CatmullRom<T>,
    params: Vec<Tcb>,
    leaving: Vec<Vec3<T>>,
    arriving: Vec<Vec3<T>>,
}

impl<T: Real> KochanekBartels<T> {
    /// The spline through `keys` with each key's own parameters ([`KeyFrames::with_tcb`])
    /// and `default` for the rest. Errors: `default` out of range ([`Error::BadParameter`]).
    pub fn new(keys: &KeyFrames<T>, default: Tcb) -> Result<Self> {
        default.check()?;
        let n = keys.len();
        let params: Vec<Tcb> = match keys.tcb() {
            Some(per_key) => per_key.iter().map(|k| k.resolve(default)).collect(),
            None => vec![default; n],
        };
        let (u, span) = chords(keys)?;
        let mut leaving = Vec::with_capacity(n);
        let mut arriving = Vec::with_capacity(n);
        let mut before = Vec::with_capacity(n);
        let mut after = Vec::with_capacity(n);
        for (i, p) in params.iter().enumerate() {
            let (alpha, beta) = weights(&span, i);
            // The phantom keys: the chord beyond an end is the end interval's own.
            let u_in = u[i.saturating_sub(1)];
            let u_out = u[i.min(n - 2)];
            let f = |v: f64| T::from_f64(v);
            let (t, c, b) = (f(p.tension), f(p.continuity), f(p.bias));
            let one = T::ONE;
            let ts = (u_in * ((one + c) * (one + b) * alpha)
                + u_out * ((one - c) * (one - b) * beta))
                * (one - t);
            let td = (u_in * ((one - c) * (one + b) * alpha)
                + u_out * ((one + c) * (one - b) * beta))
                * (one - t);
            before.push((ts - u_out * beta) / alpha);
            after.push((td - u_in * alpha) / beta);
            leaving.push(ts * T::TWO);
            arriving.push(td * T::TWO);
        }
        let curve = CatmullRom::from_parts(keys.quats().to_vec(), span, before, after);
        Ok(Self {
            curve,
            params,
            leaving,
            arriving,
        })
    }
    /// The curve at `h ∈ [0, 1]` into interval `i` (clamped to the last interval).
    pub fn eval(&self, interval: usize, h: T) -> Quat<T> {
        self.curve.eval(interval, h)
    }
    /// Each key's parameters as used (its own, else the default).
    pub fn params(&self) -> &[Tcb] {
        &self.params
    }
    /// The angular velocity `2 TS_i` with which the curve leaves each key (body frame,
    /// radians per unit of the parameter).
    pub fn leaving(&self) -> &[Vec3<T>] {
        &self.leaving
    }
    /// The angular velocity `2 TD_i` with which the curve arrives at each key.
    pub fn arriving(&self) -> &[Vec3<T>] {
        &self.arriving
    }
}
