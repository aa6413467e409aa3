//! A large character built in code, to measure the page on big meshes: a snake — a tube of
//! [`BONES`] bones along x, `rings × segments` vertices, each blended smoothly between the
//! two nearest bones — with a two-second clip in which every bone bends and twists in a
//! travelling wave (the candy wrapper and the lost volume of Kavan et al. 2006, §6,
//! everywhere along it).

use chasles::{Mat4, Quat, Vec3};
use chasles_skin::animation::{Animation, Channel, Interpolation, Path};
use chasles_skin::rig::compute_normals;
use chasles_skin::{Influences, Mesh, Node, Rig, SkinError, Trs};

/// Bones along the snake, each of length 1.
pub const BONES: usize = 8;
/// Vertices around each ring.
pub const SEGMENTS: usize = 250;
/// The tube's radius.
pub const RADIUS: f32 = 0.3;

/// A snake of about `vertices` vertices (rings of [`SEGMENTS`]; at least two rings) with one
/// clip, "wave".
pub fn snake(vertices: usize) -> Result<Rig, SkinError> {
    let rings = (vertices / SEGMENTS).max(2);
    let length = BONES as f32;
    let mut positions = Vec::with_capacity(rings * SEGMENTS);
    let mut lists = Vec::with_capacity(rings * SEGMENTS);
    for r in 0..rings {
        let x = length * r as f32 / (rings - 1) as f32;
        // Bone k's middle is at k + ½; between two middles the weight moves smoothly.
        let f = (x - 0.5).clamp(0.0, (BONES - 1) as f32);
        let k = (f.floor() as usize).min(BONES - 2);
        let u = (f - k as f32).clamp(0.0, 1.0);
        let w = u * u * (3.0 - 2.0 * u);
        for s in 0..SEGMENTS {
            let a = std::f32::consts::TAU * s as f32 / SEGMENTS as f32;
            positions.push(Vec3::new(x, RADIUS * a.cos(), RADIUS * a.sin()));
            lists.push(vec![(k, 1.0 - w), (k + 1, w)]);
        }
    }
    let idx = |r: usize, s: usize| (r * SEGMENTS + s % SEGMENTS) as u32;
    let mut triangles = Vec::with_capacity(2 * (rings - 1) * SEGMENTS);
    for r in 0..rings - 1 {
        for s in 0..SEGMENTS {
            triangles.push([idx(r, s), idx(r, s + 1), idx(r + 1, s + 1)]);
            triangles.push([idx(r, s), idx(r + 1, s + 1), idx(r + 1, s)]);
        }
    }
    let normals = compute_normals(&positions, &triangles);
    let nodes = (0..BONES)
        .map(|k| Node {
            name: format!("bone{k}"),
            parent: k.checked_sub(1),
            rest: Trs {
                translation: Vec3::new(if k == 0 { 0.0 } else { 1.0 }, 0.0, 0.0),
                ..Trs::default()
            },
        })
        .collect();
    let inverse_bind = (0..BONES)
        .map(|k| {
            Mat4::from_rotation_translation(
                &chasles::Mat3::identity(),
                Vec3::new(-(k as f32), 0.0, 0.0),
            )
        })
        .collect();
    // Keys every ¼ s over 2 s: bone k bends about z and twists about x, a quarter period
    // behind bone k − 1.
    let times: Vec<f32> = (0..=8).map(|i| i as f32 * 0.25).collect();
    let channels = (1..BONES)
        .map(|k| Channel {
            node: k,
            path: Path::Rotation,
            interpolation: Interpolation::Linear,
            times: times.clone(),
            values: times
                .iter()
                .map(|t| {
                    let phase = std::f32::consts::PI * (t - 0.25 * k as f32);
                    let bend = Quat::from_axis_index(2, 0.5 * phase.sin());
                    let twist = Quat::from_axis_index(0, 1.2 * phase.cos());
                    (bend * twist).to_array()
                })
                .collect(),
        })
        .collect();
    Rig::new(
        format!("snake ({} vertices)", positions.len()),
        Mesh {
            positions,
            normals,
            triangles,
        },
        nodes,
        (0..BONES).collect(),
        inverse_bind,
        Influences::from_lists(&lists, BONES)?,
        vec![Animation {
            name: "wave".into(),
            channels,
        }],
    )
}
