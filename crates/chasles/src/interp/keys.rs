//! Key frames: the rotations a curve must pass through, with optional times, optional
//! angular velocities (Barr et al. 1992; Dam et al. §8.2's "supply the angular velocity at an
//! arbitrary key frame") and per-key parameters (Kochanek–Bartels' tension, continuity and
//! bias).

use super::tcb::TcbKey;
use crate::{Error, EulerOrder, Quat, Real, Result, Vec3};

/// Validated key frames: unit quaternions (at least two), optionally with strictly
/// increasing times, optionally the Euler-angle triples they were given as, and optionally
/// each key's own tension, continuity and bias ([`KeyFrames::with_tcb`]).
#[derive(Debug, Clone, PartialEq)]
pub struct KeyFrames<T> {
    q: Vec<Quat<T>>,
    times: Option<Vec<T>>,
    euler: Option<(EulerOrder, Vec<[T; 3]>)>,
    velocities: Option<Vec<Option<Vec3<T>>>>,
    tcb: Option<Vec<TcbKey>>,
}

/// Which signs the keys keep. q and −q are the same rotation but not the same point of the
/// sphere, and every quaternion curve depends on the choice (Dam et al. §6.1.5, footnote
/// 7; Squad needs same-hemisphere keys, §6.2.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Hemisphere {
    /// Flip each key to the hemisphere of the one before it (`q_i · q_{i−1} ≥ 0`): every
    /// interval then takes the shorter rotation. The default.
    #[default]
    Chain,
    /// Keep the signs as given: an interval whose keys have `q_i · q_{i+1} < 0` takes the
    /// longer way round.
    AsGiven,
}

impl<T: Real> KeyFrames<T> {
    /// Keys from quaternions (normalized here) and optional times. Errors: fewer than two
    /// keys, a zero or non-finite key (naming its index), times of the wrong count, not
    /// finite or not strictly increasing.
    pub fn new(keys: &[Quat<T>], times: Option<&[T]>, hemisphere: Hemisphere) -> Result<Self> {
        if keys.len() < 2 {
            return Err(Error::TooFewKeys {
                what: "interpolation",
                needed: 2,
                got: keys.len(),
            });
        }
        let mut q = Vec::with_capacity(keys.len());
        for (index, k) in keys.iter().enumerate() {
            let u = k.normalize().map_err(|e| Error::BadKey {
                index,
                source: Box::new(e),
            })?;
            let u = match (hemisphere, q.last()) {
                (Hemisphere::Chain, Some(prev)) if u.dot(*prev) < T::ZERO => -u,
                _ => u,
            };
            q.push(u);
        }
        if let Some(t) = times {
            if t.len() != keys.len() {
                return Err(Error::WrongLength {
                    what: "key times",
                    expected: "one per key",
                    got: t.len(),
                });
            }
            for (index, v) in t.iter().enumerate() {
                if !v.is_finite() || (index > 0 && *v <= t[index - 1]) {
                    return Err(Error::BadKeyTime {
                        index,
                        value: v.to_f64(),
                    });
                }
            }
        }
        Ok(Self {
            q,
            times: times.map(|t| t.to_vec()),
            euler: None,
            velocities: None,
            tcb: None,
        })
    }
    /// The keys with angular velocities at some of them: `ω` (rad per unit of the curve
    /// parameter — the key times, or one per interval without times) in world coordinates,
    /// `q̇ = ½ (0, ω) q`; `None` where the curve chooses. Squad ([`super::Squad`]) and the
    /// converged Spring ([`super::Solver::Converged`]) honour them. Errors: not one entry per
    /// key, or a velocity that is not finite (naming its key).
    pub fn with_velocities(mut self, velocities: &[Option<Vec3<T>>]) -> Result<Self> {
        if velocities.len() != self.q.len() {
            return Err(Error::WrongLength {
                what: "key velocities",
                expected: "one per key (None where free)",
                got: velocities.len(),
            });
        }
        for (index, v) in velocities.iter().enumerate() {
            if let Some(v) = v {
                crate::error::check_finite("angular velocity", &v.to_array()).map_err(|e| {
                    Error::BadKey {
                        index,
                        source: Box::new(e),
                    }
                })?;
            }
        }
        self.velocities = velocities
            .iter()
            .any(Option::is_some)
            .then(|| velocities.to_vec());
        Ok(self)
    }
    /// The keys' angular velocities ([`KeyFrames::with_velocities`]), if any is given.
    pub fn velocities(&self) -> Option<&[Option<Vec3<T>>]> {
        self.velocities.as_deref()
    }
    /// The angular velocity given at key `i`, if any.
    pub fn velocity(&self, i: usize) -> Option<Vec3<T>> {
        self.velocities
            .as_ref()
            .and_then(|v| v.get(i).copied().flatten())
    }
    /// The parameter length of interval `i`: the difference of its key times, or 1.
    pub fn duration(&self, interval: usize) -> T {
        match &self.times {
            Some(t) => t[interval + 1] - t[interval],
            None => T::ONE,
        }
    }
    /// Keys given as Euler-angle triples in `order` (radians, any size: `(0, 0, 4)` stays
    /// 4 rad about the last axis, not its principal value): the rotations are made from
    /// them, and LinEuler in the same order interpolates the triples themselves (eq. 6.1)
    /// instead of angles extracted from the rotations. Errors: as [`KeyFrames::new`], and
    /// a non-finite angle (naming its key).
    pub fn from_euler(
        order: EulerOrder,
        angles: &[[T; 3]],
        times: Option<&[T]>,
        hemisphere: Hemisphere,
    ) -> Result<Self> {
        for (index, a) in angles.iter().enumerate() {
            crate::error::check_finite("Euler angle", a).map_err(|e| Error::BadKey {
                index,
                source: Box::new(e),
            })?;
        }
        let q: Vec<Quat<T>> = angles.iter().map(|a| Quat::from_euler(order, *a)).collect();
        let mut keys = Self::new(&q, times, hemisphere)?;
        keys.euler = Some((order, angles.to_vec()));
        Ok(keys)
    }
    /// The Euler-angle triples the keys were given as ([`KeyFrames::from_euler`]), with
    /// their order.
    pub fn euler(&self) -> Option<(EulerOrder, &[[T; 3]])> {
        self.euler.as_ref().map(|(o, a)| (*o, a.as_slice()))
    }
    /// The unit key quaternions (signs as chosen by [`Hemisphere`]).
    pub fn quats(&self) -> &[Quat<T>] {
        &self.q
    }
    /// The key times, if given.
    pub fn times(&self) -> Option<&[T]> {
        self.times.as_deref()
    }
    /// Number of keys (≥ 2).
    pub fn len(&self) -> usize {
        self.q.len()
    }
    /// Always false: there are at least two keys.
    pub fn is_empty(&self) -> bool {
        false
    }
    /// The keys with their own Kochanek–Bartels parameters, one [`TcbKey`] per key (a
    /// parameter a key leaves out is the method's, [`super::Method::KochanekBartels`]).
    /// Errors: not one per key ([`Error::WrongLength`]); a value that is not finite or
    /// outside [−1, 1] ([`Error::BadKey`] naming the key, with [`Error::BadParameter`]
    /// naming the field).
    pub fn with_tcb(mut self, per_key: Vec<TcbKey>) -> Result<Self> {
        if per_key.len() != self.q.len() {
            return Err(Error::WrongLength {
                what: "per-key tension, continuity and bias",
                expected: "one per key",
                got: per_key.len(),
            });
        }
        for (index, k) in per_key.iter().enumerate() {
            k.check().map_err(|e| Error::BadKey {
                index,
                source: Box::new(e),
            })?;
        }
        self.tcb = Some(per_key);
        Ok(self)
    }
    /// Each key's own tension, continuity and bias, if given ([`KeyFrames::with_tcb`]).
    pub fn tcb(&self) -> Option<&[TcbKey]> {
        self.tcb.as_deref()
    }
    /// The length of interval `i` in the curve's parameter: `t_{i+1} − t_i` with key
    /// times, else 1 (clamped to the last interval).
    pub fn span(&self, interval: usize) -> T {
        let i = interval.min(self.q.len() - 2);
        match &self.times {
            Some(t) => t[i + 1] - t[i],
            None => T::ONE,
        }
    }
    /// The parameter value of a point `h` into interval `i`: the key time interpolated
    /// linearly, or `i + h` without times.
    pub fn parameter(&self, interval: usize, h: T) -> T {
        match &self.times {
            Some(t) => t[interval] + (t[interval + 1] - t[interval]) * h,
            None => T::from_f64(interval as f64) + h,
        }
    }
}
