//! The sphere plot (Dam et al. 1998, §5.3, Figures 5.1–5.3): the quaternions of a curve
//! whose key frames share one fixed coordinate, drawn as points of the remaining three on a
//! shaded unit sphere. The report ray-traced this with POV-Ray; here a small renderer does
//! the same job: each point is a shaded little sphere (first key larger, other keys
//! medium, frames small) with a depth test, and the unit sphere is drawn over them
//! semi-transparently, so a frame inside the sphere (a curve that "dips below the surface",
//! like LinEuler's or raw Lerp's) shows through dimmed while frames on the surface sit on
//! it. The view looks at the curve's side of the sphere.

use crate::image::Image;
use chasles::{Quat, Vec3};

/// What a plotted point is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    /// The first key frame (largest).
    FirstKey,
    /// Another key frame (medium).
    Key,
    /// An interpolated frame (small).
    Frame,
}

/// The coordinate of `[w, x, y, z]` that varies least over the points (the fixed one).
pub fn fixed_coordinate(q: &[Quat<f64>]) -> usize {
    let n = q.len().max(1) as f64;
    let var: Vec<f64> = (0..4)
        .map(|c| {
            let v: Vec<f64> = q.iter().map(|x| x.to_array()[c]).collect();
            let m = v.iter().sum::<f64>() / n;
            v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / n
        })
        .collect();
    (0..4)
        .min_by(|a, b| var[*a].total_cmp(&var[*b]))
        .unwrap_or(3)
}

/// Renders the plot: `points` with their marks; `fixed` is the coordinate left out
/// (see [`fixed_coordinate`]).
pub fn render(points: &[(Quat<f64>, Mark)], fixed: usize, size: usize) -> Image {
    let keep: Vec<usize> = (0..4).filter(|c| *c != fixed).collect();
    let p3: Vec<(Vec3<f64>, Mark)> = points
        .iter()
        .map(|(q, m)| {
            let a = q.to_array();
            (Vec3::new(a[keep[0]], a[keep[1]], a[keep[2]]), *m)
        })
        .collect();
    // Look from the side of the curve: towards the centroid of its points.
    let centroid = p3.iter().fold(Vec3::zero(), |c, (p, _)| c + *p);
    let toward = centroid.normalize().unwrap_or(Vec3::new(0.0, 0.0, 1.0));
    // Tilt the view a little so the curve is seen at an angle, not straight on.
    let side = toward.any_perpendicular();
    let eye = (toward + side * 0.45).normalize().unwrap_or(toward);
    let right = eye
        .cross(side)
        .normalize()
        .unwrap_or(Vec3::new(1.0, 0.0, 0.0));
    let up = right.cross(eye);
    let light = (eye + up * 0.6 + right * -0.4).normalize().unwrap_or(eye);
    let scale = 0.42 * size as f64;
    let c = size as f64 / 2.0;
    let mut depth = vec![f64::NEG_INFINITY; size * size];
    let mut colour = vec![[255.0f64, 255.0, 255.0]; size * size];
    let mut is_point = vec![false; size * size];
    for (p, m) in &p3 {
        let (r, base) = match m {
            Mark::FirstKey => (0.045, [200.0, 30.0, 30.0]),
            Mark::Key => (0.03, [235.0, 140.0, 20.0]),
            Mark::Frame => (0.012, [30.0, 80.0, 190.0]),
        };
        let (u, v, d) = (p.dot(right), p.dot(up), p.dot(eye));
        let rp = r * scale;
        let (cx, cy) = (c + u * scale, c - v * scale);
        let (x0, x1) = (
            (cx - rp).floor().max(0.0) as usize,
            ((cx + rp).ceil() as usize).min(size - 1),
        );
        let (y0, y1) = (
            (cy - rp).floor().max(0.0) as usize,
            ((cy + rp).ceil() as usize).min(size - 1),
        );
        for py in y0..=y1 {
            for px in x0..=x1 {
                let (du, dv) = ((px as f64 + 0.5 - cx) / rp, (cy - (py as f64 + 0.5)) / rp);
                let q2 = du * du + dv * dv;
                if q2 > 1.0 {
                    continue;
                }
                let dz = (1.0 - q2).sqrt();
                let z = d + dz * r;
                let k = py * size + px;
                if z > depth[k] {
                    let normal = right * du + up * dv + eye * dz;
                    let shade = 0.35 + 0.65 * normal.dot(light).max(0.0);
                    depth[k] = z;
                    colour[k] = base.map(|b| b * shade);
                    is_point[k] = true;
                }
            }
        }
    }
    // The unit sphere, front surface, semi-transparent over what lies behind it.
    let mut rgb = Vec::with_capacity(size * size * 3);
    for py in 0..size {
        for px in 0..size {
            let k = py * size + px;
            let (u, v) = (
                (px as f64 + 0.5 - c) / scale,
                (c - (py as f64 + 0.5)) / scale,
            );
            let q2 = u * u + v * v;
            let mut col = colour[k];
            if q2 <= 1.0 {
                let dz = (1.0 - q2).sqrt();
                let normal = right * u + up * v + eye * dz;
                let diffuse = normal.dot(light).max(0.0);
                let half = (light + eye).normalize().unwrap_or(eye);
                let spec = normal.dot(half).max(0.0).powi(40);
                let s = 95.0 + 130.0 * diffuse + 60.0 * spec;
                let sphere = [s, s, s * 1.04];
                if is_point[k] && depth[k] >= dz - 1e-3 {
                    // On or outside the visible surface: drawn as is.
                } else if is_point[k] {
                    col = [0, 1, 2].map(|i| 0.35 * col[i] + 0.65 * sphere[i]);
                } else {
                    col = sphere;
                }
                // A thin rim for the silhouette.
                if q2 > 0.985 && !is_point[k] {
                    col = [70.0, 70.0, 80.0];
                }
            }
            rgb.extend(col.map(|x| x.clamp(0.0, 255.0) as u8));
        }
    }
    Image {
        width: size,
        height: size,
        rgb,
    }
}

/// The plot of an interpolated curve: its frames, key frames marked (the first key larger),
/// the fixed coordinate found from the frames.
pub fn render_frames(frames: &[chasles::interp::Frame<f64>], size: usize) -> Image {
    let pts: Vec<(Quat<f64>, Mark)> = frames
        .iter()
        .map(|f| {
            let m = match f.key {
                Some(0) => Mark::FirstKey,
                Some(_) => Mark::Key,
                None => Mark::Frame,
            };
            (f.q, m)
        })
        .collect();
    let q: Vec<Quat<f64>> = frames.iter().map(|f| f.q).collect();
    render(&pts, fixed_coordinate(&q), size)
}
