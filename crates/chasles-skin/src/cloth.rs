//! The piece of cloth of Kavan et al. 2006, Figure 1 and §6 — "6000 vertices, 12000
//! triangles and 49 joints" — built in code, and the measure of Figure 1(c)'s seams.
//!
//! [`cloth`] is a 100 × 60 grid of vertices over 3 × 1.8 units in the xy plane (6000
//! vertices, 11 682 triangles) with 49 joints on a 7 × 7 grid over it, each at the rest
//! position of its own root node. A vertex is moved by the joints of the grid cell it lies
//! in, weighted by the compactly supported bump `(1 − d/h)²` of its distance d to each
//! (h the joints' spacing), so every weight falls to 0 before its joint leaves a vertex's
//! set: the weights are continuous across the mesh, and so is every blend of them — except
//! SBS's, whose rotation centre is solved once per *cluster* (the vertices with one joint
//! set) and jumps from cluster to cluster (Figure 1(c)). [`pose`] crumples the cloth in its
//! plane: every joint turns about the normal through itself, by `+angle` and `−angle` in a
//! checkerboard over the joint grid (numbered row by row, seven to a row, so that even and
//! odd indices alternate along rows and columns both).
//!
//! [`seams`] measures the jumps: the largest second difference of the posed positions along
//! the grid lines, over the triples of neighbours that cross an SBS cluster border (the
//! seams) and over the others.

use crate::error::Result;
use crate::pose::Pose;
use crate::rig::{compute_normals, Influences, Mesh, Node, Rig, Trs};
use crate::rotation_centre::Clusters;
use chasles::{Mat3, Mat4, Quat, Vec3};

/// The rig's name.
pub const NAME: &str = "cloth";
/// Vertices along x.
pub const NX: usize = 100;
/// Vertices along y.
pub const NY: usize = 60;
/// Joints along each side.
pub const JOINTS_PER_SIDE: usize = 7;
/// The cloth's size along x.
const WIDTH: f32 = 3.0;
/// The cloth's size along y.
const HEIGHT: f32 = 1.8;

/// Joint `(i, k)`'s rest position.
fn joint_at(i: usize, k: usize) -> Vec3<f32> {
    let n = (JOINTS_PER_SIDE - 1) as f32;
    Vec3::new(WIDTH * i as f32 / n, HEIGHT * k as f32 / n, 0.0)
}

/// The cloth rig: 6000 vertices, 49 joints.
pub fn cloth() -> Result<Rig> {
    let n = JOINTS_PER_SIDE;
    let (hx, hy) = (WIDTH / (n - 1) as f32, HEIGHT / (n - 1) as f32);
    let mut positions = Vec::with_capacity(NX * NY);
    let mut lists = Vec::with_capacity(NX * NY);
    for y in 0..NY {
        for x in 0..NX {
            let p = Vec3::new(
                WIDTH * x as f32 / (NX - 1) as f32,
                HEIGHT * y as f32 / (NY - 1) as f32,
                0.0,
            );
            positions.push(p);
            // The corners of the joint cell the vertex lies in, by the bump of their
            // distance (in units of the spacing).
            let (ci, ck) = (
                ((p.x / hx) as usize).min(n - 2),
                ((p.y / hy) as usize).min(n - 2),
            );
            let mut list = Vec::new();
            for (i, k) in [(ci, ck), (ci + 1, ck), (ci, ck + 1), (ci + 1, ck + 1)] {
                let d = p - joint_at(i, k);
                let r = ((d.x / hx).powi(2) + (d.y / hy).powi(2)).sqrt();
                if r < 1.0 {
                    list.push((k * n + i, (1.0 - r) * (1.0 - r)));
                }
            }
            lists.push(list);
        }
    }
    let idx = |x: usize, y: usize| (y * NX + x) as u32;
    let mut triangles = Vec::with_capacity(2 * (NX - 1) * (NY - 1));
    for y in 0..NY - 1 {
        for x in 0..NX - 1 {
            triangles.push([idx(x, y), idx(x + 1, y), idx(x + 1, y + 1)]);
            triangles.push([idx(x, y), idx(x + 1, y + 1), idx(x, y + 1)]);
        }
    }
    let normals = compute_normals(&positions, &triangles);
    let joints = n * n;
    let nodes = (0..joints)
        .map(|j| Node {
            name: format!("joint{j}"),
            parent: None,
            rest: Trs {
                translation: joint_at(j % n, j / n),
                ..Trs::default()
            },
        })
        .collect();
    let inverse_bind = (0..joints)
        .map(|j| Mat4::from_rotation_translation(&Mat3::identity(), -joint_at(j % n, j / n)))
        .collect();
    Rig::new(
        NAME.into(),
        Mesh {
            positions,
            normals,
            triangles,
        },
        nodes,
        (0..joints).collect(),
        inverse_bind,
        Influences::from_lists(&lists, joints)?,
        Vec::new(),
    )
}

/// The cloth crumpled in its plane: each joint turned about the z axis through itself by
/// `angle`, the next one by `−angle` (a checkerboard over the joint grid), so that every
/// joint's neighbours turn the other way and the SBS clusters' rotation centres differ
/// from one cluster to the next.
pub fn pose(rig: &Rig, angle: f32) -> Pose {
    let mut p = Pose::rest(rig);
    for (j, local) in p.local.iter_mut().enumerate() {
        let a = if j % 2 == 0 { angle } else { -angle };
        local.rotation =
            Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), a).unwrap_or(Quat::identity());
    }
    p
}

/// The largest kink of the posed cloth along its grid lines — the second difference
/// `‖p(v−1) − 2 p(v) + p(v+1)‖` of three neighbours along x or along y, which a smooth
/// deformation keeps of the order of the spacing squared and a jump makes as large as the
/// jump — over the triples that cross an SBS cluster border (the seams) and over the
/// others: `(seams, inside)`.
pub fn seams(rig: &Rig, posed: &[Vec3<f32>]) -> (f64, f64) {
    let clusters = Clusters::new(rig.mesh.positions.len(), |v| {
        rig.influences.of(v).map(|(j, _)| j as u16)
    });
    let of = clusters.of_vertex();
    let idx = |x: usize, y: usize| y * NX + x;
    let (mut seam, mut inside) = (0.0f64, 0.0f64);
    let mut visit = |a: usize, b: usize, c: usize| {
        let kink = f64::from((posed[a] - posed[b] * 2.0 + posed[c]).norm());
        if of[a] == of[b] && of[b] == of[c] {
            inside = inside.max(kink);
        } else {
            seam = seam.max(kink);
        }
    };
    for y in 0..NY {
        for x in 1..NX - 1 {
            visit(idx(x - 1, y), idx(x, y), idx(x + 1, y));
        }
    }
    for y in 1..NY - 1 {
        for x in 0..NX {
            visit(idx(x, y - 1), idx(x, y), idx(x, y + 1));
        }
    }
    (seam, inside)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{skin, Method};

    /// The paper's sizes, weights that sum to 1 with at most four joints, and Figure 1(c):
    /// SBS's kinks across cluster borders stand out, DQS's do not.
    #[test]
    fn the_cloth_shows_sbs_seams_and_dqs_none() {
        let rig = cloth().unwrap();
        assert_eq!((rig.mesh.positions.len(), rig.joints.len()), (6000, 49));
        assert_eq!(rig.mesh.triangles.len(), 2 * 99 * 59);
        for v in 0..6000 {
            let w: Vec<f32> = rig.influences.of(v).map(|(_, w)| w).collect();
            assert!(!w.is_empty() && w.len() <= 4, "{v}: {w:?}");
            assert!((w.iter().sum::<f32>() - 1.0).abs() < 1e-5, "{v}: {w:?}");
        }
        let p = pose(&rig, 0.6);
        let (sbs, sbs_in) = seams(&rig, &skin(&rig, &p, Method::Sbs).unwrap().positions);
        let (dqs, dqs_in) = seams(&rig, &skin(&rig, &p, Method::Dqs).unwrap().positions);
        assert!(sbs > 1.5 * dqs, "SBS {sbs} vs DQS {dqs}");
        assert!(
            sbs > 1.3 * sbs_in && dqs < 1.1 * dqs_in,
            "{sbs} {sbs_in} {dqs} {dqs_in}"
        );
        // At rest nothing kinks.
        let (a, b) = seams(&rig, &rig.mesh.positions);
        assert!(a < 1e-6 && b < 1e-6, "{a} {b}");
    }
}
