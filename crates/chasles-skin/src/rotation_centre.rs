//! The centres that decomposed blends rotate about (Kavan et al. 2006, §2.2 and §6: Dec and
//! QLB are coordinate dependent, so skinning must choose a centre per vertex).
//!
//! * [`joint_centres`] — each joint's origin in the bind pose; decomposed QLB (Hejl 2004)
//!   rotates a vertex about the weighted mean of its joints' origins.
//! * [`Clusters`] — spherical blend skinning (Kavan & Žára 2005) groups the vertices bound
//!   to the same set of joints and gives each cluster one *rotation centre* per pose: the
//!   point r whose images under the cluster's joint transforms agree best,
//!   `min Σ_{a<b} ‖(R_a − R_b) r + t_a − t_b‖²`. The 3×3 normal equations are solved in f64
//!   with a small Tikhonov term (1e-6 of the trace) pulling r towards the mean of the
//!   cluster's joint origins, where the problem is rank-deficient (the paper takes the
//!   SVD's pseudo-inverse; along a deficient direction the blend does not depend on r).
//!   A cluster of one joint moves rigidly, about any centre.
//!
//! The reference and fast paths share this code, so their centres are the same numbers.

use chasles::{DualQuat, Mat3, Mat4, Vec3};
use rayon::prelude::*;
use std::collections::HashMap;

/// The origin of each joint's frame in bind space: the translation of the inverse of its
/// inverse bind matrix (the origin where that matrix is singular).
pub fn joint_centres(inverse_bind: &[Mat4<f32>]) -> Vec<Vec3<f32>> {
    inverse_bind
        .iter()
        .map(|ib| match ib.linear_part().inverse() {
            Some(inv) => -inv.mul_vec(ib.translation()),
            None => Vec3::zero(),
        })
        .collect()
}

/// Vertices grouped by the set of joints that move them.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Clusters {
    /// The cluster of each vertex.
    of_vertex: Vec<u32>,
    /// The sorted joints of cluster c: `joints[start[c]..start[c + 1]]`.
    start: Vec<u32>,
    joints: Vec<u16>,
}

/// Clusters at least this many are solved on all threads.
const PARALLEL: usize = 256;

impl Clusters {
    /// Groups `vertices` vertices by their joint sets; `joints_of(v)` lists vertex v's
    /// joints (any order, repeats allowed).
    pub fn new<I: IntoIterator<Item = u16>>(
        vertices: usize,
        joints_of: impl Fn(usize) -> I,
    ) -> Self {
        let mut index: HashMap<Vec<u16>, u32> = HashMap::new();
        let mut out = Clusters {
            of_vertex: Vec::with_capacity(vertices),
            start: vec![0],
            joints: Vec::new(),
        };
        for v in 0..vertices {
            let mut key: Vec<u16> = joints_of(v).into_iter().collect();
            key.sort_unstable();
            key.dedup();
            let next = index.len() as u32;
            let c = *index.entry(key).or_insert_with_key(|key| {
                out.joints.extend_from_slice(key);
                out.start.push(out.joints.len() as u32);
                next
            });
            out.of_vertex.push(c);
        }
        out
    }

    /// The number of clusters.
    pub fn len(&self) -> usize {
        self.start.len() - 1
    }

    /// Whether there are no clusters (no vertices).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The cluster of each vertex.
    pub fn of_vertex(&self) -> &[u32] {
        &self.of_vertex
    }

    /// The sorted joints of cluster `c`.
    pub fn joints(&self, c: usize) -> &[u16] {
        &self.joints[self.start[c] as usize..self.start[c + 1] as usize]
    }

    /// The rotation centre of every cluster for joint transforms `d` (one per joint) and the
    /// joints' bind origins `bind` ([`joint_centres`]); on all threads for many clusters.
    pub fn centres(&self, d: &[DualQuat<f32>], bind: &[Vec3<f32>]) -> Vec<Vec3<f32>> {
        let m: Vec<Mat4<f32>> = d.iter().map(|d| d.to_matrix4()).collect();
        let solve = |c: usize| {
            let joints = self.joints(c);
            let prior = joints
                .iter()
                .fold(Vec3::zero(), |s, j| s + bind[usize::from(*j)])
                * (1.0 / joints.len().max(1) as f32);
            rotation_centre(joints, &m, prior)
        };
        if self.len() >= PARALLEL {
            (0..self.len()).into_par_iter().map(solve).collect()
        } else {
            (0..self.len()).map(solve).collect()
        }
    }
}

/// The rotation centre of one cluster: `min Σ_{a<b} ‖(R_a − R_b) r + t_a − t_b‖²`, with a
/// Tikhonov pull towards `prior` (1e-6 of the trace) for the rank-deficient directions.
pub fn rotation_centre(joints: &[u16], m: &[Mat4<f32>], prior: Vec3<f32>) -> Vec3<f32> {
    let mut a = [[0f64; 3]; 3];
    let mut b = [0f64; 3];
    for (i, ja) in joints.iter().enumerate() {
        for jb in &joints[i + 1..] {
            let (ma, mb) = (&m[usize::from(*ja)], &m[usize::from(*jb)]);
            let d: [[f64; 3]; 3] = core::array::from_fn(|r| {
                core::array::from_fn(|c| f64::from(ma.m[r][c] - mb.m[r][c]))
            });
            let e: [f64; 3] = core::array::from_fn(|r| f64::from(ma.m[r][3] - mb.m[r][3]));
            for r in 0..3 {
                for c in 0..3 {
                    a[r][c] += (0..3).map(|k| d[k][r] * d[k][c]).sum::<f64>();
                }
                b[r] -= (0..3).map(|k| d[k][r] * e[k]).sum::<f64>();
            }
        }
    }
    let lambda = 1e-6 * (a[0][0] + a[1][1] + a[2][2]) + 1e-12;
    let p = prior.cast::<f64>().to_array();
    for r in 0..3 {
        a[r][r] += lambda;
        b[r] += lambda * p[r];
    }
    match Mat3::from_rows(a).inverse() {
        Some(inv) => inv.mul_vec(Vec3::from_array(b)).cast(),
        None => prior,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use chasles::Quat;

    #[test]
    fn clusters_group_equal_joint_sets() {
        let sets: [&[u16]; 5] = [&[3, 1], &[1, 3], &[2], &[1, 3, 3], &[0, 2]];
        let c = Clusters::new(sets.len(), |v| sets[v].iter().copied());
        assert_eq!(c.len(), 3);
        assert_eq!(c.of_vertex(), &[0, 0, 1, 0, 2]);
        assert_eq!(c.joints(0), &[1, 3]);
        assert_eq!(c.joints(2), &[0, 2]);
    }

    #[test]
    fn the_centre_is_the_common_fixed_point() {
        // Joints rotating about different axes through the point x (and then all moved by
        // one offset): x is the point they all map to the same place.
        let x = Vec3::new(0.3f32, -1.2, 2.0);
        let q = [
            Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.7).unwrap(),
            Quat::from_axis_angle(Vec3::new(0.0, 1.0, 1.0), -1.1).unwrap(),
            Quat::from_axis_angle(Vec3::new(1.0, -2.0, 0.5), 0.4).unwrap(),
        ];
        let d = q.map(|q| {
            DualQuat::from_rotation_translation(q, x - q.rotate(x) + Vec3::new(0.5, 0.0, 0.1))
        });
        let bind = [
            Vec3::zero(),
            Vec3::new(5.0, 5.0, 5.0),
            Vec3::new(1.0, 0.0, 4.0),
        ];
        // Three joints: x, and only x.
        let r = Clusters::new(1, |_| [0u16, 1, 2]).centres(&d, &bind)[0];
        assert!((r - x).norm() < 1e-4, "{r:?}");
        // Two joints agree on the whole line through x along the axis u of their relative
        // rotation; the Tikhonov term picks its point nearest the prior (the mean of the
        // bind origins).
        let two = Clusters::new(1, |_| [0u16, 1]);
        let r = two.centres(&d, &bind)[0];
        let u = (q[1].conjugate() * q[0]).vector().normalize().unwrap();
        let prior = Vec3::new(2.5, 2.5, 2.5);
        let want = x + u * (prior - x).dot(u);
        assert!((r - want).norm() < 1e-3, "{r:?} vs {want:?}");
        // Equal rotations (rank 0): the prior itself.
        let r = two.centres(&[d[0], d[0], d[0]], &bind)[0];
        assert!((r - prior).norm() < 1e-4, "{r:?}");
        // One joint: the prior, its own origin.
        let one = Clusters::new(1, |_| [2u16]);
        assert!((one.centres(&d, &bind)[0] - bind[2]).norm() < 1e-6);
    }

    #[test]
    fn joint_centres_invert_the_bind_matrices() {
        let origin = Vec3::new(1.0f32, 2.0, -3.0);
        let q = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 0.4).unwrap();
        let bind = DualQuat::from_rotation_translation(q, origin).to_matrix4();
        let ib = chasles::blend::log::inverse_rigid(&bind);
        let c = joint_centres(&[ib, Mat4::from_rows([[0.0; 4]; 4])]);
        assert!((c[0] - origin).norm() < 1e-5, "{:?}", c[0]);
        assert_eq!(c[1], Vec3::zero(), "a singular matrix gives the origin");
    }
}
