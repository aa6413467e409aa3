//! A z-buffered software renderer for the direct visualisation of Dam et al. 1998, §5.1
//! ("the rotations are applied to an object, and the result is shown as an animation"),
//! and for the skinning pictures of Kavan et al. 2006, §6 / Figure 1. Orthographic
//! projection, flat Lambert shading lit from over the viewer's shoulder, both faces of
//! every triangle lit (so a skinned mesh that folds through itself still shows), a depth
//! buffer, and 2× supersampling for smooth edges.

use crate::image::Image;
use chasles::{Quat, Vec3};

/// An orthographic view: where it looks from, which way is up, what it is centred on and
/// how many pixels a unit is.
#[derive(Debug, Clone, Copy)]
pub struct View {
    right: Vec3<f64>,
    up: Vec3<f64>,
    toward_viewer: Vec3<f64>,
    centre: Vec3<f64>,
    scale: f64,
}

impl View {
    /// Looks at `centre` from direction `from` (a vector from the centre towards the
    /// viewer) with `up` roughly up, `scale` pixels per unit. Degenerate directions fall
    /// back to looking down −z with y up.
    pub fn new(from: Vec3<f64>, up: Vec3<f64>, centre: Vec3<f64>, scale: f64) -> Self {
        let toward_viewer = from.normalize().unwrap_or(Vec3::new(0.0, 0.0, 1.0));
        let right = up
            .cross(toward_viewer)
            .normalize()
            .unwrap_or_else(|_| toward_viewer.any_perpendicular());
        let up = toward_viewer.cross(right);
        View {
            right,
            up,
            toward_viewer,
            centre,
            scale,
        }
    }

    /// A view from `from` with `up` that fits every point of `points` into a
    /// `width × height` picture with a margin of `margin` (a fraction of the size).
    pub fn fit(
        points: &[Vec3<f64>],
        from: Vec3<f64>,
        up: Vec3<f64>,
        width: usize,
        height: usize,
        margin: f64,
    ) -> Self {
        let v = View::new(from, up, Vec3::zero(), 1.0);
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in points.iter().filter(|p| p.is_finite()) {
            let (x, y) = (p.dot(v.right), p.dot(v.up));
            lo = [lo[0].min(x), lo[1].min(y)];
            hi = [hi[0].max(x), hi[1].max(y)];
        }
        if lo[0] > hi[0] {
            return View { scale: 1.0, ..v };
        }
        let ext = [(hi[0] - lo[0]).max(1e-9), (hi[1] - lo[1]).max(1e-9)];
        let usable = 1.0 - 2.0 * margin;
        let scale = (width as f64 * usable / ext[0]).min(height as f64 * usable / ext[1]);
        let (cx, cy) = ((lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0);
        View {
            centre: v.right * cx + v.up * cy,
            scale,
            ..v
        }
    }

    /// Screen x, screen y (pixels from the centre of the picture, y up) and depth
    /// (larger is nearer).
    fn project(&self, p: Vec3<f64>) -> [f64; 3] {
        let d = p - self.centre;
        [
            d.dot(self.right) * self.scale,
            d.dot(self.up) * self.scale,
            d.dot(self.toward_viewer),
        ]
    }
}

/// A picture being drawn: colour and depth, at twice the final resolution.
pub struct Canvas {
    width: usize,
    height: usize,
    colour: Vec<[f64; 3]>,
    depth: Vec<f64>,
}

const SS: usize = 2;

impl Canvas {
    /// A `width × height` canvas (final pixels) filled with `background`.
    pub fn new(width: usize, height: usize, background: [u8; 3]) -> Self {
        let n = width * SS * height * SS;
        Canvas {
            width,
            height,
            colour: vec![background.map(f64::from); n],
            depth: vec![f64::NEG_INFINITY; n],
        }
    }

    /// Draws a triangle mesh seen through `view`, triangle `i` in `colour(i)` shaded by
    /// how squarely it faces the light. Triangles with an index out of range or a
    /// non-finite corner are skipped.
    pub fn mesh(
        &mut self,
        view: &View,
        positions: &[Vec3<f64>],
        triangles: &[[u32; 3]],
        colour: impl Fn(usize) -> [u8; 3],
    ) {
        let light = (view.toward_viewer + view.up * 0.7 - view.right * 0.4)
            .normalize()
            .unwrap_or(view.toward_viewer);
        for (i, t) in triangles.iter().enumerate() {
            let Some(p) = t
                .iter()
                .map(|i| positions.get(*i as usize))
                .collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            let (a, b, c) = (*p[0], *p[1], *p[2]);
            if !(a.is_finite() && b.is_finite() && c.is_finite()) {
                continue;
            }
            let Ok(n) = (b - a).cross(c - a).normalize() else {
                continue;
            };
            let shade = 0.22 + 0.78 * n.dot(light).abs();
            let col = colour(i).map(|x| f64::from(x) * shade);
            self.triangle([view.project(a), view.project(b), view.project(c)], col);
        }
    }

    fn triangle(&mut self, v: [[f64; 3]; 3], col: [f64; 3]) {
        let (w, h) = ((self.width * SS) as f64, (self.height * SS) as f64);
        let s = v.map(|p| [w / 2.0 + p[0] * SS as f64, h / 2.0 - p[1] * SS as f64, p[2]]);
        let area =
            (s[1][0] - s[0][0]) * (s[2][1] - s[0][1]) - (s[2][0] - s[0][0]) * (s[1][1] - s[0][1]);
        if area.abs() < 1e-12 {
            return;
        }
        let x0 = s
            .iter()
            .map(|p| p[0])
            .fold(f64::INFINITY, f64::min)
            .floor()
            .max(0.0);
        let x1 = s
            .iter()
            .map(|p| p[0])
            .fold(f64::NEG_INFINITY, f64::max)
            .ceil()
            .min(w - 1.0);
        let y0 = s
            .iter()
            .map(|p| p[1])
            .fold(f64::INFINITY, f64::min)
            .floor()
            .max(0.0);
        let y1 = s
            .iter()
            .map(|p| p[1])
            .fold(f64::NEG_INFINITY, f64::max)
            .ceil()
            .min(h - 1.0);
        if x0 > x1 || y0 > y1 {
            return;
        }
        let ww = self.width * SS;
        for py in y0 as usize..=y1 as usize {
            for px in x0 as usize..=x1 as usize {
                let (x, y) = (px as f64 + 0.5, py as f64 + 0.5);
                let e = |i: usize, j: usize| {
                    ((s[j][0] - s[i][0]) * (y - s[i][1]) - (x - s[i][0]) * (s[j][1] - s[i][1]))
                        / area
                };
                let (l0, l1, l2) = (e(1, 2), e(2, 0), e(0, 1));
                if l0 < 0.0 || l1 < 0.0 || l2 < 0.0 {
                    continue;
                }
                let z = l0 * s[0][2] + l1 * s[1][2] + l2 * s[2][2];
                let k = py * ww + px;
                if z > self.depth[k] {
                    self.depth[k] = z;
                    self.colour[k] = col;
                }
            }
        }
    }

    /// Writes `text` (see [`crate::font`]) at final-pixel position `(x, y)`, `px` final
    /// pixels per font dot.
    pub fn text(&mut self, x: usize, y: usize, px: usize, text: &str, colour: [u8; 3]) {
        let ww = self.width * SS;
        let hh = self.height * SS;
        for (dx, dy) in crate::font::dots(text) {
            for sy in 0..px * SS {
                for sx in 0..px * SS {
                    let (sx_, sy_) = ((x + dx * px) * SS + sx, (y + dy * px) * SS + sy);
                    if sx_ < ww && sy_ < hh {
                        self.colour[sy_ * ww + sx_] = colour.map(f64::from);
                    }
                }
            }
        }
    }

    /// The finished picture (supersamples averaged).
    pub fn finish(&self) -> Image {
        let ww = self.width * SS;
        let mut out = Image::filled(self.width, self.height, [0, 0, 0]);
        for y in 0..self.height {
            for x in 0..self.width {
                let mut acc = [0.0; 3];
                for sy in 0..SS {
                    for sx in 0..SS {
                        let c = self.colour[(y * SS + sy) * ww + x * SS + sx];
                        acc = [acc[0] + c[0], acc[1] + c[1], acc[2] + c[2]];
                    }
                }
                let n = (SS * SS) as f64;
                out.set(x, y, acc.map(|a| (a / n).round().clamp(0.0, 255.0) as u8));
            }
        }
        out
    }
}

/// `positions` turned by `q` (about the origin).
pub fn rotated(q: Quat<f64>, positions: &[Vec3<f64>]) -> Vec<Vec3<f64>> {
    positions.iter().map(|p| q.rotate(*p)).collect()
}
