//! Side-by-side pictures of one mesh posed several ways — a skinned pose under each
//! blending method (Kavan et al. 2006, §6 and Figure 1) — all seen through one view fitted
//! to every panel, so that sizes compare, each panel labelled.

use crate::image::Image;
use crate::raster::{Canvas, View};
use chasles::Vec3;

/// One panel: its label and the mesh's vertex positions.
pub struct Panel<'a> {
    /// Written at the panel's top left (see [`crate::font`]).
    pub label: &'a str,
    /// Vertex positions, indexed by the shared triangles.
    pub positions: Vec<Vec3<f64>>,
}

/// Renders every panel `width × height` pixels, looking from `from` with `up` up,
/// triangle `i` in `colour(i)`, and places them left to right.
pub fn side_by_side(
    panels: &[Panel],
    triangles: &[[u32; 3]],
    colour: &dyn Fn(usize) -> [u8; 3],
    from: Vec3<f64>,
    up: Vec3<f64>,
    width: usize,
    height: usize,
) -> Image {
    let all: Vec<Vec3<f64>> = panels
        .iter()
        .flat_map(|p| p.positions.iter().copied())
        .collect();
    side_by_side_fitted(panels, triangles, colour, &all, from, up, (width, height))
}

/// As [`side_by_side`], the view fitted to `focus` (points of interest, e.g. one joint's
/// neighbourhood) rather than to everything: a close-up; what falls outside is cut off.
pub fn side_by_side_fitted(
    panels: &[Panel],
    triangles: &[[u32; 3]],
    colour: &dyn Fn(usize) -> [u8; 3],
    focus: &[Vec3<f64>],
    from: Vec3<f64>,
    up: Vec3<f64>,
    (width, height): (usize, usize),
) -> Image {
    let view = View::fit(focus, from, up, width, height, 0.08);
    let images: Vec<Image> = panels
        .iter()
        .map(|p| {
            let mut c = Canvas::new(width, height, [250, 250, 250]);
            c.mesh(&view, &p.positions, triangles, colour);
            c.text(6, 6, 3, p.label, [40, 40, 40]);
            c.finish()
        })
        .collect();
    let mut out = Image::side_by_side(&images);
    for k in 1..panels.len() {
        for y in 0..out.height {
            out.set(k * width, y, [180, 180, 180]);
        }
    }
    out
}
