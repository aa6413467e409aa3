//! Pictures of blending (Kavan et al. 2006, §2–5): what each method does along a path of
//! weights. With two transforms the path is their interpolation, weights (1 − t, t); with
//! more, it runs from the first transform (all weight on it) to the given blend,
//! w(t) = (1 − t)·e₀ + t·w. `--plot` draws each method's rotation angle away from the first
//! transform along the path (a straight line is constant angular speed — ScLERP's, and
//! what DLB approximates); `--render` draws the inputs as grey letters R and each method's
//! blend in colour, side by side (Lin's matrix drawn as it is, so its shrinking shows);
//! `--gif` moves the R along the path for the chosen method; `--sphere` plots the chosen
//! method's rotations along the path on the unit sphere (Dam et al. §5.3), the inputs as
//! keys.

use anyhow::Result;
use chasles::blend::{blend_dual_quats, Blended, Method, Options};
use chasles::{DualQuat, Mat4, Vec3};
use chasles_viz::letter::letter_r;
use chasles_viz::plot::{lines_svg, Series};
use chasles_viz::raster::{Canvas, View};
use chasles_viz::Image;

/// One blend problem: transforms, weights and options.
pub struct Case<'a> {
    /// The transforms.
    pub x: &'a [DualQuat<f64>],
    /// The weights the case asks for.
    pub w: &'a [f64],
    /// Centre, precision, iterations.
    pub opt: &'a Options<f64>,
}

const COLOURS: [&str; 8] = [
    "#7f7f7f", "#e67e22", "#8e44ad", "#16a085", "#2980b9", "#c0392b", "#27ae60", "#d35400",
];

impl Case<'_> {
    /// The weights at `t` along the path.
    fn weights(&self, t: f64) -> Vec<f64> {
        if self.x.len() == 2 {
            vec![1.0 - t, t]
        } else {
            let mut w: Vec<f64> = self.w.iter().map(|v| v * t).collect();
            if let Some(first) = w.first_mut() {
                *first += 1.0 - t;
            }
            w
        }
    }

    fn blend(&self, m: Method, t: f64) -> chasles::Result<Blended<f64>> {
        blend_dual_quats(m, self.x, &self.weights(t), self.opt)
    }
}

/// The rotation angle (degrees) of every method's blend away from the first transform,
/// over t ∈ [0, 1]. Methods that do not apply (ScLERP with more than two) are left out.
pub fn plot(case: &Case) -> Result<String> {
    let q0 = case.x[0].real;
    let mut series = Vec::new();
    for (i, m) in Method::ALL.iter().enumerate() {
        let pts: Option<Vec<(f64, f64)>> = (0..=100)
            .map(|k| {
                let t = k as f64 / 100.0;
                let b = case.blend(*m, t).ok()?;
                let rel = q0.conjugate() * b.dq.real;
                Some((t, rel.w.abs().min(1.0).acos().to_degrees() * 2.0))
            })
            .collect();
        if let Some(points) = pts {
            series.push((
                m.name(),
                COLOURS[i % COLOURS.len()],
                points,
                *m == Method::ScLerp,
            ));
        }
    }
    let ser: Vec<Series> = series
        .iter()
        .map(|(n, c, p, dashed)| Series {
            name: n,
            colour: c,
            dashed: *dashed,
            points: p.clone(),
        })
        .collect();
    Ok(lines_svg(
        &ser,
        "rotation away from the first transform along the path of weights",
        "t",
        "degrees",
    ))
}

fn letter_at(m: &Mat4<f64>, v: &[Vec3<f64>]) -> Vec<Vec3<f64>> {
    v.iter().map(|p| m.transform_point(*p)).collect()
}

/// A fixed view that fits the letter at every input transform and at the blends.
fn view_for(points: &[Vec3<f64>], size: usize) -> View {
    View::fit(
        points,
        Vec3::new(0.3, 0.4, 1.0),
        Vec3::new(0.0, 1.0, 0.0),
        size,
        size,
        0.06,
    )
}

/// The letter at a fifth of its size (about the inputs' translations), and its triangles.
fn small_letter() -> (Vec<Vec3<f64>>, Vec<[u32; 3]>) {
    let (v, t) = letter_r(0.8);
    (v.iter().map(|p| *p * 0.2).collect(), t)
}

/// One picture per placed letter (label, vertices): it in red over the inputs in grey,
/// all seen through one view fitted to everything.
fn scenes(
    case: &Case,
    placed: &[(&str, Vec<Vec3<f64>>)],
    letter: &[Vec3<f64>],
    triangles: &[[u32; 3]],
    size: usize,
) -> Vec<Image> {
    let inputs: Vec<Vec<Vec3<f64>>> = case
        .x
        .iter()
        .map(|d| letter_at(&d.to_matrix4(), letter))
        .collect();
    let all: Vec<Vec3<f64>> = inputs
        .iter()
        .chain(placed.iter().map(|p| &p.1))
        .flatten()
        .copied()
        .collect();
    let view = view_for(&all, size);
    placed
        .iter()
        .map(|(label, pts)| scene(&view, size, &inputs, pts, triangles, label))
        .collect()
}

/// The inputs in grey and each method's blend (at the case's own weights) in colour, one
/// panel per method.
pub fn render(case: &Case) -> Result<Image> {
    let (v, t) = small_letter();
    let placed: Vec<(&str, Vec<Vec3<f64>>)> = Method::ALL
        .iter()
        .filter_map(|m| {
            let b = blend_dual_quats(*m, case.x, case.w, case.opt).ok()?;
            Some((m.name(), letter_at(&b.matrix, &v)))
        })
        .collect();
    Ok(Image::side_by_side(&scenes(case, &placed, &v, &t, 260)))
}

/// The letter moved along the path by `method`, `frames` pictures, inputs in grey.
pub fn animate(case: &Case, method: Method, frames: usize) -> Result<Vec<Image>> {
    let (v, t) = small_letter();
    let n = frames.max(2);
    let placed = (0..n)
        .map(|k| {
            let b = case.blend(method, k as f64 / (n - 1) as f64)?;
            Ok((method.name(), letter_at(&b.matrix, &v)))
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(scenes(case, &placed, &v, &t, 280))
}

/// One picture: the input letters in grey, the blended one in red, labelled.
fn scene(
    view: &View,
    size: usize,
    inputs: &[Vec<Vec3<f64>>],
    blended: &[Vec3<f64>],
    triangles: &[[u32; 3]],
    label: &str,
) -> Image {
    let mut c = Canvas::new(size, size, [250, 250, 250]);
    for inp in inputs {
        c.mesh(view, inp, triangles, |_| [185, 185, 185]);
    }
    c.mesh(view, blended, triangles, |_| [200, 45, 45]);
    c.text(6, 6, 3, label, [40, 40, 40]);
    c.finish()
}

/// The chosen method's rotations along the path (small) and the inputs' rotations (keys,
/// the first larger) on the unit sphere, one coordinate left out.
pub fn sphere(case: &Case, method: Method) -> Result<Image> {
    use chasles_viz::sphere::{fixed_coordinate, render, Mark};
    let mut pts: Vec<(chasles::Quat<f64>, Mark)> = Vec::new();
    let q0 = case.x[0].real;
    for (i, d) in case.x.iter().enumerate() {
        // Each input on q0's side, as the blends choose.
        let q = if d.real.dot(q0) < 0.0 {
            -d.real
        } else {
            d.real
        };
        pts.push((q, if i == 0 { Mark::FirstKey } else { Mark::Key }));
    }
    for k in 0..=100 {
        let q = case.blend(method, k as f64 / 100.0)?.dq.real;
        pts.push((if q.dot(q0) < 0.0 { -q } else { q }, Mark::Frame));
    }
    let all: Vec<chasles::Quat<f64>> = pts.iter().map(|p| p.0).collect();
    Ok(render(&pts, fixed_coordinate(&all), 500))
}
