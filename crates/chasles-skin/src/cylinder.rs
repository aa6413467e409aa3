//! The candy-wrapper artifact, measured (Kavan et al. 2006, §6 and Figure 6(a–b)).
//!
//! [`twisted_cylinder`] builds a closed cylinder along x — length 2, radius 0.25, 81 rings
//! of 48 vertices and two capped ends — with two bones: joint 0 at the origin, joint 1 at
//! x = 1. Weights blend smoothly across the joint: joint 1's weight is the smoothstep of
//! `(x − 0.6)/0.8`, so vertices from x = 0.6 to 1.4 are shared.
//!
//! [`measure`] poses joint 1 — a twist about the bone's axis x, or a bend about z — skins,
//! and reports the mean radius of the middle cross-section (the ring at x = 1, about its
//! own centroid), the mesh volume and the bulge (the largest vertex distance from the posed
//! bones), all relative to the rest pose. Linear blending
//! collapses the twisted middle towards a line (the candy wrapper: radius → 0 at 180°);
//! dual quaternion skinning keeps it (radius ≈ 1).

use crate::animation::Animation;
use crate::error::Result;
use crate::pose::Pose;
use crate::rig::{compute_normals, Influences, Mesh, Node, Rig, Trs};
use crate::skinning::{skin, Method};
use chasles::{Mat4, Quat, Vec3};

/// The rig's name.
pub const NAME: &str = "twisted cylinder";
/// Rings along the cylinder.
pub const RINGS: usize = 81;
/// Vertices per ring.
pub const SEGMENTS: usize = 48;
/// Rest radius.
pub const RADIUS: f32 = 0.25;

/// The two-bone cylinder rig.
pub fn twisted_cylinder() -> Rig {
    let mut positions = Vec::new();
    let mut lists = Vec::new();
    let weight1 = |x: f32| {
        let u = ((x - 0.6) / 0.8).clamp(0.0, 1.0);
        u * u * (3.0 - 2.0 * u)
    };
    for r in 0..RINGS {
        let x = 2.0 * r as f32 / (RINGS - 1) as f32;
        for s in 0..SEGMENTS {
            let a = std::f32::consts::TAU * s as f32 / SEGMENTS as f32;
            positions.push(Vec3::new(x, RADIUS * a.cos(), RADIUS * a.sin()));
            let w = weight1(x);
            lists.push(vec![(0usize, 1.0 - w), (1usize, w)]);
        }
    }
    let caps = positions.len() as u32;
    positions.push(Vec3::new(0.0, 0.0, 0.0));
    positions.push(Vec3::new(2.0, 0.0, 0.0));
    lists.push(vec![(0, 1.0)]);
    lists.push(vec![(1, 1.0)]);
    let idx = |r: usize, s: usize| (r * SEGMENTS + s % SEGMENTS) as u32;
    let mut triangles = Vec::new();
    for r in 0..RINGS - 1 {
        for s in 0..SEGMENTS {
            // Counter-clockwise seen from outside: outward normals, positive volume.
            triangles.push([idx(r, s), idx(r, s + 1), idx(r + 1, s + 1)]);
            triangles.push([idx(r, s), idx(r + 1, s + 1), idx(r + 1, s)]);
        }
    }
    for s in 0..SEGMENTS {
        triangles.push([caps, idx(0, s + 1), idx(0, s)]);
        triangles.push([caps + 1, idx(RINGS - 1, s), idx(RINGS - 1, s + 1)]);
    }
    let normals = compute_normals(&positions, &triangles);
    let influences = Influences::from_lists(&lists, 2).unwrap_or_default();
    Rig {
        name: NAME.into(),
        mesh: Mesh {
            positions,
            normals,
            triangles,
        },
        nodes: vec![
            Node {
                name: "bone0".into(),
                parent: None,
                rest: Trs::default(),
            },
            Node {
                name: "bone1".into(),
                parent: Some(0),
                rest: Trs {
                    translation: Vec3::new(1.0, 0.0, 0.0),
                    ..Trs::default()
                },
            },
        ],
        joints: vec![0, 1],
        inverse_bind: vec![
            Mat4::identity(),
            Mat4::from_rotation_translation(&chasles::Mat3::identity(), Vec3::new(-1.0, 0.0, 0.0)),
        ],
        influences,
        animations: Vec::<Animation>::new(),
    }
}

/// Which way joint 1 turns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Motion {
    /// About the bone's own axis (x): the candy wrapper.
    Twist,
    /// About z: an elbow.
    Bend,
}

/// The pose with joint 1 turned by `angle` radians.
pub fn pose(rig: &Rig, motion: Motion, angle: f32) -> Pose {
    let mut p = Pose::rest(rig);
    p.local[1].rotation = pose_rotation(motion, angle);
    p
}

/// Mean radius of ring `r` about its centroid.
pub fn ring_radius(positions: &[Vec3<f32>], r: usize) -> f32 {
    let ring = &positions[r * SEGMENTS..(r + 1) * SEGMENTS];
    let c = ring.iter().fold(Vec3::zero(), |a, p| a + *p) / SEGMENTS as f32;
    ring.iter().map(|p| (*p - c).norm()).sum::<f32>() / SEGMENTS as f32
}

/// The enclosed volume of a closed triangle mesh (divergence theorem), in f64.
pub fn volume(positions: &[Vec3<f32>], triangles: &[[u32; 3]]) -> f64 {
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| positions[i as usize].cast::<f64>());
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// The largest distance of a ring vertex from the posed skeleton — bone 0 from the origin
/// to the joint, bone 1 from the joint to its turned end — over all rings.
pub fn bulge(positions: &[Vec3<f32>], motion: Motion, angle: f32) -> f32 {
    let joint = Vec3::new(1.0f32, 0.0, 0.0);
    let end = joint + pose_rotation(motion, angle).rotate(Vec3::new(1.0, 0.0, 0.0));
    let seg = |p: Vec3<f32>, a: Vec3<f32>, b: Vec3<f32>| {
        let d = b - a;
        let u = ((p - a).dot(d) / d.norm_squared()).clamp(0.0, 1.0);
        (p - (a + d * u)).norm()
    };
    positions[..RINGS * SEGMENTS]
        .iter()
        .map(|p| seg(*p, Vec3::zero(), joint).min(seg(*p, joint, end)))
        .fold(0.0f32, f32::max)
}

fn pose_rotation(motion: Motion, angle: f32) -> Quat<f32> {
    let axis = match motion {
        Motion::Twist => 0,
        Motion::Bend => 2,
    };
    Quat::from_axis_index(axis, angle)
}

/// One measurement, relative to the rest pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Artifact {
    /// Mean radius of the ring at the joint, divided by the rest radius.
    pub radius: f32,
    /// Mesh volume divided by the rest volume.
    pub volume: f64,
    /// The largest distance of a vertex from the posed skeleton, divided by the rest radius:
    /// above 1 where the skin bulges out (DQS at a bend).
    pub bulge: f32,
}

/// Skins the cylinder turned by `angle` with `method` and measures it.
pub fn measure(rig: &Rig, method: Method, motion: Motion, angle: f32) -> Result<Artifact> {
    let rest = volume(&rig.mesh.positions, &rig.mesh.triangles);
    let s = skin(rig, &pose(rig, motion, angle), method)?;
    Ok(Artifact {
        radius: ring_radius(&s.positions, RINGS / 2) / RADIUS,
        volume: volume(&s.positions, &rig.mesh.triangles) / rest,
        bulge: bulge(&s.positions, motion, angle) / RADIUS,
    })
}
