//! What a page shows, as data: the bind mesh laid out for the vertex shaders (positions,
//! normals, four joints a vertex heaviest first, weights, triangles), and the joint palettes
//! of every frame — a clip sampled at a fixed rate, or the twisted cylinder's grid of twist
//! and bend angles — each joint as its LBS rows ([`Affine3x4`]) then its dual quaternion
//! ([`UnitDualQuat`]), made by [`Palette::update`] from
//! [`chasles_skin::pose::skinning_matrices`]. With each frame goes LBS's smallest local
//! volume there (the det of the blended 3×3, [`chasles_skin::volume`]), so the page can say
//! where linear blending loses the most.

use crate::ViewError;
use chasles_skin::cylinder::{self, Motion};
use chasles_skin::fast::{Affine3x4, FastRig, Joints, Palette, UnitDualQuat};
use chasles_skin::pose::skinning_matrices;
use chasles_skin::{volume, Method, Pose, Rig};
use serde::Serialize;

/// Floats a joint takes in a palette: LBS's 12, then DQS's 8 (five RGBA texels).
pub const FLOATS_PER_JOINT: usize = 20;

/// The most palette floats a page holds (64 MiB of them): a ceiling against a clip that
/// lasts an hour.
pub const MAX_PALETTE_FLOATS: usize = 16 << 20;

/// One clip, sampled.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Clip {
    /// Its name (`clip N` when the file has none, `rest pose` for a rig without clips).
    pub name: String,
    /// Seconds.
    pub duration: f32,
    /// Frames a second.
    pub fps: f32,
    /// The time of every frame: `k / fps`, the last one the clip's end.
    pub times: Vec<f32>,
    /// LBS's smallest det of the blended 3×3 at every frame.
    pub min_det: Vec<f32>,
    /// The frame where it is smallest.
    pub worst: usize,
    /// `frames × joints ×` [`FLOATS_PER_JOINT`] floats.
    #[serde(skip)]
    pub palettes: Vec<f32>,
}

/// The twisted cylinder's poses: joint 1 turned by `Rz(bend) · Rx(twist)` for every pair
/// of angles on the grid (degrees), palettes bend-major.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Grid {
    /// Twist angles, degrees.
    pub twist: Vec<f32>,
    /// Bend angles, degrees.
    pub bend: Vec<f32>,
    /// LBS's smallest det of the blended 3×3 at every pose (bend-major).
    pub min_det: Vec<f32>,
    /// `bend × twist × joints ×` [`FLOATS_PER_JOINT`] floats.
    #[serde(skip)]
    pub palettes: Vec<f32>,
}

/// The bind mesh as the vertex shaders read it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Buffers {
    /// xyz per vertex.
    pub positions: Vec<f32>,
    /// xyz per vertex.
    pub normals: Vec<f32>,
    /// Four joint indices per vertex, heaviest influence first.
    pub joints: Vec<u16>,
    /// Four weights per vertex, summing to 1.
    pub weights: Vec<f32>,
    /// Three vertex indices per triangle.
    pub triangles: Vec<u32>,
}

/// Everything a page shows.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The title (the file name, or the cylinder's).
    pub title: String,
    /// Licence and attribution of the model.
    pub credit: String,
    /// Joints of the skin.
    pub joints: usize,
    /// The mesh.
    pub buffers: Buffers,
    /// The clips (empty for the cylinder).
    pub clips: Vec<Clip>,
    /// The clip shown first.
    pub clip: usize,
    /// The cylinder's twist × bend grid.
    pub grid: Option<Grid>,
    /// The skinned mesh's bounds over some frames: smallest and largest corner.
    pub bounds: [[f32; 3]; 2],
}

/// The mesh of `rig` laid out four influences a vertex (an error for more).
fn buffers(rig: &Rig, fast: &FastRig<4>) -> Buffers {
    let mut b = Buffers::default();
    for v in fast.vertices() {
        b.positions.extend(v.p);
        b.normals.extend(v.n);
        b.joints.extend(v.j);
        b.weights.extend(v.w);
    }
    b.triangles = rig.mesh.triangles.iter().flatten().copied().collect();
    b
}

/// Reusable palettes for one pose after another.
struct Palettes {
    lbs: Palette,
    dqs: Palette,
}

impl Palettes {
    fn new() -> Self {
        Palettes {
            lbs: Palette::new(Method::Lbs),
            dqs: Palette::new(Method::Dqs),
        }
    }

    /// Appends `pose`'s joints to `out` (LBS rows then dual quaternion, joint by joint) and
    /// returns LBS's smallest local volume there.
    fn push(
        &mut self,
        rig: &Rig,
        fast: &FastRig<4>,
        pose: &Pose,
        out: &mut Vec<f32>,
    ) -> Result<f32, ViewError> {
        let matrices = skinning_matrices(rig, pose)?;
        self.lbs.update(fast, &matrices, false)?;
        self.dqs.update(fast, &matrices, false)?;
        let (Joints::Lbs(rows), Joints::Dqs(dqs)) = (self.lbs.data(), self.dqs.data()) else {
            unreachable!("palettes made for LBS and DQS");
        };
        for (a, d) in rows.iter().zip(dqs) {
            let a: &Affine3x4 = a;
            let d: &UnitDualQuat = d;
            out.extend(a.rows.iter().flatten());
            out.extend(d.real);
            out.extend(d.dual);
        }
        Ok(volume::lbs_min_determinant(rig, pose)?)
    }
}

/// The clip `clip` of `rig` at `fps` (the rest pose alone when `clip` is `None`).
fn sample(
    rig: &Rig,
    fast: &FastRig<4>,
    clip: Option<usize>,
    fps: f32,
    budget: &mut usize,
) -> Result<Clip, ViewError> {
    let (name, duration) = match clip {
        Some(c) => {
            let a = &rig.animations[c];
            let name = if a.name.is_empty() {
                format!("clip {c}")
            } else {
                a.name.clone()
            };
            (name, a.duration())
        }
        None => ("rest pose".to_string(), 0.0),
    };
    let frames = (f64::from(duration) * f64::from(fps) - 1e-6)
        .ceil()
        .max(0.0)
        + 1.0;
    let floats = frames * (rig.joints.len() * FLOATS_PER_JOINT) as f64;
    if floats > *budget as f64 {
        return Err(ViewError::TooLong {
            clip: name,
            frames: frames as u64,
            limit: MAX_PALETTE_FLOATS / (rig.joints.len() * FLOATS_PER_JOINT).max(1),
        });
    }
    *budget -= floats as usize;
    let frames = frames as usize;
    let times: Vec<f32> = (0..frames)
        .map(|k| (k as f32 / fps).min(duration))
        .collect();
    let mut palettes = Vec::with_capacity(floats as usize);
    let mut min_det = Vec::with_capacity(frames);
    let mut p = Palettes::new();
    for &t in &times {
        let pose = match clip {
            Some(c) => Pose::animated(rig, c, t)?,
            None => Pose::rest(rig),
        };
        min_det.push(p.push(rig, fast, &pose, &mut palettes)?);
    }
    let worst = (0..frames).fold(0, |w, k| if min_det[k] < min_det[w] { k } else { w });
    Ok(Clip {
        name,
        duration,
        fps,
        times,
        min_det,
        worst,
        palettes,
    })
}

/// The bounds of `rig` skinned by DQS in `poses`.
fn bounds<'a>(
    rig: &Rig,
    poses: impl Iterator<Item = &'a Pose>,
) -> Result<[[f32; 3]; 2], ViewError> {
    let mut b = [[f32::INFINITY; 3], [f32::NEG_INFINITY; 3]];
    for pose in poses {
        for p in chasles_skin::skin(rig, pose, Method::Dqs)?.positions {
            for (i, x) in p.to_array().into_iter().enumerate() {
                b[0][i] = b[0][i].min(x);
                b[1][i] = b[1][i].max(x);
            }
        }
    }
    if b[0][0] > b[1][0] {
        return Ok([[-1.0; 3], [1.0; 3]]);
    }
    Ok(b)
}

impl Scene {
    /// A character: every clip of `rig` sampled at `fps`, `clip` (by name or index) shown
    /// first; a rig without clips shows its rest pose.
    pub fn character(
        rig: &Rig,
        clip: Option<&str>,
        fps: f32,
        credit: &str,
    ) -> Result<Scene, ViewError> {
        if !(fps.is_finite() && (1.0..=240.0).contains(&fps)) {
            return Err(ViewError::Fps(fps));
        }
        let first = match clip {
            None => 0,
            Some(name) => find_clip(rig, name)?,
        };
        let fast = FastRig::<4>::new(rig)?;
        let mut budget = MAX_PALETTE_FLOATS;
        let clips = if rig.animations.is_empty() {
            vec![sample(rig, &fast, None, fps, &mut budget)?]
        } else {
            (0..rig.animations.len())
                .map(|c| sample(rig, &fast, Some(c), fps, &mut budget))
                .collect::<Result<_, _>>()?
        };
        // Bounds over nine times of the first clip shown.
        let shown = &clips[first];
        let n = shown.times.len();
        let poses: Vec<Pose> = (0..9)
            .map(|k| {
                let t = shown.times[(k * (n - 1)) / 8];
                if rig.animations.is_empty() {
                    Ok(Pose::rest(rig))
                } else {
                    Pose::animated(rig, first, t)
                }
            })
            .collect::<Result<_, _>>()?;
        Ok(Scene {
            title: rig.name.clone(),
            credit: credit.into(),
            joints: rig.joints.len(),
            buffers: buffers(rig, &fast),
            bounds: bounds(rig, poses.iter())?,
            clips,
            clip: first,
            grid: None,
        })
    }

    /// The twisted two-bone cylinder of [`chasles_skin::cylinder`] (the candy wrapper,
    /// Kavan et al. 2006, Figure 6(a)–(b)): joint 1 turned by `Rz(bend) · Rx(twist)` for
    /// twist 0°–360° and bend 0°–180°, every `step` degrees.
    pub fn cylinder(step: f32) -> Result<Scene, ViewError> {
        let rig = cylinder::twisted_cylinder();
        let fast = FastRig::<4>::new(&rig)?;
        let angles = |end: f32| -> Vec<f32> {
            let n = (end / step).round() as usize;
            (0..=n).map(|k| k as f32 * step).collect()
        };
        let (twist, bend) = (angles(360.0), angles(180.0));
        let mut palettes = Vec::new();
        let mut min_det = Vec::new();
        let mut p = Palettes::new();
        for &b in &bend {
            for &t in &twist {
                min_det.push(p.push(&rig, &fast, &cylinder_pose(&rig, t, b), &mut palettes)?);
            }
        }
        // Centred on the joint: the twisted poses' bounds (the bent end stays within their
        // sphere).
        let corners = [(0.0, 0.0), (180.0, 0.0)];
        let poses: Vec<Pose> = corners
            .iter()
            .map(|&(t, b)| cylinder_pose(&rig, t, b))
            .collect();
        Ok(Scene {
            title: "the twisted cylinder".into(),
            credit: "built in code by chasles (chasles_skin::cylinder): two bones, smooth weights across the joint".into(),
            joints: rig.joints.len(),
            buffers: buffers(&rig, &fast),
            bounds: bounds(&rig, poses.iter())?,
            clips: Vec::new(),
            clip: 0,
            grid: Some(Grid {
                twist,
                bend,
                min_det,
                palettes,
            }),
        })
    }
}

/// The cylinder's pose with joint 1 twisted about its axis by `twist` degrees, then bent
/// about z by `bend` degrees (either alone is [`cylinder::pose`]'s).
pub fn cylinder_pose(rig: &Rig, twist: f32, bend: f32) -> Pose {
    let mut pose = cylinder::pose(rig, Motion::Twist, twist.to_radians());
    let b = cylinder::pose(rig, Motion::Bend, bend.to_radians());
    pose.local[1].rotation = b.local[1].rotation * pose.local[1].rotation;
    pose
}

/// The index of the clip called `name` (or numbered `name`), or an error listing them.
pub fn find_clip(rig: &Rig, name: &str) -> Result<usize, ViewError> {
    rig.clip_index(name).map_err(|_| ViewError::UnknownClip {
        rig: rig.name.clone(),
        clip: name.into(),
        known: rig.clip_names(),
    })
}
