//! *Spring* solved to its optimum: the energy of Dam et al. 1998 §6.3.7 minimized over unit
//! quaternions by a second-order method, as §8.2 asks ("a more robust numerical solution
//! with a faster convergence", after Ramamoorthi & Barr 1997).
//!
//! The energy is the report's F on unit frames (keys fixed):
//! `F = Σ_i c_i l_i ‖κ̃_i‖² + c_w Σ_i w_i²` (eq. 6.23, 6.25–6.26, 6.40–6.41; the unit penalty
//! of eq. 6.27 is zero on unit frames), a sum of squares of residuals that each depend on
//! three neighbouring frames: `r_i = √c_i P_i u_i / l_i^{3/2}` with `u_i = q_{i−1} − 2q_i +
//! q_{i+1}` and `P_i = I − q_i q_iᵀ` (so `‖r_i‖² = c_i l_i ‖κ̃_i‖²`), and `v_i = √c_w w_i`.
//!
//! Gauss–Newton on the sphere: each frame moves in its tangent space, `q_i ← (q_i + B_i δ_i)
//! / ‖·‖` with `B_i = [q_i e₁, q_i e₂, q_i e₃]` (the quaternion times the unit pure
//! quaternions: an orthonormal basis of the tangent space), and the step solves
//! `(JᵀJ + μ D) δ = −Jᵀ r` with J the residuals' Jacobian in the δ. A residual couples
//! frames at most two apart, so JᵀJ is a band matrix of half-bandwidth 8 (three unknowns a
//! frame) and the solve costs O(N) ([`crate::banded`]). The second-order term that
//! Gauss–Newton leaves out, `Σ r ∇²r`, is of the order of the second differences (the
//! curvature times the squared frame spacing), so the steps converge almost quadratically;
//! μ (Levenberg–Marquardt, D the diagonal of JᵀJ) is raised only when a step does not lower
//! F. It stops when the projected gradient `2 Jᵀr` has fallen to `tolerance` times its
//! start, when no step lowers F any more (rounding: at 10⁵ frames and more the second
//! differences are down to a few digits of f64), or at the iteration cap. There is no step
//! length or penalty to tune.
//!
//! The Jacobian's blocks, for the three frames a, b, c of term i and a tangent direction t
//! of each (`P = I − b bᵀ`, `s = √c_i / l^{3/2}`): `∂r/∂a = s P t`, `∂r/∂c = s P t`,
//! `∂r/∂b = s (−(2 + b·u) t − b (u·t))` (from `∂(P u)` with `P t = t` for t ⊥ b), each plus
//! `−(3/2) r (∂l·t) / l` for the chord and angle widths. The tests hold `2 Jᵀr` against the
//! report solver's analytic gradient projected onto the tangent spaces, and `JᵀJ + S`
//! (S: the second-order part, [`curvature_residual`], [`velocity_residual`]) against second
//! differences of F.
//!
//! A finding against the report's eq. 6.24: with the chord or angle widths the minimum of F
//! is a badly sampled curve. A term is `‖P u‖² / l³ ≈ κ² l` (κ the curvature): F is about
//! the curvature integral whatever the spacing, and its discrete form is lowered by
//! spacing the frames unevenly — on Table 5.1 at 120 frames the stationary point the solver
//! reaches, from Slerp or Squad alike, has chords from 0.03 to 0.49 where the report's
//! descent (which stays near its start with small steps) keeps 0.03 to 0.11, at a fifteenth
//! of its F; with a velocity weight frames even jump to their neighbour's antipode (the same
//! rotation, chord 2). With width 1 (eq. 6.43, the report's final choice) F is a
//! fourth-difference energy with one minimum, which the solver reaches from any start.
//!
//! Past 500 lines because the residuals, their first and second derivatives and the Newton
//! loop that assembles them are one algorithm whose parts change together (a term added to
//! F needs its Jacobian and Hessian beside it), and the tests that hold the derivatives to
//! finite differences belong with them.

use super::spring::{EnergyRecord, Progress, SpringConfig, SpringResult, Start, Stopped};
use super::{interpolate, Frame, KeyFrames, Method, Timing};
use crate::analysis::curvature::Width;
use crate::banded::Band;
use crate::{Error, Quat, Result};

/// Unknowns per frame (the tangent space of the unit quaternions).
const DIM: usize = 3;
/// Half-bandwidth of JᵀJ: a term couples frames i − 1 … i + 1, so unknowns up to two frames
/// (and two coordinates) apart.
const BAND: usize = 2 * DIM + DIM - 1;

/// The tangent basis of unit q: q times the three unit pure quaternions.
fn basis(q: Quat<f64>) -> [Quat<f64>; DIM] {
    [
        q * Quat::new(0.0, 1.0, 0.0, 0.0),
        q * Quat::new(0.0, 0.0, 1.0, 0.0),
        q * Quat::new(0.0, 0.0, 0.0, 1.0),
    ]
}

/// Tangent coordinates of a term's three frames: index `3f + k` (frame f of a, b, c,
/// direction k).
const T9: usize = 3 * DIM;

/// A 9×9 block in the term's tangent coordinates.
type Block = [[f64; T9]; T9];

/// The chord `n = ‖b − x‖` between a term's middle frame b and its neighbour x (f = 0: a,
/// f = 2: c), with its first and second derivatives in the term's tangent coordinates,
/// the retraction's second order included (`∂²x/∂δₖ∂δₗ = −δₖₗ x`): `n_p = e·D_p`,
/// `n_pq = e·d_pq + (D_p·D_q − n_p n_q)/n` with `e = (b − x)/n`, `D_p = ∂(b − x)/∂p`.
/// Zero derivatives where the frames coincide.
fn chord(q: [Quat<f64>; 3], t: [[Quat<f64>; DIM]; 3], f: usize) -> (f64, [f64; T9], Block) {
    let (x, b) = (q[f], q[1]);
    let d = b - x;
    let n = d.norm();
    let mut first = [0.0; T9];
    let mut second = [[0.0; T9]; T9];
    if n.is_nan() || n <= 0.0 {
        return (n, first, second);
    }
    let e = d / n;
    let dirs: [Quat<f64>; T9] = core::array::from_fn(|p| {
        let (g, k) = (p / DIM, p % DIM);
        if g == 1 {
            t[1][k]
        } else if g == f {
            -t[f][k]
        } else {
            Quat::zero()
        }
    });
    for p in 0..T9 {
        first[p] = e.dot(dirs[p]);
    }
    let (eb, ex) = (e.dot(b), e.dot(x));
    for p in 0..T9 {
        for q in 0..T9 {
            // d_pq: −b for a b-direction twice (the same k), +x for x-directions.
            let mut v = (dirs[p].dot(dirs[q]) - first[p] * first[q]) / n;
            if p == q && p / DIM == 1 {
                v -= eb;
            } else if p == q && p / DIM == f {
                v += ex;
            }
            second[p][q] = v;
        }
    }
    (n, first, second)
}

/// The width `l` of a term with its first and second derivatives (see [`chord`]): 1;
/// the chord average `(n₁ + n₂)/2`; or the angle average `(θ(n₁) + θ(n₂))/2` with
/// `θ(n) = 2 asin(n/2)` (the angle between unit frames at chord n), `θ' = 1/√(1 − n²/4)`,
/// `θ'' = (n/4)/(1 − n²/4)^{3/2}`.
fn width(q: [Quat<f64>; 3], t: [[Quat<f64>; DIM]; 3], w: Width) -> (f64, [f64; T9], Block) {
    if w == Width::Unit {
        return (1.0, [0.0; T9], [[0.0; T9]; T9]);
    }
    let ends = [chord(q, t, 0), chord(q, t, 2)];
    let mut l = 0.0;
    let mut first = [0.0; T9];
    let mut second = [[0.0; T9]; T9];
    for (n, np, npq) in &ends {
        let (value, d1, d2) = match w {
            Width::Angle => {
                let c2 = (1.0 - n * n / 4.0).max(f64::MIN_POSITIVE);
                (
                    2.0 * (n / 2.0).min(1.0).asin(),
                    1.0 / c2.sqrt(),
                    n / 4.0 / (c2 * c2.sqrt()),
                )
            }
            _ => (*n, 1.0, 0.0),
        };
        l += 0.5 * value;
        for p in 0..T9 {
            first[p] += 0.5 * d1 * np[p];
            for q in 0..T9 {
                second[p][q] += 0.5 * (d1 * npq[p][q] + d2 * np[p] * np[q]);
            }
        }
    }
    (l, first, second)
}

/// One curvature residual `r = s y`, `y = P u`, `s = √c / l^{3/2}` (4 numbers), its
/// Jacobian columns `J_p = s Y_p + s_p y` and its second-order Hessian part `S_pq = r·∂²r_pq
/// = s_pq (r·y) + s_p (r·Y_q) + s_q (r·Y_p) + s (r·∂²y_pq)`, where `Y_p = ∂y/∂p` (`P t` for a
/// tangent direction t of a or c, `−(2 + b·u) t − b (u·t)` of b) and, for z ⊥ b,
/// `z·∂²y_pq` is nonzero only in the blocks `aa: −δₖₗ z·a`, `cc: −δₖₗ z·c`,
/// `bb: −((z·B_k)(u·B_l) + (z·B_l)(u·B_k))`, `ba: −(z·B_k)(b·A_l)`, `bc: −(z·B_k)(b·C_l)`
/// (from `∂(P u)` and the retraction's second order; r ⊥ b drops the terms along b).
/// Zero everything where the width is zero. `S` is written into `second` when it is given,
/// only its lower triangle (q ≤ p): the part the band holds (in the caller's block, so that
/// no 9×9 array is cleared, filled and copied out a term).
fn curvature_residual(
    q: [Quat<f64>; 3],
    t: [[Quat<f64>; DIM]; 3],
    key_weight: f64,
    w: Width,
    second: Option<&mut Block>,
) -> (Quat<f64>, [Quat<f64>; T9]) {
    let zero = Quat::zero();
    let [a, b, c] = q;
    // Width 1 has no derivatives: no blocks of zeros made for it.
    let shaped = (w != Width::Unit).then(|| width(q, t, w));
    let (l, lp) = shaped
        .as_ref()
        .map_or((1.0, [0.0; T9]), |(l, lp, _)| (*l, *lp));
    if l.is_nan() || l <= 0.0 {
        if let Some(second) = second {
            for (p, row) in second.iter_mut().enumerate() {
                row[..=p].fill(0.0);
            }
        }
        return (zero, [zero; T9]);
    }
    let u = a - b * 2.0 + c;
    let bu = b.dot(u);
    let y = u - b * bu;
    let s = key_weight.sqrt() / (l * l.sqrt());
    let r = y * s;
    let dir = |p: usize| t[p / DIM][p % DIM];
    let yp: [Quat<f64>; T9] = core::array::from_fn(|p| {
        let x = dir(p);
        if p / DIM == 1 {
            x * -(2.0 + bu) - b * u.dot(x)
        } else {
            x - b * b.dot(x)
        }
    });
    let sp: [f64; T9] = core::array::from_fn(|p| -1.5 * s * lp[p] / l);
    let cols = core::array::from_fn(|p| yp[p] * s + y * sp[p]);
    let Some(second) = second else {
        return (r, cols);
    };
    // r·∂²y, blockwise, in the lower triangle: the blocks aa, cc (diagonal), bb, ba and cb.
    let (ra, rc) = (r.dot(a), r.dot(c));
    let rb: [f64; DIM] = core::array::from_fn(|k| r.dot(t[1][k]));
    let ub: [f64; DIM] = core::array::from_fn(|k| u.dot(t[1][k]));
    let ba: [f64; DIM] = core::array::from_fn(|k| b.dot(t[0][k]));
    let bc: [f64; DIM] = core::array::from_fn(|k| b.dot(t[2][k]));
    for k in 0..DIM {
        // The zeros of the lower triangle: the aa and cc blocks off their diagonals, the
        // whole ca block (written one by one: a fill of each row's part was a memset call).
        for m in 0..k {
            second[k][m] = 0.0;
            second[2 * DIM + k][2 * DIM + m] = 0.0;
        }
        for x in &mut second[2 * DIM + k][..DIM] {
            *x = 0.0;
        }
        second[k][k] = -ra;
        second[2 * DIM + k][2 * DIM + k] = -rc;
        for m in 0..DIM {
            if m <= k {
                second[DIM + k][DIM + m] = -(rb[k] * ub[m] + rb[m] * ub[k]);
            }
            second[DIM + k][m] = -rb[k] * ba[m];
            second[2 * DIM + m][DIM + k] = -rb[k] * bc[m];
        }
    }
    // S in place of r·∂²y.
    match &shaped {
        None => {
            for (p, row) in second.iter_mut().enumerate() {
                for x in &mut row[..=p] {
                    *x *= s;
                }
            }
        }
        Some((_, _, lpq)) => {
            let ry = r.dot(y);
            let ryp: [f64; T9] = core::array::from_fn(|p| r.dot(yp[p]));
            for (p, row) in second.iter_mut().enumerate() {
                for (qq, x) in row[..=p].iter_mut().enumerate() {
                    let spq = s * (3.75 * lp[p] * lp[qq] / (l * l) - 1.5 * lpq[p][qq] / l);
                    *x = spq * ry + sp[p] * ryp[qq] + sp[qq] * ryp[p] + s * *x;
                }
            }
        }
    }
    (r, cols)
}

/// One velocity residual `v = √c_w (n₁ − n₂)` (chords to a and to c, [`chord`]), its
/// Jacobian entries and its second-order Hessian part `v ∂²v`.
fn velocity_residual(
    q: [Quat<f64>; 3],
    t: [[Quat<f64>; DIM]; 3],
    weight: f64,
) -> (f64, [f64; T9], Block) {
    let s = weight.sqrt();
    let (n1, p1, s1) = chord(q, t, 0);
    let (n2, p2, s2) = chord(q, t, 2);
    let v = s * (n1 - n2);
    let cols = core::array::from_fn(|p| s * (p1[p] - p2[p]));
    let second =
        core::array::from_fn(|p| core::array::from_fn(|qq| v * s * (s1[p][qq] - s2[p][qq])));
    (v, cols, second)
}

/// The energy F of unit frames `q` (see the module docs).
fn energy(q: &[Quat<f64>], is_key: &[bool], cfg: &SpringConfig) -> f64 {
    let mut f = 0.0;
    for i in 1..q.len().saturating_sub(1) {
        let c = if is_key[i] { cfg.key_weight } else { 1.0 };
        let (a, b, cc) = (q[i - 1], q[i], q[i + 1]);
        let (n1, n2) = ((b - a).norm(), (b - cc).norm());
        let angle = |n: f64| 2.0 * (n / 2.0).min(1.0).asin();
        let l = match cfg.width {
            Width::Unit => 1.0,
            Width::Centered => (n1 + n2) * 0.5,
            Width::Angle => (angle(n1) + angle(n2)) * 0.5,
        };
        if l > 0.0 {
            let u = a - b * 2.0 + cc;
            let pu = u - b * b.dot(u);
            f += c * pu.dot(pu) / (l * l * l);
        }
        if cfg.velocity_penalty > 0.0 {
            let w = n1 - n2;
            f += cfg.velocity_penalty * w * w;
        }
    }
    f
}

/// `JᵀJ + S` (into `h`) and `Jᵀr` (into `g`) at unit frames `q`: key frames weighted by
/// c_k, `fixed` frames (the keys, and the neighbours of keys with a velocity) held (their
/// unknowns get the identity and no gradient); returns F.
fn normal_equations(
    q: &[Quat<f64>],
    is_key: &[bool],
    fixed: &[bool],
    cfg: &SpringConfig,
    h: &mut Band,
    g: &mut [f64],
    hessian: bool,
) -> f64 {
    if hessian {
        h.clear();
    }
    g.fill(0.0);
    let n = q.len();
    let mut f = 0.0;
    let bases: Vec<[Quat<f64>; DIM]> = q.iter().map(|x| basis(*x)).collect();
    // A term's second-order block (its lower triangle), written by each term in turn.
    let mut sr: Block = [[0.0; T9]; T9];
    for i in 1..n.saturating_sub(1) {
        let frames = [q[i - 1], q[i], q[i + 1]];
        let t = [bases[i - 1], bases[i], bases[i + 1]];
        let c = if is_key[i] { cfg.key_weight } else { 1.0 };
        let (r, jr) = curvature_residual(frames, t, c, cfg.width, hessian.then_some(&mut sr));
        // (No zero blocks made up for an absent velocity term: the sums below skip it.)
        let vel = (cfg.velocity_penalty > 0.0)
            .then(|| velocity_residual(frames, t, cfg.velocity_penalty));
        let (v, jv) = vel
            .as_ref()
            .map_or((0.0, [0.0; T9]), |(v, jv, _)| (*v, *jv));
        f += r.dot(r) + v * v;
        // The term's nine unknowns are consecutive, from `base`; a key frame's columns are
        // zero (it does not move). The columns as rows of numbers (four components and the
        // velocity residual's entry), so that each band row takes one run of sums.
        let base = (i - 1) * DIM;
        let free: [f64; T9] =
            core::array::from_fn(|p| if fixed[i - 1 + p / DIM] { 0.0 } else { 1.0 });
        let mut m = [[0.0f64; T9]; 5];
        for p in 0..T9 {
            let [cw, cx, cy, cz] = jr[p].to_array();
            m[0][p] = cw * free[p];
            m[1][p] = cx * free[p];
            m[2][p] = cy * free[p];
            m[3][p] = cz * free[p];
            m[4][p] = jv[p] * free[p];
        }
        let rv = [r.w, r.x, r.y, r.z, v];
        for p in 0..T9 {
            g[base + p] += (0..5).map(|c| m[c][p] * rv[c]).sum::<f64>();
        }
        if !hessian {
            continue;
        }
        for p in 0..T9 {
            // Row base + p holds columns base + p − BAND … base + p; those of this term,
            // base … base + p, are its last p + 1 entries.
            let row = &mut h.row_mut(base + p)[BAND - p..];
            if let Some((_, _, sv)) = &vel {
                for (q, x) in row.iter_mut().enumerate() {
                    *x += m[0][p] * m[0][q]
                        + m[1][p] * m[1][q]
                        + m[2][p] * m[2][q]
                        + m[3][p] * m[3][q]
                        + m[4][p] * m[4][q]
                        + (sr[p][q] + sv[p][q]) * free[p] * free[q];
                }
            } else {
                // No velocity term: its row of m and its part of S are zero.
                for (q, x) in row.iter_mut().enumerate() {
                    *x += m[0][p] * m[0][q]
                        + m[1][p] * m[1][q]
                        + m[2][p] * m[2][q]
                        + m[3][p] * m[3][q]
                        + sr[p][q] * free[p] * free[q];
                }
            }
        }
    }
    if hessian {
        for (i, held) in fixed.iter().enumerate() {
            if *held {
                for k in 0..DIM {
                    h.add(i * DIM + k, i * DIM + k, 1.0);
                }
            }
        }
    }
    f
}

fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// The frames moved by `delta` in their tangent spaces and normalized.
fn retract(q: &[Quat<f64>], delta: &[f64]) -> Vec<Quat<f64>> {
    q.iter()
        .enumerate()
        .map(|(i, qi)| {
            let t = basis(*qi);
            let d = &delta[i * DIM..i * DIM + DIM];
            let moved = *qi + t[0] * d[0] + t[1] * d[1] + t[2] * d[2];
            moved / moved.norm()
        })
        .collect()
}

/// Honours the keys' angular velocities (§8.2; [`KeyFrames::with_velocities`]) on the frames:
/// each neighbour of a key with velocity ω is set to `exp(½ Δt (0, ω)) q_key` (Δt its
/// parameter offset from the key) and held, so that the one-sided differences of the curve
/// at the key are ω on both sides. Returns which frames are held (keys included). Errors:
/// a neighbour that is itself a key or held by another key's velocity.
fn pin_velocities(keys: &KeyFrames<f64>, frames: &mut [Frame<f64>]) -> Result<Vec<bool>> {
    let mut fixed: Vec<bool> = frames.iter().map(|f| f.key.is_some()).collect();
    if keys.velocities().is_none() {
        return Ok(fixed);
    }
    for i in 0..frames.len() {
        let Some(k) = frames[i].key else { continue };
        let Some(w) = keys.velocity(k) else { continue };
        for j in [i.wrapping_sub(1), i + 1] {
            if j >= frames.len() {
                continue;
            }
            if fixed[j] {
                return Err(Error::KeyVelocity {
                    index: k,
                    why: "the frame beside it is a key or held by another velocity: ask for more frames",
                });
            }
            let dt = frames[j].t - frames[i].t;
            frames[j].q = Quat::pure(w * (0.5 * dt)).exp() * frames[i].q;
            fixed[j] = true;
        }
    }
    Ok(fixed)
}

/// Frame counts above which the solve starts from a coarser solution.
const SINGLE_LEVEL: usize = 20_000;
/// How much coarser each coarser level is.
const COARSER: usize = 8;
/// A step that lowers F by less than this share of it, from a point whose gradient is not
/// half the last one's, ends the solve (`Stopped::Rounding`): at 10⁶ frames the residuals
/// (second differences of 10⁻¹¹) carry about six digits, F about nine, and the gradient
/// stays at its rounding floor.
const STAGNANT: f64 = 1e-9;

/// The converged solver for [`super::spring`] (f64): from Slerp or Squad through the keys
/// at `frames` frames, Gauss–Newton to a stationary point of F (module docs), at most
/// `max_iterations` steps, stopping when the projected gradient has fallen to `tolerance`
/// times the start curve's, or when a step no longer lowers F by more than 1e-9 of it.
///
/// Past 20 000 frames the start is the solution at an eighth of the frames (solved the same
/// way), resampled: the second differences are then too small for f64 to resolve the
/// curve's slowest modes (the normal equations' condition grows like N⁴), which a coarse
/// solve settles, leaving the fine steps the local corrections they converge on at once.
/// The history holds every level, coarse to fine.
pub(super) fn spring_converged(
    keys: &KeyFrames<f64>,
    frames: usize,
    timing: Timing,
    cfg: &SpringConfig,
    tolerance: f64,
    max_iterations: usize,
    progress: &mut dyn FnMut(&Progress),
) -> Result<SpringResult<f64>> {
    let method = match cfg.start {
        Start::Slerp => Method::Slerp,
        Start::Squad => Method::Squad,
    };
    let initial = interpolate(method, keys, frames, timing)?;
    let is_key: Vec<bool> = initial.iter().map(|f| f.key.is_some()).collect();
    let mut initial = initial;
    let fixed = pin_velocities(keys, &mut initial)?;
    let n = initial.len();
    let unknowns = n.checked_mul(DIM).ok_or(Error::TooManyFrames { frames })?;
    let mut h = Band::zeros(unknowns, BAND)?;
    let mut g = vec![0.0; unknowns];
    let coarse = (frames / COARSER).max(4 * keys.len().saturating_sub(1) + 1);
    // The start curve's gradient, which the tolerance is relative to: here, or at the first
    // iteration when the solve starts from that curve.
    let mut g0 = None;
    let (mut current, mut history) = if frames > SINGLE_LEVEL && coarse < frames {
        let q0: Vec<Quat<f64>> = initial.iter().map(|f| f.q).collect();
        normal_equations(&q0, &is_key, &fixed, cfg, &mut h, &mut g, false);
        g0 = Some(2.0 * norm(&g));
        let c = spring_converged(
            keys,
            coarse,
            timing,
            cfg,
            tolerance,
            max_iterations,
            progress,
        )?;
        let mut fine = super::spring::resample(keys, &c.frames, frames, timing)?;
        pin_velocities(keys, &mut fine)?;
        (fine, c.history)
    } else {
        (initial, Vec::new())
    };
    let level = history.last().map_or(0, |r: &EnergyRecord| r.level + 1);
    let mut q: Vec<Quat<f64>> = current.iter().map(|f| f.q).collect();
    let mut mu = 0.0f64;
    let mut stopped = Stopped::MaxIterations;
    let mut stagnant = false;
    let mut polished = false;
    let mut last_gradient = f64::INFINITY;
    for it in 0..=max_iterations {
        // After the polishing step only F and the gradient are wanted (the solve ends).
        let f = normal_equations(&q, &is_key, &fixed, cfg, &mut h, &mut g, !polished);
        let gn = 2.0 * norm(&g);
        history.push(EnergyRecord {
            level,
            iteration: it,
            frames: n,
            energy: f,
            gradient_norm: gn,
        });
        if !(f.is_finite() && gn.is_finite()) {
            return Err(Error::BadParameter {
                what: "the converged Spring's energy",
                rule: "finite (the keys or options give a curve past f64's range)",
                value: f,
            });
        }
        if polished || gn == 0.0 {
            stopped = Stopped::Converged;
            break;
        }
        // At the tolerance, one more step: Newton's convergence is quadratic, so it takes
        // the remaining error (slowest, along the curve's smooth modes) down to rounding,
        // and the result no longer depends on where the solve started.
        polished = gn <= tolerance * *g0.get_or_insert(gn);
        if stagnant && !polished {
            stopped = Stopped::Rounding;
            break;
        }
        if it == max_iterations {
            break;
        }
        // Levenberg–Marquardt: from the last μ, raised tenfold until a step lowers F. The
        // matrix is factored in place; after a refused step it is assembled again.
        // Marquardt's scaling by the diagonal, made positive: the Newton term can make an
        // entry negative, and the damped matrix must become positive definite as μ grows.
        let largest = (0..h.len()).fold(0.0f64, |m, i| m.max(h.diagonal(i).abs()));
        let diagonal: Vec<f64> = (0..h.len())
            .map(|i| h.diagonal(i).abs().max(1e-12 * largest))
            .collect();
        let mut accepted = None;
        for attempt in 0..40 {
            if attempt > 0 {
                normal_equations(&q, &is_key, &fixed, cfg, &mut h, &mut g, true);
            }
            if mu > 0.0 {
                for (i, d) in diagonal.iter().enumerate() {
                    h.add(i, i, mu * d);
                }
            }
            if h.cholesky() {
                let mut delta: Vec<f64> = g.iter().map(|x| -x).collect();
                h.solve(&mut delta);
                let trial = retract(&q, &delta);
                let ft = energy(&trial, &is_key, cfg);
                // Lower, or (a full Newton step at the minimum) equal to F's rounding.
                if ft < f || (mu == 0.0 && ft <= f * (1.0 + 1e-13)) {
                    accepted = Some((trial, ft));
                    break;
                }
            }
            mu = if mu == 0.0 { 1e-12 } else { mu * 10.0 };
        }
        progress(&Progress {
            level,
            levels: level + 1,
            iteration: it + 1,
            iterations: max_iterations,
            energy: f,
        });
        match accepted {
            Some((trial, ft)) => {
                q = trial;
                mu = if mu < 1e-12 { 0.0 } else { mu * 0.1 };
                // A gain that is rounding ends the solve after this step (unless its
                // gradient meets the tolerance): F no longer falls, nor the gradient by half.
                stagnant = f - ft <= STAGNANT * f && gn >= 0.5 * last_gradient;
                last_gradient = gn;
            }
            None => {
                stopped = Stopped::Rounding;
                break;
            }
        }
    }
    for (fr, qi) in current.iter_mut().zip(q) {
        fr.q = qi;
    }
    Ok(SpringResult {
        frames: current,
        history,
        stopped,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interp::spring::energy_and_gradient;
    use crate::interp::{examples, Hemisphere};

    /// `2 Jᵀr` is the report solver's analytic gradient of F projected onto each free
    /// frame's tangent space, for every width, with key and velocity weights.
    #[test]
    fn the_normal_equations_hold_the_projected_gradient() {
        let set = examples::table_5_1();
        let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::AsGiven).unwrap();
        // A curve off the optimum: Squad, its frames pushed a little off it and normalized.
        let mut q: Vec<Quat<f64>> = interpolate(Method::Squad, &keys, 41, Timing::Angle)
            .unwrap()
            .iter()
            .map(|f| f.q)
            .collect();
        let is_key: Vec<bool> = interpolate(Method::Squad, &keys, 41, Timing::Angle)
            .unwrap()
            .iter()
            .map(|f| f.key.is_some())
            .collect();
        for (i, x) in q.iter_mut().enumerate() {
            if !is_key[i] {
                let p = Quat::new(0.0, (i as f64).sin(), (i as f64 * 1.7).cos(), 0.3) * 0.01;
                *x = (*x + p).normalize().unwrap();
            }
        }
        for width in [Width::Unit, Width::Centered, Width::Angle] {
            let mut cfg = SpringConfig::converged();
            cfg.width = width;
            cfg.key_weight = 1.7;
            cfg.velocity_penalty = 0.4;
            let mut h = Band::zeros(q.len() * DIM, BAND).unwrap();
            let mut g = vec![0.0; q.len() * DIM];
            let f = normal_equations(&q, &is_key, &is_key, &cfg, &mut h, &mut g, true);
            let (f_report, grad) = energy_and_gradient(&q, &is_key, &cfg);
            assert!(
                (f - f_report).abs() <= 1e-12 * f_report,
                "{width:?}: {f} vs {f_report}"
            );
            for (i, gi) in grad.iter().enumerate() {
                let t = basis(q[i]);
                for k in 0..DIM {
                    let want = gi.dot(t[k]);
                    let got = 2.0 * g[i * DIM + k];
                    assert!(
                        (got - want).abs() <= 1e-9 * (1.0 + want.abs()),
                        "{width:?} frame {i} {k}: {got} vs {want}"
                    );
                }
            }
        }
    }

    /// `JᵀJ + S` is half the Hessian of F pulled back by the retraction, `F(R_q(δ))`, at
    /// δ = 0: against its central second differences, entry by entry over a stretch of
    /// frames, for every width with key and velocity weights.
    #[test]
    fn the_normal_matrix_is_the_hessian() {
        let set = examples::table_5_1();
        let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::AsGiven).unwrap();
        let frames = interpolate(Method::Squad, &keys, 31, Timing::Angle).unwrap();
        let is_key: Vec<bool> = frames.iter().map(|f| f.key.is_some()).collect();
        let mut q: Vec<Quat<f64>> = frames.iter().map(|f| f.q).collect();
        for (i, x) in q.iter_mut().enumerate() {
            if !is_key[i] {
                let p = Quat::new(0.0, (i as f64).sin(), (i as f64 * 1.7).cos(), 0.3) * 0.02;
                *x = (*x + p).normalize().unwrap();
            }
        }
        let n = q.len() * DIM;
        for width in [Width::Unit, Width::Centered, Width::Angle] {
            let mut cfg = SpringConfig::converged();
            cfg.width = width;
            cfg.key_weight = 1.7;
            cfg.velocity_penalty = 0.4;
            let mut h = Band::zeros(n, BAND).unwrap();
            let mut g = vec![0.0; n];
            normal_equations(&q, &is_key, &is_key, &cfg, &mut h, &mut g, true);
            let at = |d: &[(usize, f64)]| {
                let mut delta = vec![0.0; n];
                for (i, v) in d {
                    delta[*i] = *v;
                }
                energy(&retract(&q, &delta), &is_key, &cfg)
            };
            // Steps small enough for the chord widths' third derivatives (the chords are
            // ~0.07), large enough for F's rounding.
            let e = 4e-5;
            // The unknowns of frames 5–12, every pair within the band (key frames, which do
            // not move, left out).
            let free = |i: usize| !is_key[i / DIM];
            assert!(
                (15..39).filter(|i| !free(*i)).count() > 0,
                "a key among them"
            );
            for i in (15usize..39).filter(|i| free(*i)) {
                for j in (i.saturating_sub(BAND)..=i).filter(|j| free(*j)) {
                    let fd = if i == j {
                        (at(&[(i, e)]) - 2.0 * at(&[]) + at(&[(i, -e)])) / (e * e)
                    } else {
                        (at(&[(i, e), (j, e)]) - at(&[(i, e), (j, -e)]) - at(&[(i, -e), (j, e)])
                            + at(&[(i, -e), (j, -e)]))
                            / (4.0 * e * e)
                    };
                    let got = 2.0 * h.row_mut(i)[BAND - (i - j)];
                    assert!(
                        (got - fd).abs() <= 3e-5 * (1.0 + fd.abs()),
                        "{width:?} ({i}, {j}): {got} vs {fd}"
                    );
                }
            }
        }
    }
}
