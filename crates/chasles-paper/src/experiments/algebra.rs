//! The core algebra by number: Dam et al. 1998, App. A and B.1 (the report's Euler
//! convention `R = Rz(γ) Ry(β) Rx(α)`), App. B.4 against Shepperd's method near 180°,
//! §4.1 and Figure 4.1 (the order of two rotations matters), §4.1 and Figure 4.3 (gimbal
//! lock loses a degree of freedom; Figure 4.2's gimbal rings are not drawn), App. B.2 (extraction at gimbal lock),
//! Definitions 14–16 (exp, log and powers near the identity and
//! near 2π); Kavan et al. 2006, eq. (1)–(2) (a rigid motion as a unit dual quaternion, its
//! screw, its powers).

use super::arr;
use crate::claim::Paper::{Dam1998, Kavan2006};
use crate::section::{PaperFigure, Section};
use crate::table::{Cell, Number, Table};
use chasles::{DualQuat, EulerOrder, Mat3, Quat, Vec3};
use std::f64::consts::{FRAC_PI_2, PI};

/// App. A + B.1: Euler angles (0.1, 0.2, 0.3) to a quaternion and a matrix, and back.
pub fn euler_convention() -> Section {
    let mut s = Section::new(
        "Dam et al. App. A + B.1: the report's Euler convention, R = Rz(γ) Ry(β) Rx(α)",
    );
    s.attempt(
        Dam1998,
        "App. A, B.1–B.2",
        "the matrix of Euler angles, R = Rz(γ) Ry(β) Rx(α), gives the angles back",
        |s| -> chasles::Result<_> {
            let angles: [f64; 3] = [0.1, 0.2, 0.3];
            let q = Quat::from_euler(EulerOrder::DAM, angles);
            let m = Mat3::from_euler(EulerOrder::DAM, angles);
            let back = m.to_euler(EulerOrder::DAM)?;
            let err = back
                .angles
                .iter()
                .zip(angles)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            let mut t = Table::new("(α, β, γ) = (0.1, 0.2, 0.3)", &["quantity", "value"]);
            t.row(vec![
                Cell::text("angles (α, β, γ)"),
                Cell::text(arr(&angles)),
            ]);
            t.row(vec![
                Cell::text("quaternion [w, x, y, z]"),
                Cell::text(arr(&q.to_array())),
            ]);
            for (i, row) in m.m.iter().enumerate() {
                t.row(vec![
                    Cell::text(format!("matrix (B.1), row {}", i + 1)),
                    Cell::text(arr(row)),
                ]);
            }
            t.row(vec![
                Cell::text("back to angles"),
                Cell::text(arr(&back.angles)),
            ]);
            s.table(t);
            Ok((format!("angles back with error {err:.1e}"), err < 1e-12))
        },
    );
    s
}

/// App. B.4 (the trace formula) against the largest-diagonal choice, at angles π − 10⁻ᵏ.
pub fn b4_near_half_turn() -> Section {
    let mut s = Section::new("Dam et al. App. B.4 versus Shepperd's method near 180°");
    s.attempt(
        Dam1998,
        "App. B.4",
        "the quaternion is recovered from the trace, dividing by 4s with s = cos(angle/2): it loses accuracy as the angle nears 180° (our fix: Shepperd's largest-diagonal choice)",
        |s| -> chasles::Result<_> {
            s.text("B.4 divides by 4s, s = cos(angle/2) → 0. Error of the recovered quaternion:");
            let mut t = Table::new(
                "rotation about (1, 2, 3) by π − 10⁻ᵏ",
                &["angle", "trace-only (B.4)", "largest-diagonal (ours)"],
            );
            let axis = Vec3::new(1.0, 2.0, 3.0);
            let mut at_8 = (f64::NAN, f64::NAN);
            for k in [2, 4, 6, 8, 10] {
                let q = Quat::from_axis_angle(axis, PI - 10f64.powi(-k))?;
                let m = q.to_rotation_matrix();
                let dist = |p: Quat<f64>| (p - q).norm().min((p + q).norm());
                let trace = dist(Quat::from_rotation_matrix_trace_only(&m));
                let ours = dist(Quat::from_rotation_matrix(&m)?);
                t.row(vec![
                    Cell::text(format!("π − 1e-{k}")),
                    Cell::Number(Number::sci(trace, 2)),
                    Cell::Number(Number::sci(ours, 2)),
                ]);
                if k == 8 {
                    at_8 = (trace, ours);
                }
            }
            s.table(t);
            let (trace, ours) = at_8;
            Ok((
                format!("at π − 1e-8: trace-only error {trace:.1e}, ours {ours:.1e}"),
                trace > 1e3 * ours && ours < 1e-12,
            ))
        },
    );
    s
}

/// App. B.2: at β = π/2 only α − γ is determined; γ = 0 is chosen.
pub fn gimbal_lock() -> Section {
    let mut s = Section::new("Dam et al. App. B.2: gimbal lock (β = π/2) sets γ = 0");
    s.attempt(
        Dam1998,
        "App. B.2",
        "at β = π/2 only α − γ is determined; setting γ = 0 still rebuilds the matrix",
        |s| -> chasles::Result<_> {
            let m = Mat3::from_euler(EulerOrder::DAM, [0.4, FRAC_PI_2, -1.1]);
            let e = m.to_euler(EulerOrder::DAM)?;
            let rebuilt = Mat3::from_euler(EulerOrder::DAM, e.angles).max_abs_diff(&m);
            s.text(format!(
                "built from (0.4, π/2, −1.1); extracted {} gimbal_lock={}",
                arr(&e.angles),
                e.gimbal_lock
            ));
            s.text(format!(
                "α − γ = 1.5 is all the matrix knows; rebuilt matrix error {rebuilt:.1e}"
            ));
            Ok((
                format!(
                    "extracted γ = {:.1e}, rebuilt matrix error {rebuilt:.1e}",
                    e.angles[2]
                ),
                e.gimbal_lock && e.angles[2] == 0.0 && rebuilt < 1e-12,
            ))
        },
    );
    s
}

/// §4.1, Figure 4.1: the object rotated by π/2 about x and then π/4 about y, and in the
/// other order (fixed axes: `Ry(π/4) Rx(π/2)` against `Rx(π/2) Ry(π/4)`).
pub fn figure_4_1() -> Section {
    let mut s = Section::new("Dam et al. §4.1, Figure 4.1: the order of two rotations matters");
    let x = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), FRAC_PI_2);
    let y = Quat::from_axis_angle(Vec3::new(0.0, 1.0, 0.0), PI / 4.0);
    s.attempt(
        Dam1998,
        "§4.1, Figure 4.1",
        "By rotating the object in figure 4.1.i the angle π/2 about x and then π/4 about y the result is 4.1.ii. If the convention y, x, z is used instead [...] yielding 4.1.iii.",
        |s| -> chasles::Result<_> {
            let (x, y) = (x?, y?);
            let (xy, yx) = (y * x, x * y);
            let apart = xy.angle_to(yx)?;
            let size = 260;
            let picture = chasles_viz::Image::side_by_side(&[
                chasles_viz::letter::draw(Quat::identity(), "i", size),
                chasles_viz::letter::draw(xy, "ii: x then y", size),
                chasles_viz::letter::draw(yx, "iii: y then x", size),
            ]);
            s.paper_figure(
                PaperFigure::new(Dam1998, "4.1", "In the coordinate system the x -axis points to the right, the y -axis points up and the z -axis point to the left. Figures ii) and iii) show the result of applying different rotation conventions to the object in figure i)."),
                "dam-figure-4-1.png",
                Ok::<_, String>(picture.png()),
                "The extruded R (i) turned by π/2 about x and then π/4 about y (ii), and by π/4 about y and then π/2 about x (iii), about fixed axes; seen from slightly above and to the right, y up.",
            );
            Ok((
                format!("the two results differ by a rotation of {apart:.4} rad ({:.1}°)", apart.to_degrees()),
                apart > 0.1,
            ))
        },
    );
    s
}

/// The angular velocity of the rotation made by the report's Euler angles (`R = Rz Ry Rx`)
/// per unit rate of each angle, at `angles`: the Jacobian's three columns, by central
/// differences of the quaternions (`vec(q(θ + h) q(θ − h)*) / h`, the angle `2h ω`'s
/// half-angle sine over h).
fn euler_jacobian(angles: [f64; 3]) -> [Vec3<f64>; 3] {
    let h = 1e-6;
    std::array::from_fn(|k| {
        let mut a = angles;
        let mut b = angles;
        a[k] += h;
        b[k] -= h;
        let d =
            Quat::from_euler(EulerOrder::DAM, a) * Quat::from_euler(EulerOrder::DAM, b).conjugate();
        d.vector() * (1.0 / h)
    })
}

/// §4.1, Figure 4.3: at β = π/2 the x and the z rotation act about the same axis —
/// the determinant of the Euler angles' Jacobian falls to 0 (one degree of freedom lost),
/// and turning α or γ gives the same motion.
pub fn gimbal_lock_figure() -> Section {
    let mut s = Section::new("Dam et al. §4.1, Figure 4.3: gimbal lock loses a degree of freedom");
    s.attempt(
        Dam1998,
        "§4.1, Figure 4.3",
        "In this situation the x and the z -rotation act about the same axis. This phenomenon is called gimbal lock.",
        |s| -> Result<_, String> {
            let det = |beta: f64| {
                let [a, b, c] = euler_jacobian([0.4, beta, -0.2]);
                a.dot(b.cross(c))
            };
            let mut t = Table::new(
                "the determinant of the Jacobian of (α, β, γ) ↦ Rz(γ) Ry(β) Rx(α) (angular velocity per unit angle rate; |det| = |cos β|)",
                &["β", "det", "|α column × γ column|"],
            );
            for (name, beta) in [("0", 0.0), ("π/4", PI / 4.0), ("π/2 − 0.01", FRAC_PI_2 - 0.01), ("π/2", FRAC_PI_2)] {
                let [a, _, c] = euler_jacobian([0.4, beta, -0.2]);
                t.row(vec![
                    Cell::text(name),
                    Cell::Number(Number::sci(det(beta), 2)),
                    Cell::Number(Number::sci(a.cross(c).norm(), 2)),
                ]);
            }
            s.table(t);
            // α swept and γ swept at β = π/2: the same motion (α up is γ down).
            let n = 7;
            let sweep = |k: usize| -> Vec<Quat<f64>> {
                (0..n)
                    .map(|i| {
                        let v = -0.9 + 1.8 * i as f64 / (n - 1) as f64;
                        let mut e = [0.0, FRAC_PI_2, 0.0];
                        e[k] = if k == 0 { v } else { -v };
                        Quat::from_euler(EulerOrder::DAM, e)
                    })
                    .collect()
            };
            let (by_alpha, by_gamma) = (sweep(0), sweep(2));
            let same = by_alpha
                .iter()
                .zip(&by_gamma)
                .map(|(a, g)| a.angle_to(*g).map_err(|e| e.to_string()))
                .try_fold(0.0f64, |m, d| d.map(|d| m.max(d)))?;
            let picture = chasles_viz::Image::stacked(&[
                chasles_viz::letter::strip(&by_alpha, n, 150),
                chasles_viz::letter::strip(&by_gamma, n, 150),
            ]);
            s.paper_figure(
                PaperFigure::new(Dam1998, "4.3", "In the coordinate system the x -axis points up, the y -axis points to the left and the z -axis points to the right. In this situation the x and the z -rotation act about the same axis. This phenomenon is called gimbal lock."),
                "dam-figure-4-3.png",
                Ok::<_, String>(picture.png()),
                &format!("At β = π/2: top, α swept from −0.9 to 0.9 rad (γ = 0); bottom, γ swept from 0.9 to −0.9 rad (α = 0). The two rows are the same motion (largest difference {same:.1e} rad): only α − γ is felt, one degree of freedom is gone."),
            );
            let (free, locked) = (det(0.3), det(FRAC_PI_2));
            Ok((
                format!("Jacobian determinant {free:.3} at β = 0.3 (= cos 0.3), {locked:.1e} at β = π/2; α and γ sweeps at the lock differ by {same:.1e} rad"),
                (free - 0.3f64.cos()).abs() < 1e-6 && locked.abs() < 1e-9 && same < 1e-9,
            ))
        },
    );
    s
}

/// Definitions 14–16: exp(log q) = q and (q^½)² = q next to the identity and to 2π.
pub fn exp_log() -> Section {
    let mut s = Section::new(
        "Dam et al. Definitions 14–16: exp, log and powers near the identity and near 2π",
    );
    s.attempt(
        Dam1998,
        "Definitions 14–16",
        "exp(log q) = q and (q^½)² = q, including next to the identity and to 2π where sin(θ)/θ and log need care",
        |s| -> chasles::Result<_> {
            let axis = Vec3::new(1.0, 2.0, 3.0);
            let mut t = Table::new(
                "rotations about (1, 2, 3)",
                &["rotation angle", "|exp(log q) − q|", "|(q^½)² − q|"],
            );
            let mut worst = 0.0f64;
            for d in [1e-12, 1e-6, 1e-2] {
                for (label, q) in [
                    (format!("{d:.0e}"), Quat::from_axis_angle(axis, d)?),
                    (format!("2π − {d:.0e}"), -Quat::from_axis_angle(axis, d)?),
                ] {
                    let e1 = (q.log()?.exp() - q).norm();
                    let h = q.powf(0.5)?;
                    let e2 = (h * h - q).norm();
                    t.row(vec![
                        Cell::text(label),
                        Cell::Number(Number::sci(e1, 1)),
                        Cell::Number(Number::sci(e2, 1)),
                    ]);
                    worst = worst.max(e1).max(e2);
                }
            }
            s.table(t);
            Ok((
                format!("worst error over angles 1e-12 … 2π − 1e-12: {worst:.1e}"),
                worst < 1e-12,
            ))
        },
    );
    s
}

/// Kavan et al. eq. (1)–(2): 90° about z then (1, 2, 3) as `q0 + ε ½ t q0`, its screw, a
/// point moved by it and by its 4×4 matrix, its square root; a pure translation's screw.
pub fn dual_quaternion() -> Section {
    let mut s =
        Section::new("Kavan et al. eq. (1) and (2): a rigid motion as a unit dual quaternion");
    s.attempt(
        Kavan2006,
        "eq. (1)–(2), §3",
        "a unit dual quaternion q0 + ε ½ t q0 moves points as its 4×4 matrix does, and q̂^½ applied twice is q̂",
        |s| -> chasles::Result<_> {
            let q = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), FRAC_PI_2)?;
            let dq = DualQuat::from_rotation_translation(q, Vec3::new(1.0, 2.0, 3.0));
            s.text("90° about z, then translate (1, 2, 3):");
            s.text(format!("q̂ = q0 + ε ½ t q0 = {}", arr(&dq.to_array())));
            let sc = dq.to_screw()?;
            s.text(format!(
                "screw: axis {} through {} angle {:.6} slide {:.6} pitch {:.6}",
                arr(&sc.axis.to_array()),
                arr(&sc.point().to_array()),
                sc.angle,
                sc.translation,
                sc.pitch().unwrap_or(f64::INFINITY)
            ));
            let p = Vec3::new(0.5, -1.0, 2.0);
            let by_dq = dq.transform_point(p);
            let point_err = (by_dq - dq.to_matrix4().transform_point(p)).norm();
            s.text(format!(
                "point (0.5, −1, 2) → {} (4×4 matrix agrees to {point_err:.1e})",
                arr(&by_dq.to_array())
            ));
            let h = dq.powf(0.5)?;
            let half_err = ((h * h) - dq)
                .to_array()
                .iter()
                .fold(0.0f64, |m, v| m.max(v.abs()));
            s.text(format!(
                "half the screw, q̂^½: {} ; applied twice, error {half_err:.1e}",
                arr(&h.to_array())
            ));
            let st = DualQuat::from_translation(Vec3::new(0.0, 3.0, 4.0)).to_screw()?;
            s.text(format!(
                "pure translation (0, 3, 4): screw axis {} slide {:.6} (the translation direction)",
                arr(&st.axis.to_array()),
                st.translation
            ));
            Ok((
                format!("point against the matrix {point_err:.1e}; (q̂^½)² against q̂ {half_err:.1e}"),
                point_err < 1e-12 && half_err < 1e-12,
            ))
        },
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Jacobian of the report's Euler angles has determinant cos β: zero at the lock.
    #[test]
    fn the_euler_jacobian_loses_a_rank_at_the_lock() {
        for beta in [-1.2, -0.3, 0.0, 0.7, 1.4, FRAC_PI_2] {
            let [a, b, c] = euler_jacobian([0.4, beta, -0.2]);
            let det = a.dot(b.cross(c));
            assert!((det - beta.cos()).abs() < 1e-8, "β = {beta}: {det}");
        }
        // Both sections' claims hold.
        for s in [figure_4_1(), gimbal_lock_figure()] {
            assert!(s.claims().all(|c| c.verdict.agrees()), "{}", s.title);
            assert_eq!(s.figures().count(), 1);
        }
    }
}
