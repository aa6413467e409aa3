//! Kavan et al. 2006's figures of §3 drawn from the library's own dual quaternions:
//! Figure 2 (a screw motion — the axis, the turn about it and the slide along it, side and
//! top view) and Figure 3 (`q^t` against `(−q)^t`: the same rotation, the long and the
//! short way round). The object is the extruded R of the interpolation pictures (the paper
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figures_2_and_3_hold_and_draw() {
        for s in [figure_2(), figure_3()] {
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
