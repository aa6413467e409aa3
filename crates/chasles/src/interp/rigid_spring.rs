//! *Spring* on rigid motions: Dam et al. 1998 §6.3.7's curve of least curvature energy
//! (eq. 6.23 with width 1, eq. 6.43; keys fixed, c_k = 1, no velocity term) carried to the
//! rigid motions (Kavan et al. 2006, §3; §7's "spatial keyframing"). Two energies
//! ([`RigidEnergy`]):
//!
//! **[`RigidEnergy::Split`] (the default)**: the quaternion Spring's energy of the rotations
//! plus the squared second differences of the translations,
//! `F = Σ_i ‖P_i(q_{i−1} − 2q_i + q_{i+1})‖² + ¼ Σ_i ‖t_{i−1} − 2t_i + t_{i+1}‖² / ℓ²`. The
//! two parts are independent: the rotations are the quaternion Spring's, solved by the
//! converged solver of `spring_converged` (reused as it is, [`super::spring()`] with
//! [`super::SpringConfig::converged`]), and the translations the discrete natural spline,
//! a band linear solve (`crate::banded`). Keys without translation give the quaternion
//! Spring, keys without rotation the Euclidean curve, exactly.
//!
//! **[`RigidEnergy::Screw`]**: the curvature energy of the dual-quaternion curve itself.
//! For unit quaternions the width-1 term is `‖P_i u_i‖²`, and since `q_i* u_i = q_i* q_{i−1} +
//! q_i* q_{i+1} − 2` it is the vector part of `q_i* q_{i−1} + q_i* q_{i+1}`; the same on unit
//! dual quaternions,
//!
//! ```text
//! F = Σ_i ‖V(q̂_i* q̂_{i−1} + q̂_i* q̂_{i+1})‖²,   V(a + ε b) = (vec a, vec b / ℓ) ∈ ℝ⁶,
//! ```
//!
//! is the tangent part of the dual quaternions' second difference pulled back to the
//! identity — the change of the body-frame twist. With no translations it is the quaternion
//! Spring's F (and its minimum keeps every translation 0). **With no rotations it is not the
//! Euclidean curve**: the body velocity is measured in the body's frame, so turning the body
//! along a bent path makes it steadier, and the minimum turns frames whose keys all share one
//! orientation (measured in `tests/rigid.rs`: up to 11° on five keys, the path 0.06 off the
//! natural spline). It behaves like a vehicle that heads along its path — right for some
//! motions, a surprise for key-framing, hence not the default.
//!
//! **Invariance.** Both energies are unchanged when every key moves by one rigid motion on
//! the left (a change of world frame: the split energy's norms are rotation-invariant and
//! its second differences cancel a common translation; the screw energy sees only relative
//! motions), and on the right by a rotation; not by a translation on the right (a change of
//! the point of the body that is tracked: `t_i → t_i + R_i s`, or `b → b + s × a` in the
//! relative motions). No energy does better: the rigid motions have no bi-invariant
//! metric, so no positive curvature energy is invariant on both sides (ScLERP and the
//! dual-quaternion Squad, built from the group operations alone, are).
//!
//! **The screw energy's solver.** Gauss–Newton with Levenberg–Marquardt damping, written
//! here: the converged quaternion solver is built around three tangent coordinates a frame
//! and the quaternion residual `P u / l^{3/2}` with its chord and angle widths, second-order
//! terms and velocity penalty; this residual has six coordinates and another form, and only
//! the band structure carries over. Gradient descent was not used: the energy's
//! conditioning grows like the fourth power of the frame count (Dam et al. needed hundreds
//! of iterations at 550 frames). Each frame moves by `q̂ ← q̂ exp(δ̂)`, δ̂ a pure dual
//! quaternion (6 coordinates); to first order `∂(q̂_i* q̂_j)/∂δ_j = (q̂_i* q̂_j) e` and
//! `∂(q̂_i* q̂_j)/∂δ_i = −e (q̂_i* q̂_j)` for each basis element e, so the Jacobian is exact and
//! JᵀJ a band matrix of half-bandwidth 17. The steps solve `(JᵀJ + μ D) δ = −Jᵀ r`, μ raised
//! only when a step does not lower F; it stops when the gradient has fallen to `tolerance`
//! of its start, when no step lowers F any more (rounding), or at `max_iterations`. It
//! starts from piecewise ScLERP.

use super::rigid::{grid, screw, RigidFrame, RigidKeys};
use super::spring::{spring, Solver, SpringConfig};
use super::timing::Timing;
use crate::banded::Band;
use crate::{DualQuat, Error, Quat, Real, Result, Vec3};

/// Which curvature energy [`rigid_spring`] minimizes (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RigidEnergy {
    /// The rotations' Spring energy plus the translations' second differences.
    #[default]
    Split,
    /// The dual-quaternion curve's own (body-frame) curvature energy.
    Screw,
}

/// Settings of [`rigid_spring`].
#[derive(Debug, Clone, PartialEq)]
pub struct RigidSpringConfig {
    /// The energy.
    pub energy: RigidEnergy,
    /// The length ℓ that weighs as much as one radian (positive, finite).
    pub length_scale: f64,
    /// Stop when the gradient has fallen to this fraction of its start (in [0, 1)).
    pub tolerance: f64,
    /// At most this many Gauss–Newton steps (1 to 10 000).
    pub max_iterations: usize,
}

impl Default for RigidSpringConfig {
    /// The split energy, ℓ = 1, tolerance 1e-12, at most 100 steps.
    fn default() -> Self {
        Self {
            energy: RigidEnergy::Split,
            length_scale: 1.0,
            tolerance: 1e-12,
            max_iterations: 100,
        }
    }
}

/// The outcome of [`rigid_spring`].
#[derive(Debug, Clone, PartialEq)]
pub struct RigidSpringResult<T> {
    /// The frames (keys exactly where they are).
    pub frames: Vec<RigidFrame<T>>,
    /// The energy F of the start (piecewise ScLERP; the split energy: of Slerp and the
    /// polygon) and of the result.
    pub energy: (f64, f64),
    /// Steps taken (accepted or not).
    pub iterations: usize,
    /// The gradient's norm at the end over its norm at the start.
    pub gradient_ratio: f64,
}

/// Unknowns per frame.
const DIM: usize = 6;
/// Half-bandwidth of JᵀJ: unknowns up to two frames apart.
const BAND: usize = 2 * DIM + DIM - 1;

/// The six basis directions of the tangent space at the identity.
fn basis() -> [DualQuat<f64>; DIM] {
    let z = Quat::zero();
    let p = |k: usize| Quat::pure(Vec3::unit(k));
    [
        DualQuat::new(p(0), z),
        DualQuat::new(p(1), z),
        DualQuat::new(p(2), z),
        DualQuat::new(z, p(0)),
        DualQuat::new(z, p(1)),
        DualQuat::new(z, p(2)),
    ]
}

/// `V(x)`: the vector parts, the dual one over ℓ.
fn v(x: DualQuat<f64>, inv_l: f64) -> [f64; DIM] {
    [
        x.real.x,
        x.real.y,
        x.real.z,
        x.dual.x * inv_l,
        x.dual.y * inv_l,
        x.dual.z * inv_l,
    ]
}

/// The residual of the term at frame i.
fn residual(x: &[DualQuat<f64>], i: usize, inv_l: f64) -> [f64; DIM] {
    let c = x[i].conjugate();
    v(c * x[i - 1] + c * x[i + 1], inv_l)
}

/// The screw energy F of the frames.
pub fn rigid_energy(x: &[DualQuat<f64>], length_scale: f64) -> f64 {
    let inv_l = 1.0 / length_scale;
    (1..x.len().saturating_sub(1))
        .map(|i| residual(x, i, inv_l).iter().map(|r| r * r).sum::<f64>())
        .sum()
}

/// Checks the settings.
fn check(cfg: &RigidSpringConfig) -> Result<()> {
    let l = cfg.length_scale;
    if !(l > 0.0 && l.is_finite()) {
        return Err(Error::BadParameter {
            what: "the length scale",
            rule: "positive and finite",
            value: l,
        });
    }
    if !(0.0..1.0).contains(&cfg.tolerance) {
        return Err(Error::BadParameter {
            what: "the tolerance",
            rule: "in [0, 1)",
            value: cfg.tolerance,
        });
    }
    if cfg.max_iterations == 0 || cfg.max_iterations > 10_000 {
        return Err(Error::BadParameter {
            what: "the iteration cap",
            rule: "from 1 to 10000",
            value: cfg.max_iterations as f64,
        });
    }
    Ok(())
}

/// The curve of least energy F through the keys, `frames` frames (module docs). Errors:
/// bad settings (named), fewer frames than keys, too many to hold, a start or step that is
/// not finite.
pub fn rigid_spring<T: Real>(
    keys: &RigidKeys<T>,
    frames: usize,
    cfg: &RigidSpringConfig,
) -> Result<RigidSpringResult<T>> {
    check(cfg)?;
    match cfg.energy {
        RigidEnergy::Split => split_spring(keys, frames, cfg),
        RigidEnergy::Screw => screw_spring(keys, frames, cfg),
    }
}

/// The split energy's minimum: the quaternion Spring of the rotations (the converged
/// solver) and the discrete natural spline of the translations.
fn split_spring<T: Real>(
    keys: &RigidKeys<T>,
    frames: usize,
    cfg: &RigidSpringConfig,
) -> Result<RigidSpringResult<T>> {
    let g = grid(keys, frames)?;
    let mut sc = SpringConfig::converged();
    sc.solver = Solver::Converged {
        tolerance: cfg.tolerance,
        max_iterations: cfg.max_iterations,
    };
    let rot = spring(keys.rotations(), frames, Timing::Uniform, &sc, &mut |_| {})?;
    let first = rot
        .history
        .first()
        .map_or((0.0, 0.0), |h| (h.energy, h.gradient_norm));
    let last = rot
        .history
        .last()
        .map_or((0.0, 0.0), |h| (h.energy, h.gradient_norm));
    // The translations: minimize Σ ‖t_{c−1} − 2t_c + t_{c+1}‖², keys fixed.
    let kt: Vec<Vec3<f64>> = keys
        .dual_quats()
        .iter()
        .map(|d| d.translation().cast())
        .collect();
    let n = g.len();
    let known: Vec<Option<Vec3<f64>>> = g.iter().map(|s| s.key.map(|k| kt[k])).collect();
    let mut a = Band::zeros(n, 2)?;
    let mut b = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    let polygon = |s: &super::timing::Sample<T>| {
        let h = s.h.to_f64();
        kt[s.interval] * (1.0 - h) + kt[s.interval + 1] * h
    };
    let start: Vec<Vec3<f64>> = g.iter().map(polygon).collect();
    let second = |p: &[Vec3<f64>]| {
        (1..n.saturating_sub(1))
            .map(|c| (p[c - 1] - p[c] * 2.0 + p[c + 1]).norm_squared())
            .sum::<f64>()
            * 0.25
            / (cfg.length_scale * cfg.length_scale)
    };
    for c in 1..n.saturating_sub(1) {
        let coef = [(c - 1, 1.0), (c, -2.0), (c + 1, 1.0)];
        let mut fixed = Vec3::zero();
        for (i, w) in coef {
            if let Some(p) = known[i] {
                fixed += p * w;
            }
        }
        for (i, wi) in coef {
            if known[i].is_some() {
                continue;
            }
            for (j, wj) in coef {
                if known[j].is_none() && j <= i {
                    a.add(i, j, wi * wj);
                }
            }
            let r = fixed * -wi;
            b[0][i] += r.x;
            b[1][i] += r.y;
            b[2][i] += r.z;
        }
    }
    for (i, k) in known.iter().enumerate() {
        if let Some(p) = k {
            a.add(i, i, 1.0);
            (b[0][i], b[1][i], b[2][i]) = (p.x, p.y, p.z);
        }
    }
    if !a.cholesky() {
        return Err(Error::NonFinite {
            what: "the rigid Spring's translations (the keys are too large)",
        });
    }
    for v in b.iter_mut() {
        a.solve(v);
    }
    let t: Vec<Vec3<f64>> = (0..n)
        .map(|i| Vec3::new(b[0][i], b[1][i], b[2][i]))
        .collect();
    let frames = rot
        .frames
        .iter()
        .zip(&g)
        .zip(&t)
        .map(|((f, s), p)| RigidFrame {
            dq: match s.key {
                Some(k) => keys.dual_quats()[k],
                None => DualQuat::from_rotation_translation(f.q, p.cast()),
            },
            t: keys.parameter(s.interval, s.h),
            key: s.key,
        })
        .collect();
    Ok(RigidSpringResult {
        frames,
        energy: (first.0 + second(&start), last.0 + second(&t)),
        iterations: rot.history.len().saturating_sub(1),
        gradient_ratio: if first.1 > 0.0 { last.1 / first.1 } else { 0.0 },
    })
}

/// The screw energy's minimum by Gauss–Newton (module docs).
fn screw_spring<T: Real>(
    keys: &RigidKeys<T>,
    frames: usize,
    cfg: &RigidSpringConfig,
) -> Result<RigidSpringResult<T>> {
    let g = grid(keys, frames)?;
    let k64: Vec<DualQuat<f64>> = keys.dual_quats().iter().map(|d| d.cast()).collect();
    let mut x = Vec::with_capacity(g.len());
    for s in &g {
        x.push(match s.key {
            Some(k) => k64[k],
            None => screw(k64[s.interval], k64[s.interval + 1], s.h.to_f64())?,
        });
    }
    let is_key: Vec<bool> = g.iter().map(|s| s.key.is_some()).collect();
    let inv_l = 1.0 / cfg.length_scale;
    let e = basis();
    let n = x.len();
    let start = rigid_energy(&x, cfg.length_scale);
    let mut f = start;
    let (mut g0, mut gnorm) = (None, 0.0);
    let mut mu = 0.0f64;
    let mut iterations = 0;
    let mut grad = vec![0.0; DIM * n];
    let (mut rounding, mut last_g) = (false, f64::INFINITY);
    while iterations < cfg.max_iterations && n > 2 {
        // Assemble JᵀJ and Jᵀr.
        let mut a = Band::zeros(DIM * n, BAND)?;
        grad.iter_mut().for_each(|v| *v = 0.0);
        for i in 1..n - 1 {
            let c = x[i].conjugate();
            let (xm, xp) = (c * x[i - 1], c * x[i + 1]);
            let r = v(xm + xp, inv_l);
            // J blocks: column k of frame f's block.
            let mut j = [[[0.0; DIM]; DIM]; 3];
            for k in 0..DIM {
                j[0][k] = v(xm * e[k], inv_l);
                j[1][k] = v(-(e[k] * (xm + xp)), inv_l);
                j[2][k] = v(xp * e[k], inv_l);
            }
            let fr = [i - 1, i, i + 1];
            for (p, &fp) in fr.iter().enumerate() {
                if is_key[fp] {
                    continue;
                }
                for k in 0..DIM {
                    let dot: f64 = (0..DIM).map(|m| j[p][k][m] * r[m]).sum();
                    grad[DIM * fp + k] += dot;
                    for (q, &fq) in fr.iter().enumerate() {
                        if is_key[fq] {
                            continue;
                        }
                        for l in 0..DIM {
                            let (row, col) = (DIM * fp + k, DIM * fq + l);
                            if row >= col {
                                let s: f64 = (0..DIM).map(|m| j[p][k][m] * j[q][l][m]).sum();
                                a.add(row, col, s);
                            }
                        }
                    }
                }
            }
        }
        for (fr, key) in is_key.iter().enumerate() {
            if *key {
                for k in 0..DIM {
                    a.add(DIM * fr + k, DIM * fr + k, 1.0);
                }
            }
        }
        gnorm = grad.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !gnorm.is_finite() {
            return Err(Error::NonFinite {
                what: "the rigid Spring's gradient (the keys are too large)",
            });
        }
        let first = *g0.get_or_insert(gnorm);
        if gnorm <= cfg.tolerance * first || gnorm == 0.0 {
            break;
        }
        // In the rounding regime a step that no longer lowers the gradient ends it.
        if rounding && gnorm >= last_g {
            break;
        }
        last_g = gnorm;
        // Damped steps until one lowers F (or the damping says rounding has won).
        let accepted = loop {
            iterations += 1;
            let mut m = a.clone();
            if mu > 0.0 {
                for r in 0..DIM * n {
                    let d = m.diagonal(r);
                    m.add(r, r, mu * d);
                }
            }
            let mut step: Vec<f64> = grad.iter().map(|v| -v).collect();
            let solved = m.cholesky();
            if solved {
                m.solve(&mut step);
            }
            let trial: Option<Vec<DualQuat<f64>>> = solved.then(|| {
                x.iter()
                    .enumerate()
                    .map(|(fr, q)| {
                        if is_key[fr] {
                            return *q;
                        }
                        let d = &step[DIM * fr..DIM * fr + DIM];
                        let t = DualQuat::new(
                            Quat::new(0.0, d[0], d[1], d[2]),
                            Quat::new(0.0, d[3], d[4], d[5]),
                        );
                        (*q * t.exp()).normalize().unwrap_or(*q)
                    })
                    .collect()
            });
            // The model's decrease of F (= Σ‖r‖²) for the step: −2 gᵀδ − δᵀAδ ≈ −gᵀδ.
            let predicted = -grad.iter().zip(&step).map(|(g, d)| g * d).sum::<f64>();
            let better = trial.and_then(|t| {
                let ft = rigid_energy(&t, cfg.length_scale);
                // Near the minimum F's rounding hides the decrease of an undamped step
                // (the smooth modes barely change F): take it, and let the gradient judge.
                let tiny = mu == 0.0 && predicted.abs() <= 1e-12 * f;
                rounding = tiny;
                (ft < f || tiny).then_some((t, ft.min(f)))
            });
            match better {
                Some((t, ft)) => {
                    x = t;
                    f = ft;
                    mu /= 4.0;
                    if mu < 1e-12 {
                        mu = 0.0;
                    }
                    break true;
                }
                None => {
                    mu = if mu == 0.0 { 1e-6 } else { mu * 8.0 };
                    if mu > 1e8 || iterations >= cfg.max_iterations {
                        break false;
                    }
                }
            }
        };
        if !accepted {
            break;
        }
    }
    let frames = x
        .iter()
        .zip(&g)
        .map(|(d, s)| RigidFrame {
            dq: match s.key {
                Some(k) => keys.dual_quats()[k],
                None => d.cast(),
            },
            t: keys.parameter(s.interval, s.h),
            key: s.key,
        })
        .collect();
    Ok(RigidSpringResult {
        frames,
        energy: (start, f),
        iterations,
        gradient_ratio: g0.map_or(0.0, |g0| if g0 > 0.0 { gnorm / g0 } else { 0.0 }),
    })
}
