//! Past Kavan et al. 2006: what its §7 ("Conclusions and Future Work") says the
//! dual-quaternion blends "could be applied for", measured on the library's own code.
//!
//! * "computer vision – averaging of measured position and orientation of a rigid object":
//!   the rigid mean of noisy poses (DIB's fixed point, `chasles::blend::average::mean`)
//!   and the robust means (Huber's and Tukey's weights, `robust_mean`). Measured: the
//!   mean's error about the true pose against n (it should fall as σ√6/√n: six
//!   coordinates of noise, each averaged), and with 20 % wild outliers the error of DLB,
//!   DIB and the robust means against that of the inliers' own mean. Pictured: the poses
//!   as small letters R with the means in colour.
//! * "spatial keyframing": key-frame curves of rigid motions ([`super::rigid_keyframes`]).

use super::Figures;
use crate::claim::Paper::Kavan2006;
use crate::section::Section;
use crate::table::{Cell, Number, Table};
use chasles::blend::average::{distance, mean, robust_mean, Loss, Robust};
use chasles::blend::{dlb::dlb, Options};
use chasles::{DualQuat, Quat, Vec3};
use chasles_viz::raster::{Canvas, View};
use chasles_viz::Image;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// §7's words on computer vision.
const AVERAGING: &str =
    "computer vision – averaging of measured position and orientation of a rigid object";

/// The noise of a measurement, per coordinate (radians of turn, units of length).
const SIGMA: f64 = 0.05;

/// A standard normal number (Box–Muller).
fn normal(rng: &mut StdRng) -> f64 {
    let u: f64 = rng.random::<f64>().max(1e-300);
    let v: f64 = rng.random();
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

/// Three normal numbers of deviation `s`.
fn gauss3(rng: &mut StdRng, s: f64) -> Vec3<f64> {
    Vec3::new(normal(rng) * s, normal(rng) * s, normal(rng) * s)
}

/// The pose the measurements scatter about.
fn truth() -> chasles::Result<DualQuat<f64>> {
    Ok(DualQuat::from_rotation_translation(
        Quat::from_axis_angle(Vec3::new(1.0, -2.0, 0.5), 2.1)?,
        Vec3::new(0.7, -1.2, 3.0),
    ))
}

/// `n` measurements of `g`: `g exp(twist)`, the twist's six coordinates normal with
/// deviation σ, each measurement of either sign.
fn noisy(rng: &mut StdRng, g: DualQuat<f64>, n: usize) -> Vec<DualQuat<f64>> {
    (0..n)
        .map(|_| {
            let (w, v) = (gauss3(rng, SIGMA), gauss3(rng, SIGMA));
            let p = g * DualQuat::new(Quat::pure(w * 0.5), Quat::pure(v * 0.5)).exp();
            if rng.random::<bool>() {
                -p
            } else {
                p
            }
        })
        .collect()
}

/// A wrong detection: a uniformly random rotation, the translation 1 to 3 off in x and y
/// and up to 1 in z.
fn outlier(rng: &mut StdRng, g: DualQuat<f64>) -> chasles::Result<DualQuat<f64>> {
    let q = Quat::new(normal(rng), normal(rng), normal(rng), normal(rng)).normalize()?;
    let t = Vec3::new(
        rng.random_range(1.0..3.0),
        rng.random_range(1.0..3.0),
        rng.random_range(-1.0..1.0),
    );
    Ok(DualQuat::from_rotation_translation(q, g.translation() + t))
}

/// The distance of two poses (turn and move in quadrature, `average::distance`, ℓ = 1).
fn err(a: DualQuat<f64>, b: DualQuat<f64>) -> chasles::Result<f64> {
    distance(a, b, 1.0)
}

/// The rms error of the mean of n measurements over `seeds` draws, for each n.
fn error_against_n(sizes: &[usize], seeds: u64) -> chasles::Result<Vec<f64>> {
    let g = truth()?;
    sizes
        .iter()
        .map(|&n| {
            let mut sum = 0.0;
            for seed in 0..seeds {
                let mut rng = StdRng::seed_from_u64(7919 * n as u64 + seed);
                let p = noisy(&mut rng, g, n);
                sum += err(mean(&p, None, &Options::default())?.pose, g)?.powi(2);
            }
            Ok((sum / seeds as f64).sqrt())
        })
        .collect()
}

/// The least-squares slope of log y on log x.
fn log_slope(x: &[f64], y: &[f64]) -> f64 {
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let n = lx.len() as f64;
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// One draw with outliers: the poses (inliers first) and the means.
struct Scene {
    /// The poses: `inliers` measurements, then the outliers.
    poses: Vec<DualQuat<f64>>,
    /// How many of `poses` are measurements.
    inliers: usize,
    /// The inliers' own mean, DLB, DIB, Huber's and Tukey's means of all poses.
    means: [DualQuat<f64>; 5],
}

/// `n` poses of which `bad` are outliers (placed at random among them in the inputs; kept
/// apart here for drawing), with every mean.
fn scene(seed: u64, n: usize, bad: usize) -> chasles::Result<Scene> {
    let g = truth()?;
    let mut rng = StdRng::seed_from_u64(seed);
    let mut poses = noisy(&mut rng, g, n - bad);
    for _ in 0..bad {
        poses.push(outlier(&mut rng, g)?);
    }
    // The averages see the outliers mixed in: shuffle a copy.
    let mut mixed = poses.clone();
    for i in (1..mixed.len()).rev() {
        mixed.swap(i, rng.random_range(0..=i));
    }
    let o = Options::default();
    let means = [
        mean(&poses[..n - bad], None, &o)?.pose,
        dlb(&mixed, &vec![1.0; n])?,
        mean(&mixed, None, &o)?.pose,
        robust_mean(&mixed, None, &Robust::new(Loss::Huber))?.pose,
        robust_mean(&mixed, None, &Robust::new(Loss::Tukey))?.pose,
    ];
    Ok(Scene {
        poses,
        inliers: n - bad,
        means,
    })
}

/// The names and colours of [`Scene::means`] in pictures and tables.
const MEANS: [(&str, [u8; 3]); 5] = [
    ("inliers only", [60, 60, 60]),
    ("DLB", [230, 126, 34]),
    ("DIB", [142, 68, 173]),
    ("Huber", [39, 150, 96]),
    ("Tukey", [200, 45, 45]),
];

/// A mesh with one colour per triangle: vertices, triangles, colours.
type Coloured = (Vec<Vec3<f64>>, Vec<[u32; 3]>, Vec<[u8; 3]>);

/// The letter R at `scale[k]` for pose k, moved by it and then by `lift` (towards the
/// viewer, so that it is drawn over what lies at its place); one colour per pose.
fn letters(
    poses: &[(DualQuat<f64>, [u8; 3])],
    scale: impl Fn(usize) -> f64,
    lift: Vec3<f64>,
) -> Coloured {
    let (v, t) = chasles_viz::letter::letter_r(0.8);
    let (mut pos, mut tri, mut col) = (Vec::new(), Vec::new(), Vec::new());
    for (k, (d, c)) in poses.iter().enumerate() {
        let base = pos.len() as u32;
        pos.extend(v.iter().map(|p| d.transform_point(*p * scale(k)) + lift));
        tri.extend(t.iter().map(|x| x.map(|i| i + base)));
        col.extend(std::iter::repeat_n(*c, t.len()));
    }
    (pos, tri, col)
}

/// Two panels: every pose (measurements pale, outliers blue-grey) with the means, and a
/// close-up of the measurements with the means; the means are larger letters in their
/// colours, drawn over the poses (the three that nearly coincide nested, largest first).
fn picture(s: &Scene) -> Image {
    let size = 440;
    let g = s.means[0].real;
    // Facing the letters of the measurements, upright.
    let from = g.rotate(Vec3::new(0.25, 0.3, 1.0));
    let up = g.rotate(Vec3::new(0.0, 1.0, 0.0));
    let toward = from.normalize().unwrap_or(Vec3::new(0.0, 0.0, 1.0));
    let panel = |poses: &[(DualQuat<f64>, [u8; 3])],
                 small: f64,
                 big: f64,
                 title: &str,
                 focus_means: bool| {
        let (mut pos, mut tri, mut col) = letters(poses, |_| small, Vec3::zero());
        let means: Vec<_> = s
            .means
            .iter()
            .zip(MEANS)
            .map(|(d, (_, c))| (*d, c))
            .collect();
        // Drawn over the poses, and over each other in order: the inliers' own mean
        // largest, Huber's, then Tukey's smallest and nearest.
        let nested = [1.0, 1.0, 1.0, 0.72, 0.45];
        let mut mp = Vec::new();
        let (mut mt, mut mc) = (Vec::new(), Vec::new());
        for (k, m) in means.iter().enumerate() {
            let (p, t, c) = letters(&[*m], |_| big * nested[k], toward * (100.0 + k as f64));
            let base = mp.len() as u32;
            mp.extend(p);
            mt.extend(t.iter().map(|x| x.map(|i| i + base)));
            mc.extend(c);
        }
        let focus: Vec<Vec3<f64>> = if focus_means {
            let lifted: Vec<Vec3<f64>> = means
                .iter()
                .flat_map(|(d, _)| {
                    let c = d.translation();
                    [c + up * (3.0 * big), c - up * (3.0 * big)]
                })
                .collect();
            pos.iter().chain(&lifted).copied().collect()
        } else {
            pos.clone()
        };
        let view = View::fit(&focus, from, up, size, size, 0.1);
        let base = pos.len() as u32;
        pos.extend(mp);
        tri.extend(mt.iter().map(|x| x.map(|i| i + base)));
        col.extend(mc);
        let mut c = Canvas::new(size, size, [250, 250, 250]);
        c.mesh(&view, &pos, &tri, |i| col[i]);
        c.text(8, 8, 2, title, [40, 40, 40]);
        for (k, (name, colour)) in MEANS.iter().enumerate() {
            c.text(8, size - 16 - 14 * (MEANS.len() - 1 - k), 2, name, *colour);
        }
        c.finish()
    };
    let poses: Vec<_> = s
        .poses
        .iter()
        .enumerate()
        .map(|(i, d)| {
            let c = if i < s.inliers {
                [225, 225, 225]
            } else {
                [150, 170, 205]
            };
            (*d, c)
        })
        .collect();
    let all = panel(&poses, 0.05, 0.09, "all poses: 20 % outliers", false);
    let near = panel(&poses[..s.inliers], 0.012, 0.028, "close up", true);
    Image::side_by_side(&[all, near])
}

/// The section "beyond Kavan et al. (§7)".
pub fn beyond_the_blending_paper(figures: Figures) -> Section {
    let mut s = Section::new(
        "Beyond Kavan et al. (§7): averaging measured poses, key-frame curves of rigid motions",
    );
    s.text("§7 names where the dual-quaternion blends should go next. Averaging measured poses: the rigid mean is the pose DIB converges to, Σ wᵢ log(b̂* q̂ᵢ) = 0 (bi-invariant; its rotation part is the geodesic mean of the rotations); the robust means reweight every pose by its distance to the current mean — turn in radians and move in units, in quadrature — with Huber's or Tukey's weights and the scale 1.4826 × the median distance, from the input pose of least median distance to the others (chasles::blend::average, `chasles average`). Each measurement below is the true pose moved by a random twist whose six coordinates have deviation σ = 0.05, given with a random sign.");
    s.attempt(Kavan2006, "§7", AVERAGING, |s| {
        let sizes = [16usize, 64, 256, 1024];
        let rms = error_against_n(&sizes, 16).map_err(|e| e.to_string())?;
        let ns: Vec<f64> = sizes.iter().map(|n| *n as f64).collect();
        let slope = log_slope(&ns, &rms);
        let mut t = Table::new(
            "the rigid mean of n measurements: rms error about the true pose (16 draws each) against σ√6/√n",
            &["n", "rms error", "σ√6/√n", "ratio"],
        );
        let mut worst_ratio = 0.0f64;
        for (n, e) in sizes.iter().zip(&rms) {
            let p = SIGMA * 6f64.sqrt() / (*n as f64).sqrt();
            worst_ratio = worst_ratio.max((e / p - 1.0).abs());
            t.row(vec![
                Cell::text(n.to_string()),
                Cell::Number(Number::sci(*e, 3)),
                Cell::Number(Number::sci(p, 3)),
                Cell::Number(Number::fixed(e / p, 3)),
            ]);
        }
        s.table(t);
        // 20 % outliers: 10 draws of 200 poses.
        let draws = 10;
        let mut sums = [0.0f64; 5];
        let mut first = None;
        for seed in 0..draws {
            let sc = scene(31 + seed, 200, 40).map_err(|e| e.to_string())?;
            let g = truth().map_err(|e| e.to_string())?;
            for (k, m) in sc.means.iter().enumerate() {
                sums[k] += err(*m, g).map_err(|e| e.to_string())? / draws as f64;
            }
            if first.is_none() {
                first = Some(sc);
            }
        }
        let mut t = Table::new(
            "200 poses of which 40 are wild (random rotation, 1–3 units off): the mean error about the true pose over 10 draws (one measurement's own: σ√6 = 0.122)",
            &["mean", "error"],
        );
        for (k, (name, _)) in MEANS.iter().enumerate() {
            t.row(vec![Cell::text(*name), Cell::Number(Number::fixed(sums[k], 4))]);
        }
        s.table(t);
        if figures == Figures::Draw {
            if let Some(sc) = &first {
                s.try_figure(
                    "beyond-average.png",
                    Ok::<_, String>(picture(sc).png()),
                    &format!("200 measured poses of one rigid object as small letters R (160 measurements pale, 40 wild detections grey) and their means as larger letters: the inliers' own mean (black), DLB (orange), DIB (purple), Huber's (green) and Tukey's (red) robust means. Left: everything; right: the measurements close up. Over 10 such draws DLB is {:.2} off the true pose and DIB {:.2}; Huber's mean {:.3}, Tukey's {:.4} (the inliers' own {:.4}).", sums[1], sums[2], sums[3], sums[4], sums[0]),
                );
            }
        }
        let noise = SIGMA * 6f64.sqrt();
        Ok::<_, String>((
            format!(
                "the mean's rms error falls as n^{slope:.3} (σ√6/√n within {:.0} %); with 20 % outliers DLB lands {:.3} and DIB {:.3} from the true pose, Huber's mean {:.4}, Tukey's {:.4} — the inliers' own mean {:.4}, one measurement {noise:.3}",
                worst_ratio * 100.0,
                sums[1], sums[2], sums[3], sums[4], sums[0]
            ),
            (slope + 0.5).abs() < 0.05
                && worst_ratio < 0.2
                && sums[4] < 1.5 * sums[0]
                && sums[3] < 0.5 * noise
                && sums[1] > 2.0 * noise
                && sums[2] > 2.0 * noise,
        ))
    });
    super::rigid_keyframes::rigid_keyframes(&mut s, figures);
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The claim is measured and agrees; the picture draws.
    #[test]
    fn the_section_measures_its_claims() {
        let s = beyond_the_blending_paper(Figures::Draw);
        let claims: Vec<_> = s.claims().collect();
        assert_eq!(claims.len(), 2);
        for c in &claims {
            assert!(c.verdict.agrees(), "{}", c.measured());
        }
        assert_eq!(s.figures().count(), 3);
        for c in &claims {
            println!("{}", c.measured());
        }
    }
}
