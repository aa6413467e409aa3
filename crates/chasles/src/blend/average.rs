//! Averaging measured rigid poses — Kavan et al. 2006, §7: "averaging of measured positions
//! and orientations in computer vision" is one of the uses the paper names for its blends.
//!
//! **The rigid mean** ([`mean`]) is the pose DIB converges to (§4, the algorithm box): the
//! unit dual quaternion b̂ with `Σ wᵢ log(b̂* q̂ᵢ) = 0`, each `b̂* q̂ᵢ` taken the shorter way.
//! It is bi-invariant (moving every pose by the same rigid motion on the left or on the
//! right moves the mean the same way) and its rotation part is the geodesic (Karcher) mean
//! of the rotations alone, whatever the translations. Weights are optional (uniform when
//! absent) and go through [`super::weights::convex_weights`].
//!
//! **The robust mean** ([`robust_mean`]) ignores outliers: an M-estimator solved by
//! iteratively reweighted DIB steps. The residual of pose i is its distance to the current
//! mean b̂,
//!
//! ```text
//! dᵢ = 2 ‖log(b̂* q̂ᵢ)‖ℓ,   ‖a + ε c‖ℓ² = ‖a‖² + ‖c‖²/ℓ²    (a, c the vector parts)
//! ```
//!
//! — for a small relative motion of twist (ω, v) (turn ω radians, move v) this is
//! `√(‖ω‖² + ‖v‖²/ℓ²)`, with ℓ ([`Robust::length_scale`], default 1) the length that counts
//! as much as a radian. It is left-invariant (the relative motion `b̂* q̂ᵢ` does not change
//! when every pose is moved on the left), not right-invariant when ℓ ≠ ∞: the moment of a
//! relative screw depends on where the frame's origin is. Each step takes weights
//! `uᵢ = wᵢ ψ(rᵢ)/rᵢ` with `rᵢ = dᵢ/s`, then one DIB update `b̂ ← b̂ exp(Σ uᵢ log(b̂* q̂ᵢ) /
//! Σ uᵢ)`. ψ is Huber's (`uᵢ/wᵢ = min(1, c/rᵢ)`, c = 1.345) or Tukey's biweight (`(1 −
//! (rᵢ/c)²)²` below c, 0 above, c = 4.685); the constants are the usual 95 %-efficiency
//! ones, which may be changed ([`Robust::tuning`]).
//!
//! **Scale.** s is given ([`Scale::Fixed`]) or re-estimated at every step by the median
//! absolute deviation ([`Scale::Mad`]): `s = 1.4826 · median(dᵢ)` (1.4826 makes the MAD of a
//! 1-D normal sample its σ). The dᵢ are norms of a 3- or 6-dimensional residual, so for
//! normal noise of σ per coordinate the median is about 1.54σ (3 dimensions) or 2.3σ (6),
//! and s about 2.3σ or 3.5σ: Huber's weights then leave inliers alone (they fall below 1
//! only past 3σ or 4.6σ), and Tukey's reject what lies past 11σ or 16σ. A scale below the
//! precision is raised to it (more than half of the poses at one point).
//!
//! **Start.** Reweighting from a start that outliers have already pulled away (DLB, DIB)
//! can settle on their side with Tukey's weights. The start is instead the input pose with
//! the smallest median distance to all others (least median of squares over at most 64
//! evenly spaced candidates, 64·n distances): with fewer than half outliers it lies among
//! the inliers.

use super::dib::dib_convex;
use super::weights::convex_weights;
use super::{finite_update, keep_going, Options};
use crate::{DualQuat, Error, Quat, Real, Result};

/// The loss of a robust mean.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Loss {
    /// Huber: quadratic within c·s of the mean, linear past it (weights `min(1, c/r)`).
    Huber,
    /// Tukey's biweight: weights `(1 − (r/c)²)²` within c·s, 0 past it (outliers ignored).
    Tukey,
}

impl Loss {
    /// Both losses.
    pub const ALL: [Loss; 2] = [Loss::Huber, Loss::Tukey];
    /// The command-line name: `huber` or `tukey`.
    pub fn name(self) -> &'static str {
        match self {
            Loss::Huber => "huber",
            Loss::Tukey => "tukey",
        }
    }
    /// The usual tuning constant (95 % efficiency at the normal): 1.345 (Huber), 4.685
    /// (Tukey).
    pub fn default_tuning(self) -> f64 {
        match self {
            Loss::Huber => 1.345,
            Loss::Tukey => 4.685,
        }
    }
    /// The weight `ψ(r)/r` at the scaled residual `r ≥ 0` with tuning `c`.
    pub fn weight<T: Real>(self, r: T, c: T) -> T {
        match self {
            Loss::Huber if r <= c => T::ONE,
            Loss::Huber => c / r,
            Loss::Tukey if r < c => {
                let u = r / c;
                let v = T::ONE - u * u;
                v * v
            }
            Loss::Tukey => T::ZERO,
        }
    }
}

/// How the robust mean finds its scale s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scale<T> {
    /// `1.4826 · median(dᵢ)` at every step (the median absolute deviation).
    Mad,
    /// A fixed scale (in the units of the distance: radians, or lengths over ℓ).
    Fixed(T),
}

/// The settings of [`robust_mean`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Robust<T> {
    /// Huber or Tukey.
    pub loss: Loss,
    /// The tuning constant c (`None`: [`Loss::default_tuning`]).
    pub tuning: Option<T>,
    /// The scale s.
    pub scale: Scale<T>,
    /// The length ℓ that weighs as much as one radian in the distance (positive).
    pub length_scale: T,
    /// Stop when the update is smaller than this; at most this many updates.
    pub options: Options<T>,
}

impl<T: Real> Robust<T> {
    /// `loss` with its usual tuning, the MAD scale, ℓ = 1, and 200 updates at most.
    pub fn new(loss: Loss) -> Self {
        Robust {
            loss,
            tuning: None,
            scale: Scale::Mad,
            length_scale: T::ONE,
            options: Options {
                max_iterations: 200,
                ..Options::default()
            },
        }
    }
}

/// A mean of poses.
#[derive(Debug, Clone, PartialEq)]
pub struct Average<T> {
    /// The mean pose (unit).
    pub pose: DualQuat<T>,
    /// The updates made.
    pub iterations: usize,
    /// Whether it stopped at the cap on updates rather than by its stopping rule.
    pub capped: bool,
    /// Each pose's final weight, summing to 1 (the robust weights times the given ones;
    /// the given ones, scaled, for [`mean`]).
    pub weights: Vec<T>,
    /// Each pose's distance to the mean (`dᵢ` with the length scale used; ℓ = 1 for
    /// [`mean`]).
    pub distances: Vec<T>,
    /// The last scale s ([`robust_mean`] only).
    pub scale: Option<T>,
}

/// Checks the poses: at least one, each finite and unit (within
/// [`crate::default_tolerance`]); errors name the pose.
pub fn check_poses<T: Real>(poses: &[DualQuat<T>]) -> Result<()> {
    if poses.is_empty() {
        return Err(Error::BlendInput {
            what: "nothing to average: no poses".into(),
        });
    }
    for (i, p) in poses.iter().enumerate() {
        p.check_unit().map_err(|e| Error::BlendInput {
            what: format!("pose {i}: {e}"),
        })?;
    }
    Ok(())
}

/// The weights given (checked and scaled to sum to 1), or uniform ones.
fn weights_or_uniform<T: Real>(n: usize, w: Option<&[T]>) -> Result<Vec<T>> {
    match w {
        Some(w) => convex_weights(w, n),
        None => Ok(vec![T::ONE / T::from_f64(n as f64); n]),
    }
}

/// The distance `2 ‖log(a* b)‖ℓ` between two unit poses (module docs): the turn in radians
/// and the move over `length_scale`, combined in quadrature, of the shorter screw from a
/// to b. Errors: not finite.
pub fn distance<T: Real>(a: DualQuat<T>, b: DualQuat<T>, length_scale: T) -> Result<T> {
    let l = (a.conjugate() * b).to_positive_hemisphere().log()?;
    let (r, c) = (l.real.vector(), l.dual.vector());
    Ok(T::TWO * (r.norm_squared() + c.norm_squared() / (length_scale * length_scale)).sqrt())
}

/// The weighted rigid mean of unit poses: DIB's fixed point (module docs). `weights`:
/// `None` for uniform. Errors: no poses, a pose that is not finite or not unit (named),
/// bad weights, an update that overflows.
pub fn mean<T: Real>(
    poses: &[DualQuat<T>],
    weights: Option<&[T]>,
    opt: &Options<T>,
) -> Result<Average<T>> {
    check_poses(poses)?;
    let w = weights_or_uniform(poses.len(), weights)?;
    let (pose, iterations) = dib_convex(poses, &w, opt.precision, opt.max_iterations)?;
    let distances = poses
        .iter()
        .map(|p| distance(pose, *p, T::ONE))
        .collect::<Result<Vec<_>>>()?;
    Ok(Average {
        pose,
        iterations,
        capped: iterations == opt.max_iterations && poses.len() > 1,
        weights: w,
        distances,
        scale: None,
    })
}

/// The median of the values whose weight is positive (the upper one of an even count).
fn weighted_support_median<T: Real>(d: &[T], w: &[T]) -> T {
    let mut v: Vec<f64> = d
        .iter()
        .zip(w)
        .filter(|(_, w)| **w > T::ZERO)
        .map(|(d, _)| d.to_f64())
        .collect();
    if v.is_empty() {
        return T::ZERO;
    }
    let k = v.len() / 2;
    let (_, m, _) = v.select_nth_unstable_by(k, f64::total_cmp);
    T::from_f64(*m)
}

/// The start of the robust iteration: of at most 64 evenly spaced poses of positive weight,
/// the one whose median distance to the others is least.
fn lmeds_start<T: Real>(poses: &[DualQuat<T>], w: &[T], ell: T) -> Result<DualQuat<T>> {
    let support: Vec<usize> = (0..poses.len()).filter(|i| w[*i] > T::ZERO).collect();
    let m = support.len().min(64);
    let mut best = (f64::INFINITY, poses[support[0]]);
    let mut d = vec![T::ZERO; poses.len()];
    for k in 0..m {
        let c = poses[support[k * support.len() / m]];
        for (di, p) in d.iter_mut().zip(poses) {
            *di = distance(c, *p, ell)?;
        }
        let med = weighted_support_median(&d, w).to_f64();
        if med < best.0 {
            best = (med, c);
        }
    }
    Ok(best.1)
}

/// The robust mean (module docs): iteratively reweighted DIB with Huber's or Tukey's
/// weights on the poses' distances to the mean, from a least-median start. `weights`:
/// `None` for uniform; they multiply the robust ones. Errors: as [`mean`], and a tuning
/// constant, fixed scale or length scale that is not positive and finite.
pub fn robust_mean<T: Real>(
    poses: &[DualQuat<T>],
    weights: Option<&[T]>,
    robust: &Robust<T>,
) -> Result<Average<T>> {
    check_poses(poses)?;
    let w = weights_or_uniform(poses.len(), weights)?;
    let positive = |what: &'static str, v: T| {
        if v > T::ZERO && v.is_finite() {
            Ok(v)
        } else {
            Err(Error::BadParameter {
                what,
                rule: "positive and finite",
                value: v.to_f64(),
            })
        }
    };
    let c = positive(
        "the tuning constant",
        robust
            .tuning
            .unwrap_or(T::from_f64(robust.loss.default_tuning())),
    )?;
    let ell = positive("the length scale", robust.length_scale)?;
    if let Scale::Fixed(s) = robust.scale {
        positive("the scale", s)?;
    }
    let opt = &robust.options;
    let precision = positive("the precision", opt.precision)?;
    let mut b = lmeds_start(poses, &w, ell)?;
    let n = poses.len();
    let (mut d, mut u) = (vec![T::ZERO; n], vec![T::ZERO; n]);
    let mut logs = vec![DualQuat::new(Quat::zero(), Quat::zero()); n];
    let mut steps = 0;
    let mut last = T::from_f64(f64::INFINITY);
    let mut s;
    loop {
        for i in 0..n {
            let l = (b.conjugate() * poses[i]).to_positive_hemisphere().log()?;
            let (r, e) = (l.real.vector(), l.dual.vector());
            d[i] = T::TWO * (r.norm_squared() + e.norm_squared() / (ell * ell)).sqrt();
            logs[i] = l;
        }
        s = match robust.scale {
            Scale::Fixed(s) => s,
            Scale::Mad => (T::from_f64(1.4826) * weighted_support_median(&d, &w)).max(precision),
        };
        let mut sum = T::ZERO;
        for i in 0..n {
            u[i] = w[i] * robust.loss.weight(d[i] / s, c);
            sum += u[i];
        }
        if sum <= T::ZERO || !sum.is_finite() {
            return Err(Error::BlendInput {
                what: format!(
                    "every pose lies past the {} cut-off ({} × the scale {}) from the mean: no pose keeps a weight",
                    robust.loss.name(),
                    c,
                    s
                ),
            });
        }
        for ui in u.iter_mut() {
            *ui /= sum;
        }
        if steps == opt.max_iterations {
            break;
        }
        let mut x = DualQuat::new(Quat::zero(), Quat::zero());
        for (l, ui) in logs.iter().zip(&u) {
            x = x + *l * *ui;
        }
        let norm = (x.real.norm_squared() + x.dual.norm_squared()).sqrt();
        let norm = finite_update(norm, "the robust mean's update (the poses overflow)")?;
        if !keep_going(norm, last, precision) {
            break;
        }
        last = norm;
        b = (b * x.exp()).normalize()?;
        steps += 1;
    }
    Ok(Average {
        pose: b,
        iterations: steps,
        capped: steps == opt.max_iterations,
        weights: u,
        distances: d,
        scale: Some(s),
    })
}
