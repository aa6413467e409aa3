//! Pictures of rigid-motion curves (key frames that turn and move, `chasles::interp::rigid`):
//! the letter R of Dam et al. §5.1's direct visualisation, now moved as well as turned, with
//! the keys as pale letters and the path of one point of the letter (the top of its stem)
//! as a trail of small dots. One fixed view fits every key and every frame, chosen so that
//! the path spreads most, on the side the keys' letters face, z up.

use crate::image::Image;
use crate::letter::letter_r;
use crate::raster::{Canvas, View};
use chasles::{DualQuat, Vec3};

/// The point of the letter whose path is drawn: the top of the stem, in the letter's own
/// coordinates (before scaling).
const POINT: Vec3<f64> = Vec3 {
    x: -1.7,
    y: 2.5,
    z: 0.0,
};

/// How a set of keys and frames is drawn: the letter's scale and the view.
struct Layout {
    scale: f64,
    view: View,
    dot: f64,
}

/// The letter's scale for keys spread over `extent`: the R (5 units high) a sixth of the
/// spread, or 1 unit high when the keys do not move.
fn scale_for(keys: &[DualQuat<f64>]) -> f64 {
    let t: Vec<Vec3<f64>> = keys.iter().map(|k| k.translation()).collect();
    let extent = t
        .iter()
        .flat_map(|a| t.iter().map(move |b| (*a - *b).norm()))
        .fold(0.0, f64::max);
    if extent > 1e-9 {
        extent / 32.0
    } else {
        0.2
    }
}

/// The direction the view looks from (the keys' alone, so that every curve through them is
/// seen alike): of 13 candidates (the cube's faces, edges and corners, one of each opposite
/// pair), the one in which the keys' origins spread most (the largest area of its projected covariance), tilted a little from above, on the
/// side the keys' letters face (the mean of their z axes).
fn view_direction(keys: &[DualQuat<f64>]) -> Vec3<f64> {
    let spread = |d: Vec3<f64>| {
        let (_, [a, b, c]) = projected_spread(keys, d);
        a * c - b * b
    };
    let mut best = (f64::NEG_INFINITY, Vec3::new(0.0, 0.0, 1.0));
    for x in [-1.0, 0.0, 1.0] {
        for y in [-1.0, 0.0, 1.0] {
            for z in [0.0, 1.0] {
                let d = Vec3::new(x, y, z);
                let Ok(d) = d.normalize() else { continue };
                // One of each opposite pair: z > 0, or z = 0 and (y > 0, or y = 0 and x > 0).
                if z == 0.0 && (y < 0.0 || (y == 0.0 && x < 0.0)) {
                    continue;
                }
                let v = spread(d);
                if v > best.0 * (1.0 + 1e-9) {
                    best = (v, d);
                }
            }
        }
    }
    let facing = keys.iter().fold(Vec3::zero(), |s, k| {
        s + k.real.rotate(Vec3::new(0.0, 0.0, 1.0))
    });
    let d = if best.1.dot(facing) < 0.0 {
        -best.1
    } else {
        best.1
    };
    d + Vec3::new(0.15, -0.2, 0.35)
}

/// The spread of the keys' origins seen along the unit `d`: the axes `e1`, `e2` of the plane
/// across d, and `[a, b, c]` = Σx², Σxy, Σy² of the origins' offsets from their mean in
/// those axes (the projected covariance, unnormalized).
fn projected_spread(keys: &[DualQuat<f64>], d: Vec3<f64>) -> ((Vec3<f64>, Vec3<f64>), [f64; 3]) {
    let pts: Vec<Vec3<f64>> = keys.iter().map(|k| k.translation()).collect();
    let n = pts.len().max(1) as f64;
    let mean = pts.iter().fold(Vec3::zero(), |s, p| s + *p) * (1.0 / n);
    let (e1, e2) = (d.any_perpendicular(), d.cross(d.any_perpendicular()));
    let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
    for p in &pts {
        let q = *p - mean;
        let (x, y) = (q.dot(e1), q.dot(e2));
        a += x * x;
        b += x * y;
        c += y * y;
    }
    ((e1, e2), [a, b, c])
}

/// The up direction that lays the keys' spread across the picture: perpendicular to `from`
/// and to the keys' main direction in the picture's plane, on z's side (z when the keys do
/// not move).
fn level_up(keys: &[DualQuat<f64>], from: Vec3<f64>) -> Vec3<f64> {
    let f = from.normalize().unwrap_or(Vec3::new(0.0, 0.0, 1.0));
    let ((e1, e2), [a, b, c]) = projected_spread(keys, f);
    if a + c < 1e-18 {
        return Vec3::new(0.0, 0.0, 1.0);
    }
    // The major axis of [[a, b], [b, c]]: angle ½ atan2(2b, a − c).
    let phi = 0.5 * (2.0 * b).atan2(a - c);
    let major = e1 * phi.cos() + e2 * phi.sin();
    let up = f.cross(major);
    if up.z < 0.0 {
        -up
    } else {
        up
    }
}

fn layout(keys: &[DualQuat<f64>], frames: &[DualQuat<f64>], width: usize, height: usize) -> Layout {
    let scale = scale_for(keys);
    let (v, _) = letter_r(0.8);
    let pts: Vec<Vec3<f64>> = keys
        .iter()
        .chain(frames)
        .flat_map(|d| v.iter().map(move |p| d.transform_point(*p * scale)))
        .collect();
    let from = view_direction(keys);
    let up = level_up(keys, from);
    let view = View::fit(&pts, from, up, width, height, 0.06);
    Layout {
        scale,
        view,
        dot: scale * 0.35,
    }
}

/// A mesh being gathered: positions, triangles, one colour per triangle.
#[derive(Default)]
struct Mesh {
    pos: Vec<Vec3<f64>>,
    tri: Vec<[u32; 3]>,
    col: Vec<[u8; 3]>,
}

impl Mesh {
    fn letter(&mut self, d: DualQuat<f64>, scale: f64, colour: [u8; 3]) {
        let (v, t) = letter_r(0.8);
        let base = self.pos.len() as u32;
        self.pos
            .extend(v.iter().map(|p| d.transform_point(*p * scale)));
        self.tri.extend(t.iter().map(|x| x.map(|i| i + base)));
        self.col.extend(std::iter::repeat_n(colour, t.len()));
    }
    /// A small octahedron of radius `r` at `c`.
    fn dot(&mut self, c: Vec3<f64>, r: f64, colour: [u8; 3]) {
        let base = self.pos.len() as u32;
        for k in 0..3 {
            let e = Vec3::unit(k) * r;
            self.pos.push(c + e);
            self.pos.push(c - e);
        }
        // Vertices: +x 0, −x 1, +y 2, −y 3, +z 4, −z 5.
        for (a, b) in [(0, 2), (2, 1), (1, 3), (3, 0)] {
            self.tri.push([base + a, base + b, base + 4]);
            self.tri.push([base + b, base + a, base + 5]);
        }
        self.col.extend(std::iter::repeat_n(colour, 8));
    }
    fn draw(&self, view: &View, size: (usize, usize), label: &str) -> Image {
        let mut c = Canvas::new(size.0, size.1, [248, 248, 244]);
        c.mesh(view, &self.pos, &self.tri, |i| self.col[i]);
        c.text(6, 6, 2, label, [60, 60, 60]);
        c.finish()
    }
}

/// The keys (pale letters) and the path of the stem's top over `frames` (dots), gathered.
fn backdrop(keys: &[DualQuat<f64>], frames: &[DualQuat<f64>], l: &Layout) -> Mesh {
    let mut m = Mesh::default();
    for k in keys {
        m.letter(*k, l.scale, [205, 205, 210]);
    }
    for f in frames {
        m.dot(f.transform_point(POINT * l.scale), l.dot, [40, 90, 170]);
    }
    m
}

/// The keys, the path of a point over `frames`, and the R at `count` evenly spread frames
/// (red, darker later), `size` pixels, `label` in the corner.
pub fn path(
    keys: &[DualQuat<f64>],
    frames: &[DualQuat<f64>],
    count: usize,
    size: (usize, usize),
    label: &str,
) -> Image {
    let l = layout(keys, frames, size.0, size.1);
    let mut m = backdrop(keys, frames, &l);
    let n = frames.len();
    let count = count.min(n);
    for k in 0..count {
        let i = if count == 1 {
            0
        } else {
            k * (n - 1) / (count - 1)
        };
        let f = k as f64 / count.max(2).saturating_sub(1) as f64;
        let c = [
            (235.0 - 80.0 * f) as u8,
            (120.0 - 90.0 * f) as u8,
            (110.0 - 80.0 * f) as u8,
        ];
        m.letter(frames[i], l.scale, c);
    }
    m.draw(&l.view, size, label)
}

/// The R moved along `frames`, one picture per frame, over the keys and the path of the
/// point (the view fixed), `size` pixels square, the frame number in the corner.
pub fn animate(keys: &[DualQuat<f64>], frames: &[DualQuat<f64>], size: usize) -> Vec<Image> {
    let l = layout(keys, frames, size, size);
    let back = backdrop(keys, frames, &l);
    frames
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let mut m = Mesh {
                pos: back.pos.clone(),
                tri: back.tri.clone(),
                col: back.col.clone(),
            };
            m.letter(*f, l.scale, [200, 45, 45]);
            m.draw(&l.view, (size, size), &i.to_string())
        })
        .collect()
}
