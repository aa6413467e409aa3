//! Kavan et al. 2006's figures of §3 drawn from the library's own dual quaternions:
//! Figure 2 (a screw motion — the axis, the turn about it and the slide along it, side and
//! top view), Figure 3 (`q^t` against `(−q)^t`: the same rotation, the long and the
//! short way round) and Figure 4 (one DIB iteration for two inputs, in the 2D slice of the
//! tangent space spanned by their logarithms, and the iterates' distance from the exact
//! blend for two and for four inputs). The object is the extruded R of the interpolation pictures (the paper
//! draws a teapot); the axis is a thin bar.

use crate::claim::Paper::Kavan2006;
use crate::section::{PaperFigure, Section};
use chasles::blend::sclerp::sclerp_pow;
use chasles::screw::Screw;
use chasles::{DualQuat, Quat, Vec3};
use chasles_viz::raster::{Canvas, View};
use chasles_viz::Image;

/// Copies of the R scaled by `scale`, each moved by one of `poses` and coloured from pale
/// to dark in order,
/// and, if given, the axis (a point and a direction) as a grey bar, seen from `from` with
/// `up` up, `size` pixels square, `label` in the corner.
fn scene(
    poses: &[DualQuat<f64>],
    axis: Option<(Vec3<f64>, Vec3<f64>)>,
    from: Vec3<f64>,
    up: Vec3<f64>,
    size: usize,
    label: &str,
    scale: f64,
) -> Image {
    let (v, t) = chasles_viz::letter::letter_r(0.6);
    let (mut pos, mut tri, mut colour) = (Vec::new(), Vec::new(), Vec::new());
    let n = poses.len().max(2) - 1;
    for (k, d) in poses.iter().enumerate() {
        let base = pos.len() as u32;
        pos.extend(v.iter().map(|p| d.transform_point(*p * scale)));
        tri.extend(t.iter().map(|x| x.map(|i| i + base)));
        let f = k as f64 / n as f64;
        let c = [
            (235.0 - 60.0 * f) as u8,
            (160.0 - 130.0 * f) as u8,
            (150.0 - 120.0 * f) as u8,
        ];
        colour.extend(std::iter::repeat_n(c, t.len()));
    }
    let focus = pos.clone();
    if let Some((p, s)) = axis {
        // A bar of half-width 0.03 from p − 3s to p + 3s.
        let side = s.any_perpendicular() * 0.03;
        let other = s.cross(side);
        let base = pos.len() as u32;
        for e in [-3.0, 3.0] {
            for c in [side + other, side - other, -side - other, -side + other] {
                pos.push(p + s * e + c);
            }
        }
        let quads = [[0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]];
        for q in quads {
            tri.push([base + q[0], base + q[1], base + q[2]]);
            tri.push([base + q[0], base + q[2], base + q[3]]);
            colour.extend([[110, 110, 120]; 2]);
        }
    }
    let view = View::fit(&focus, from, up, size, size, 0.12);
    let mut c = Canvas::new(size, size, [248, 248, 246]);
    c.mesh(&view, &pos, &tri, |i| {
        colour.get(i).copied().unwrap_or([0, 0, 0])
    });
    c.text(6, 6, 2, label, [60, 60, 60]);
    c.finish()
}

/// Figure 2: a screw motion, side and top view, and the claim that the rigid motion is the
/// screw (its dual quaternion rebuilt from axis, angle and slide).
pub fn figure_2() -> Section {
    let mut s = Section::new("Kavan et al. §3, Figure 2: a rigid motion is a screw motion");
    s.attempt(
        Kavan2006,
        "§3, Figure 2",
        "Each rigid transformation can be described as a screw: rotation about an axis by angle θ0/2 and translation with magnitude θε/2 along the same axis [...] The axis [...] needs not pass through the origin",
        |s| -> chasles::Result<_> {
            // An axis along y through (1.5, 0, 0): 150° about it and 3 along it.
            let axis = Vec3::new(0.0, 1.0, 0.0);
            let point = Vec3::new(1.5, 0.0, 0.0);
            let screw = Screw::from_point(axis, point, 150f64.to_radians(), 3.0)?;
            let q = DualQuat::from_screw(&screw)?;
            let back = q.to_screw()?;
            let err = (back.axis - screw.axis).norm()
                + (back.moment - screw.moment).norm()
                + (back.angle - screw.angle).abs()
                + (back.translation - screw.translation).abs();
            let poses: Vec<DualQuat<f64>> = (0..6)
                .map(|k| sclerp_pow(DualQuat::identity(), q, k as f64 / 5.0))
                .collect::<chasles::Result<_>>()?;
            // A point's path: its distance from the axis stays put, its height grows evenly.
            let p0 = Vec3::new(0.2, 0.0, 0.4);
            let path: Vec<Vec3<f64>> = poses.iter().map(|d| d.transform_point(p0)).collect();
            let radius = |p: Vec3<f64>| {
                let r = p - point;
                (r - axis * r.dot(axis)).norm()
            };
            let drift = path.iter().map(|p| (radius(*p) - radius(p0)).abs()).fold(0.0, f64::max);
            let slide = path.windows(2).map(|w| (w[1] - w[0]).dot(axis)).fold(0.0f64, |m, d| m.max((d - 0.6).abs()));
            let picture = Image::side_by_side(&[
                scene(&poses, Some((point, axis)), Vec3::new(0.0, 0.2, 1.0), axis, 360, "side view", 0.35),
                scene(&poses, Some((point, axis)), axis, Vec3::new(0.0, 0.0, -1.0), 360, "top view", 0.35),
            ]);
            s.paper_figure(
                PaperFigure::new(Kavan2006, "2", "Example of a screw motion, side and top view. Each rigid transformation can be described as a screw: rotation about an axis by angle θ0/2 and translation with magnitude θε/2 along the same axis. The axis, with direction determined by unit vector s0, needs not pass through the origin 0. Its position in space is given by vector p pointing from the origin to some point on the axis. The choice of vector p is not unique, thus dual quaternions work with the unique moment: p × s0."),
                "kavan-figure-2.png",
                Ok::<_, String>(picture.png()),
                "The R moved by ScLERP from the identity to a screw of 150° about an axis along y through (1.5, 0, 0) and 3 along it, at t = 0, 0.2, …, 1 (pale to dark); the grey bar is the axis. Side view: the R climbs the axis evenly; top view (down the axis): it turns about the axis at a constant distance.",
            );
            Ok((
                format!("the motion's screw rebuilt from axis, moment, angle and slide to {err:.0e}; a point keeps its distance from the axis to {drift:.0e} and climbs 0.6 per step to {slide:.0e}"),
                err < 1e-12 && drift < 1e-12 && slide < 1e-12,
            ))
        },
    );
    s
}

/// Figure 3: `q^t` against `(−q)^t` for a rotation by 120°: the same end, 120° the short way
/// and 240° the long way.
pub fn figure_3() -> Section {
    let mut s =
        Section::new("Kavan et al. §3, Figure 3: q^t and (−q)^t, the long and the short way");
    s.attempt(
        Kavan2006,
        "§3, Figure 3",
        "Even though both q0 and −q0 represent the same rotation, the powers q0^t and (−q0)^t are different: one corresponds to clockwise and the second to counterclockwise rotation",
        |s| -> chasles::Result<_> {
            let q = Quat::from_axis_angle(Vec3::new(0.0, 1.0, 0.0), 120f64.to_radians())?;
            let turn = |q: Quat<f64>| -> chasles::Result<Vec<DualQuat<f64>>> {
                (0..7)
                    .map(|k| Ok(DualQuat::from_rotation_translation(q.powf(k as f64 / 6.0)?, Vec3::new(0.0, 0.0, 0.0))))
                    .collect()
            };
            let (short, long) = (turn(q)?, turn(-q)?);
            // The path length: the angle swept step by step.
            let swept = |p: &[DualQuat<f64>]| -> chasles::Result<f64> {
                p.windows(2).map(|w| w[0].real.angle_to(w[1].real)).sum()
            };
            let (a, b) = (swept(&short)?.to_degrees(), swept(&long)?.to_degrees());
            let same_end = short[6].real.angle_to(long[6].real)?;
            let from = Vec3::new(0.0, 1.0, 0.0);
            let up = Vec3::new(0.0, 0.0, -1.0);
            // The R placed off the axis so that its path shows.
            let off = DualQuat::from_rotation_translation(Quat::identity(), Vec3::new(1.2, 0.0, 0.0));
            let placed = |p: &[DualQuat<f64>]| -> Vec<DualQuat<f64>> { p.iter().map(|d| *d * off).collect() };
            let picture = Image::side_by_side(&[
                scene(&placed(&short), Some((Vec3::zero(), from)), from, up, 360, "q power t: the short way", 0.5),
                scene(&placed(&long), Some((Vec3::zero(), from)), from, up, 360, "-q power t: the long way", 0.5),
            ]);
            s.paper_figure(
                PaperFigure::new(Kavan2006, "3", "Dual quaternions inherit the antipodality of classical quaternions. In this example, transformation of the teapot by q0^t for t ∈ [0, 1] produces a counterclockwise rotation (longer trajectory), while transformation by (−q0)^t leads to a clockwise one (shorter trajectory)."),
                "kavan-figure-3.png",
                Ok::<_, String>(picture.png()),
                "An R turned about the vertical axis (seen from above) by q^t and (−q)^t for q the rotation by 120°, t = 0, 1/6, …, 1 (pale to dark): both end at the same rotation, one 120° one way, the other 240° the other way. Here q has w > 0, so q^t is the short way; the paper's q0 has w < 0, for which the roles swap.",
            );
            Ok((
                format!("q^t sweeps {a:.1}°, (−q)^t {b:.1}°, the same end to {same_end:.0e} rad"),
                (a - 120.0).abs() < 1e-9 && (b - 240.0).abs() < 1e-9 && same_end < 1e-12,
            ))
        },
    );
    s
}

/// The distance between two unit dual quaternions as rigid motions: the norm of the
/// logarithm of `a* b` taken to its positive hemisphere (half the rotation angle and half
/// the slide, as a dual 8-vector's length).
fn distance(a: DualQuat<f64>, b: DualQuat<f64>) -> chasles::Result<f64> {
    let l = (a.conjugate() * b)
        .to_positive_hemisphere()
        .log()?
        .to_array();
    Ok(l.iter().map(|x| x * x).sum::<f64>().sqrt())
}

/// The iterates of the library's DIB for `q`, `w` (convex): the DLB start and the blend
/// after each update, until the update is below 1e-14 (at most 12).
fn dib_iterates(q: &[DualQuat<f64>], w: &[f64]) -> chasles::Result<Vec<DualQuat<f64>>> {
    let mut out = Vec::new();
    chasles::blend::dib::dib_convex_observed(q, w, 1e-14, 12, |b| out.push(*b))?;
    Ok(out)
}

/// Figure 4: one DIB iteration for two inputs, drawn in the plane of their logarithms at
/// the DLB start, and the iterates' distances from the exact blend.
pub fn figure_4() -> Section {
    let mut s = Section::new("Kavan et al. §4, Figure 4: one iteration of DIB");
    s.attempt(
        Kavan2006,
        "§4, Figure 4",
        "The logarithm mapping then transforms b̂* q̂1, b̂* q̂2 into the tangent space [...] The blended value x̂ = w1 x̂1 + w2 x̂2 is computed and projected back by the exponential mapping. Finally, multiplication b̂ exp(x̂) yields the unit dual quaternion closer to the exact solution.",
        |s| -> chasles::Result<_> {
            let screw = |axis: Vec3<f64>, point: Vec3<f64>, deg: f64, slide: f64| {
                Screw::from_point(axis, point, deg.to_radians(), slide).and_then(|x| DualQuat::from_screw(&x))
            };
            let q1 = screw(Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.5, 0.0, 0.0), 20.0, 0.2)?;
            let q2 = screw(Vec3::new(0.3, 1.0, 0.2), Vec3::new(0.0, 0.0, 1.0), 150.0, 1.0)?;
            let w = [0.3, 0.7];
            let exact = chasles::blend::sclerp::sclerp(q1, q2, w[1])?;
            let it = dib_iterates(&[q1, q2], &w)?;
            let b0 = it[0];
            // The slice: x̂1, x̂2 at b̂0 and their blend, in the plane they span.
            let x1 = (b0.conjugate() * q1).to_positive_hemisphere().log()?.to_array();
            let x2 = (b0.conjugate() * q2).to_positive_hemisphere().log()?.to_array();
            let xe = (b0.conjugate() * exact).to_positive_hemisphere().log()?.to_array();
            let dot = |a: &[f64; 8], b: &[f64; 8]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
            let n1 = dot(&x1, &x1).sqrt();
            let e1 = x1.map(|v| v / n1);
            let mut e2 = x2;
            let along = dot(&x2, &e1);
            for c in 0..8 {
                e2[c] -= along * e1[c];
            }
            let n2 = dot(&e2, &e2).sqrt();
            let e2 = e2.map(|v| v / n2);
            let at = |x: &[f64; 8]| (dot(x, &e1), dot(x, &e2));
            let blended: [f64; 8] = std::array::from_fn(|c| w[0] * x1[c] + w[1] * x2[c]);
            let off_plane = {
                let (a, b) = at(&xe);
                let r: [f64; 8] = std::array::from_fn(|c| xe[c] - a * e1[c] - b * e2[c]);
                dot(&r, &r).sqrt()
            };
            let seg = |p: (f64, f64)| vec![(0.0, 0.0), p];
            let series = [
                chasles_viz::plot::Series { name: "x̂1 = log(b̂* q̂1)", colour: "#1f5fbf", dashed: false, points: seg(at(&x1)) },
                chasles_viz::plot::Series { name: "x̂2 = log(b̂* q̂2)", colour: "#2a9d4a", dashed: false, points: seg(at(&x2)) },
                chasles_viz::plot::Series { name: "x̂ = w1 x̂1 + w2 x̂2", colour: "#c0392b", dashed: false, points: seg(at(&blended)) },
                chasles_viz::plot::Series { name: "the segment x̂1 x̂2", colour: "#888888", dashed: true, points: vec![at(&x1), at(&x2)] },
            ];
            let svg = chasles_viz::plot::lines_svg(&series, "DIB, one iteration for n = 2, in the tangent space at the DLB start b̂ (the origin)", "along x̂1", "across, in the plane of x̂1 and x̂2");
            s.paper_figure(
                PaperFigure::new(Kavan2006, "4", "Illustration of one iteration of the DIB algorithm for n = 2 in a 2D slice of an 8-dimensional manifold Q̂1 (which is not a hypersphere). First, the input dual quaternions are left-multiplied by b̂*, which maps the initial estimate b̂ onto the identity. The logarithm mapping then transforms b̂* q̂1, b̂* q̂2 into the tangent space of Q̂1 at the identity, giving x̂1 = log(b̂* q̂1), x̂2 = log(b̂* q̂2). The blended value x̂ = w1 x̂1 + w2 x̂2 is computed and projected back by the exponential mapping. Finally, multiplication b̂ exp(x̂) yields the unit dual quaternion closer to the exact solution."),
                "kavan-figure-4.svg",
                Ok::<_, String>(svg.into_bytes()),
                &format!("Two screws (20° and 150°, weights 0.3 and 0.7) mapped by b̂* to the identity and by log into its tangent space, drawn in the plane of x̂1 and x̂2 (the exact blend's logarithm lies in it to {off_plane:.0e}): x̂ = w1 x̂1 + w2 x̂2 on the segment between them; b̂ exp(x̂) is the next iterate."),
            );
            // Distances from the exact blend: n = 2 (exact after one update, Lemma 3) and n = 4.
            let mut t = crate::table::Table::new(
                "distance of DIB's iterates from the exact blend (‖log(b̂_exact* b̂_k)‖)",
                &["inputs", "DLB start", "after 1", "after 2", "after 3", "after 4"],
            );
            let row = |name: &str, it: &[DualQuat<f64>], exact: DualQuat<f64>| -> chasles::Result<Vec<crate::table::Cell>> {
                let mut r = vec![crate::table::Cell::text(name)];
                for k in 0..5 {
                    r.push(match it.get(k) {
                        Some(b) => crate::table::Cell::Number(crate::table::Number::sci(distance(exact, *b)?, 1)),
                        None => crate::table::Cell::text("—"),
                    });
                }
                Ok(r)
            };
            t.row(row("2 (above)", &it, exact)?);
            let q3 = screw(Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0), 80.0, -0.5)?;
            let q4 = screw(Vec3::new(0.0, 1.0, 1.0), Vec3::new(1.0, 0.0, 0.0), 110.0, 0.3)?;
            let four = [q1, q2, q3, q4];
            let w4 = [0.1, 0.4, 0.3, 0.2];
            let it4 = dib_iterates(&four, &w4)?;
            let (last4, _) = chasles::blend::dib::dib(&four, &w4, 1e-15, 200)?;
            t.row(row("4", &it4, last4)?);
            s.table(t);
            let (d0, d1) = (distance(exact, it[0])?, distance(exact, it[1])?);
            let shrinking = it4.windows(2).all(|p| distance(last4, p[1]).unwrap_or(f64::NAN) <= distance(last4, p[0]).unwrap_or(f64::NAN));
            Ok((
                format!("two inputs: DLB start {d0:.1e} from the exact blend, {d1:.0e} after one update; four inputs: {} updates to 1e-14, each closer to the converged blend", it4.len() - 1),
                d1 < 1e-12 && d1 < d0 && shrinking,
            ))
        },
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figures_2_3_and_4_hold_and_draw() {
        for s in [figure_2(), figure_3(), figure_4()] {
            assert!(
                s.claims().all(|c| c.verdict.agrees()),
                "{}: {:?}",
                s.title,
                s.claims().map(|c| c.measured()).collect::<Vec<_>>()
            );
            assert_eq!(s.figures().count(), 1, "{}", s.title);
        }
    }
}
