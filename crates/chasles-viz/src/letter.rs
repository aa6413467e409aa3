//! The object of the direct visualisation (Dam et al. 1998, §5.1): a capital R, extruded,
//! because an R has no symmetry — every rotation of it, mirror included, looks different.
//! It is the union of five convex prisms (stem, top bar, middle bar, the bowl's right
//! side, the leg), centred on the origin, 5 units high.

use chasles::Vec3;

/// The outline pieces of the R in the xy-plane, each a convex polygon, counter-clockwise.
const PIECES: [&[[f64; 2]]; 5] = [
    &[[0.0, 0.0], [1.0, 0.0], [1.0, 5.0], [0.0, 5.0]],
    &[[1.0, 4.1], [2.4, 4.1], [2.4, 5.0], [1.0, 5.0]],
    &[[1.0, 2.4], [2.4, 2.4], [2.4, 3.3], [1.0, 3.3]],
    &[[2.2, 2.4], [3.0, 2.8], [3.0, 4.5], [2.2, 5.0]],
    &[[1.3, 2.5], [2.3, 2.5], [3.4, 0.0], [2.3, 0.0]],
];

/// The extruded R: vertices and triangles, `depth` units thick, centred on the origin.
pub fn letter_r(depth: f64) -> (Vec<Vec3<f64>>, Vec<[u32; 3]>) {
    let (cx, cy) = (1.7, 2.5);
    let mut v = Vec::new();
    let mut t = Vec::new();
    for piece in PIECES {
        let base = v.len() as u32;
        let n = piece.len() as u32;
        for z in [-depth / 2.0, depth / 2.0] {
            for p in piece {
                v.push(Vec3::new(p[0] - cx, p[1] - cy, z));
            }
        }
        for i in 1..n - 1 {
            t.push([base, base + i, base + i + 1]);
            t.push([base + n, base + n + i + 1, base + n + i]);
        }
        for i in 0..n {
            let j = (i + 1) % n;
            t.push([base + i, base + j, base + n + j]);
            t.push([base + i, base + n + j, base + n + i]);
        }
    }
    (v, t)
}

/// The R turned by `q`, seen from a fixed viewpoint slightly above and to the right,
/// `size` pixels square, `label` written in the corner.
pub fn draw(q: chasles::Quat<f64>, label: &str, size: usize) -> crate::Image {
    use crate::raster::{rotated, Canvas, View};
    let (v, t) = letter_r(1.2);
    let radius = v.iter().map(|p| p.norm()).fold(0.0, f64::max);
    let view = View::new(
        Vec3::new(0.35, 0.3, 1.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::zero(),
        0.46 * size as f64 / radius,
    );
    let mut c = Canvas::new(size, size, [246, 246, 242]);
    c.mesh(&view, &rotated(q, &v), &t, |_| [200, 45, 45]);
    c.text(4, 4, 2, label, [90, 90, 90]);
    c.finish()
}

/// The direct visualisation: one picture per frame of the R turned by that frame's
/// rotation, `size` pixels square, with the frame number written in the corner.
pub fn animate(frames: &[chasles::Quat<f64>], size: usize) -> Vec<crate::Image> {
    frames
        .iter()
        .enumerate()
        .map(|(i, q)| draw(*q, &i.to_string(), size))
        .collect()
}

/// A film strip: the R at `count` frames evenly spread over `frames` (always the first and
/// the last), `size` pixels each, left to right, each labelled with its frame number.
pub fn strip(frames: &[chasles::Quat<f64>], count: usize, size: usize) -> crate::Image {
    let n = frames.len();
    let count = count.clamp(1, n.max(1));
    let picked: Vec<crate::Image> = (0..count)
        .filter_map(|k| {
            let i = if count == 1 {
                0
            } else {
                k * n.saturating_sub(1) / (count - 1)
            };
            frames.get(i).map(|q| draw(*q, &i.to_string(), size))
        })
        .collect();
    crate::Image::side_by_side(&picked)
}
