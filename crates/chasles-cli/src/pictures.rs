//! The skinning pictures (Kavan et al. 2006, §6, Figures 1 and 6): one pose skinned by
//! every method side by side, and animations — the candy-wrapper twist sweep of the
//! two-bone cylinder, or a character's clip — with linear and dual-quaternion skinning
//! next to each other — and line plots of the candy wrapper (radius against twist) and of
//! LBS's volume loss over a clip. Shared by `chasles skin --render/--gif/--plot` and the
//! tour.

use anyhow::Result;
use chasles::Vec3;
use chasles_skin::cylinder::{self, Motion};
use chasles_skin::{skin, Method, Pose, Rig};
use chasles_viz::panels::{side_by_side, Panel};
use chasles_viz::Image;

/// Panel size of the side-by-side pictures.
const PANEL: (usize, usize) = (260, 320);
/// Panel size of the cylinder pictures (a long thin shape).
const CYLINDER_PANEL: (usize, usize) = (300, 170);

/// How a rig is looked at: the cylinder (along x) from above the front, a glTF character
/// (y up) from its front-left.
fn view_of(rig: &Rig) -> (Vec3<f64>, Vec3<f64>, (usize, usize)) {
    if rig.name == cylinder::NAME {
        (
            Vec3::new(0.15, 0.55, 1.0),
            Vec3::new(0.0, 1.0, 0.0),
            CYLINDER_PANEL,
        )
    } else {
        (Vec3::new(0.55, 0.2, 1.0), Vec3::new(0.0, 1.0, 0.0), PANEL)
    }
}

/// Colour of triangle `i`: skin tone; for the cylinder alternating bands around it so
/// that a twist shows as a helix; for the cloth a checkerboard of 3 × 3 grid cells, so that
/// a kink shows as a broken line.
fn colour_of(rig: &Rig) -> impl Fn(usize) -> [u8; 3] + '_ {
    let cyl = rig.name == cylinder::NAME;
    let cloth = rig.name == chasles_skin::cloth::NAME;
    move |i: usize| {
        if cloth {
            let v = rig.mesh.triangles[i][0] as usize;
            let (x, y) = (v % chasles_skin::cloth::NX, v / chasles_skin::cloth::NX);
            if (x / 3 + y / 3).is_multiple_of(2) {
                [70, 130, 200]
            } else {
                [235, 235, 225]
            }
        } else if cyl {
            let first = rig.mesh.triangles[i][0] as usize % cylinder::SEGMENTS;
            if (first / 6).is_multiple_of(2) {
                [70, 130, 200]
            } else {
                [235, 235, 225]
            }
        } else {
            [210, 165, 125]
        }
    }
}

/// `pose` of `rig` skinned by each of `methods`: one labelled panel each.
fn panels_of(rig: &Rig, pose: &Pose, methods: &[Method]) -> Result<Vec<Panel<'static>>> {
    methods
        .iter()
        .map(|m| {
            let s = skin(rig, pose, *m)?;
            Ok(Panel {
                label: m.name(),
                positions: s.positions.iter().map(|p| p.cast::<f64>()).collect(),
            })
        })
        .collect()
}

/// `pose` of `rig` skinned by each of `methods`, side by side, labelled, seen from the
/// front (+z) and fitted to the vertices `focus` (rest-pose indices) as the first method
/// places them: a close-up.
pub fn methods_facing(
    rig: &Rig,
    pose: &Pose,
    methods: &[Method],
    focus: &[usize],
    size: (usize, usize),
) -> Result<Image> {
    let panels = panels_of(rig, pose, methods)?;
    let around: Vec<Vec3<f64>> = panels
        .first()
        .map(|p| focus.iter().map(|v| p.positions[*v]).collect())
        .unwrap_or_default();
    Ok(chasles_viz::panels::side_by_side_fitted(
        &panels,
        &rig.mesh.triangles,
        &colour_of(rig),
        &around,
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.0, 1.0, 0.0),
        size,
    ))
}

/// `pose` of `rig` skinned by each of `methods`, side by side, labelled.
pub fn methods_side_by_side(rig: &Rig, pose: &Pose, methods: &[Method]) -> Result<Image> {
    let panels = panels_of(rig, pose, methods)?;
    let (from, up, (w, h)) = view_of(rig);
    Ok(side_by_side(
        &panels,
        &rig.mesh.triangles,
        &colour_of(rig),
        from,
        up,
        w,
        h,
    ))
}

/// A close-up of `pose` around the vertex where LBS keeps the least volume: every method
/// of `methods` side by side, the view fitted to the rest-pose neighbourhood (a fifth of
/// the mesh's size around) of that vertex as each method places it.
pub fn methods_closeup(rig: &Rig, pose: &Pose, methods: &[Method]) -> Result<Image> {
    let (worst, _) = chasles_skin::volume::lbs_worst_vertex(rig, pose)?;
    let rest = &rig.mesh.positions;
    let (lo, hi) = rest.iter().fold(
        ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
        |(lo, hi), p| {
            let a = p.to_array();
            (
                [lo[0].min(a[0]), lo[1].min(a[1]), lo[2].min(a[2])],
                [hi[0].max(a[0]), hi[1].max(a[1]), hi[2].max(a[2])],
            )
        },
    );
    let size = (0..3).map(|i| hi[i] - lo[i]).fold(0.0f32, f32::max);
    let near: Vec<usize> = (0..rest.len())
        .filter(|v| (rest[*v] - rest[worst]).norm() < size * 0.2)
        .collect();
    let panels = panels_of(rig, pose, methods)?;
    let focus: Vec<Vec3<f64>> = panels
        .iter()
        .flat_map(|p| near.iter().map(|v| p.positions[*v]))
        .collect();
    let (from, up, (w, h)) = view_of(rig);
    Ok(chasles_viz::panels::side_by_side_fitted(
        &panels,
        &rig.mesh.triangles,
        &colour_of(rig),
        &focus,
        from,
        up,
        (w, h),
    ))
}

/// Frames of LBS beside DQS: the cylinder twisted from 0° to 180° and back
/// (`frames` steps each way).
pub fn twist_sweep(frames: usize) -> Result<Vec<Image>> {
    let rig = cylinder::twisted_cylinder();
    let n = frames.max(2);
    let angles: Vec<f32> = (0..n)
        .chain((1..n - 1).rev())
        .map(|k| 180f32.to_radians() * k as f32 / (n - 1) as f32)
        .collect();
    angles
        .iter()
        .map(|a| {
            let pose = cylinder::pose(&rig, Motion::Twist, *a);
            methods_side_by_side(&rig, &pose, &[Method::Lbs, Method::Dqs])
        })
        .collect()
}

/// The first `n` frames of LBS beside DQS playing clip `clip` of `rig` at `fps` (the
/// caller counts them, against its ceiling).
pub fn clip_frames(rig: &Rig, clip: usize, fps: f32, n: usize) -> Result<Vec<Image>> {
    (0..n)
        .map(|f| {
            let pose = Pose::animated(rig, clip, f as f32 / fps)?;
            methods_side_by_side(rig, &pose, &[Method::Lbs, Method::Dqs])
        })
        .collect()
}

/// Line colours for the six skinning methods, in [`Method::ALL`] order.
const METHOD_COLOURS: [&str; 6] = [
    "#c0392b", "#1f5fbf", "#27ae60", "#8e44ad", "#e67e22", "#16a085",
];

/// The middle cross-section's radius against the twist angle, every method, with LBS's
/// closed form cos(θ/2) (weights ½, ½ at the middle) dashed.
pub fn twist_plot() -> Result<String> {
    use chasles_viz::plot::{lines_svg, Series};
    let rig = cylinder::twisted_cylinder();
    let angles: Vec<f32> = (0..=36).map(|k| 5.0 * k as f32).collect();
    let mut series = Vec::new();
    for (m, colour) in Method::ALL.iter().zip(METHOD_COLOURS) {
        let pts = angles
            .iter()
            .map(|deg| {
                let a = cylinder::measure(&rig, *m, Motion::Twist, deg.to_radians())?;
                Ok((f64::from(*deg), f64::from(a.radius)))
            })
            .collect::<Result<Vec<_>>>()?;
        series.push(Series {
            name: m.name(),
            colour,
            dashed: false,
            points: pts,
        });
    }
    series.push(Series {
        name: "cos(θ/2)",
        colour: "#000000",
        dashed: true,
        points: angles
            .iter()
            .map(|d| (f64::from(*d), (f64::from(*d).to_radians() / 2.0).cos()))
            .collect(),
    });
    Ok(lines_svg(
        &series,
        "The candy wrapper: middle radius of the twisted cylinder",
        "twist (degrees)",
        "radius / rest radius",
    ))
}

/// LBS's smallest determinant of the blended 3×3 over clip `clip` (41 times), with the 1
/// that rigid blends keep dashed.
pub fn volume_plot(rig: &Rig, clip: usize) -> Result<String> {
    use chasles_viz::plot::{lines_svg, Series};
    let over = chasles_skin::volume::lbs_volume_over_clip(rig, clip, 40)?;
    let lbs: Vec<(f64, f64)> = over
        .iter()
        .map(|(t, d)| (f64::from(*t), f64::from(*d)))
        .collect();
    let rigid = lbs.iter().map(|(t, _)| (*t, 1.0)).collect();
    let series = [
        Series {
            name: "lbs",
            colour: METHOD_COLOURS[0],
            dashed: false,
            points: lbs,
        },
        Series {
            name: "dqs, dib",
            colour: METHOD_COLOURS[1],
            dashed: true,
            points: rigid,
        },
    ];
    Ok(lines_svg(
        &series,
        &format!(
            "{}: smallest local volume (det of the blended 3×3)",
            rig.name
        ),
        "time in the clip (s)",
        "det",
    ))
}

/// The clip's most-turning rotation channel (the largest angle between any of its keys and
/// its first) on the unit sphere (Dam et al. §5.3): its key rotations as keys, 200 samples
/// of the clip as frames. Returns the picture and the node's name.
pub fn rotation_sphere(rig: &Rig, clip: usize) -> Result<(Image, String)> {
    use chasles::Quat;
    use chasles_skin::animation::Path;
    use chasles_viz::sphere::{fixed_coordinate, render, Mark};
    let a = rig
        .animations
        .get(clip)
        .ok_or_else(|| anyhow::anyhow!("{}: no animation {clip}", rig.name))?;
    let q_at = |c: &chasles_skin::animation::Channel, t: f32| {
        let v = c.sample(t).map(f64::from);
        Quat::new(v[0], v[1], v[2], v[3])
            .normalize()
            .unwrap_or(Quat::identity())
    };
    let turn = |c: &chasles_skin::animation::Channel| {
        let q0 = q_at(c, c.times[0]);
        c.times
            .iter()
            .map(|t| q0.angle_to(q_at(c, *t)).unwrap_or(0.0))
            .fold(0.0f64, f64::max)
    };
    let channel = a
        .channels
        .iter()
        .filter(|c| c.path == Path::Rotation && !c.times.is_empty())
        .max_by(|x, y| turn(x).total_cmp(&turn(y)))
        .ok_or_else(|| anyhow::anyhow!("{}: clip {clip} turns no joint", rig.name))?;
    let (t0, t1) = (channel.times[0], channel.times[channel.times.len() - 1]);
    // Chain the hemispheres so the curve is continuous (q and −q are one rotation).
    let near = |prev: Quat<f64>, q: Quat<f64>| if prev.dot(q) < 0.0 { -q } else { q };
    let mut pts: Vec<(Quat<f64>, Mark)> = Vec::new();
    let mut prev = q_at(channel, t0);
    for k in 0..=200 {
        let t = t0 + (t1 - t0) * k as f32 / 200.0;
        prev = near(prev, q_at(channel, t));
        pts.push((prev, Mark::Frame));
    }
    let mut prev = q_at(channel, t0);
    for (i, t) in channel.times.iter().enumerate() {
        let m = if i == 0 { Mark::FirstKey } else { Mark::Key };
        prev = near(prev, q_at(channel, *t));
        pts.push((prev, m));
    }
    let all: Vec<Quat<f64>> = pts.iter().map(|p| p.0).collect();
    let name = rig
        .nodes
        .get(channel.node)
        .map_or_else(|| format!("node {}", channel.node), |n| n.name.clone());
    Ok((render(&pts, fixed_coordinate(&all), 500), name))
}
