//! The skinning pictures (Kavan et al. 2006, §6, Figures 1 and 6): one pose skinned by
//! every method side by side, and animations — the candy-wrapper twist sweep of the
//! two-bone cylinder, or a character's clip — with linear and dual-quaternion skinning
//! next to each other. Shared by `chasles skin --render/--gif` and the tour.

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

/// Colour of triangle `i`: skin tone, or for the cylinder alternating bands around it so
/// that a twist shows as a helix.
fn colour_of(rig: &Rig) -> impl Fn(usize) -> [u8; 3] + '_ {
    let cyl = rig.name == cylinder::NAME;
    move |i: usize| {
        if cyl {
            let first = rig.mesh.triangles[i][0] as usize % cylinder::SEGMENTS;
            if (first / 6) % 2 == 0 {
                [70, 130, 200]
            } else {
                [235, 235, 225]
            }
        } else {
            [210, 165, 125]
        }
    }
}

/// `pose` of `rig` skinned by each of `methods`, side by side, labelled.
pub fn methods_side_by_side(rig: &Rig, pose: &Pose, methods: &[Method]) -> Result<Image> {
    let mut panels = Vec::new();
    for m in methods {
        let s = skin(rig, pose, *m)?;
        panels.push(Panel {
            label: m.name(),
            positions: s.positions.iter().map(|p| p.cast::<f64>()).collect(),
        });
    }
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

/// Frames of LBS beside DQS playing clip `clip` of `rig` at `fps`.
pub fn clip_frames(rig: &Rig, clip: usize, fps: f32) -> Result<Vec<Image>> {
    let duration = rig.animations[clip].duration();
    let n = (duration * fps).floor() as usize + 1;
    (0..n)
        .map(|f| {
            let pose = Pose::animated(rig, clip, f as f32 / fps)?;
            methods_side_by_side(rig, &pose, &[Method::Lbs, Method::Dqs])
        })
        .collect()
}
