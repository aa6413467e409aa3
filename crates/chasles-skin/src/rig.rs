//! The rig model: a mesh, a node hierarchy with a skin (joints and inverse bind matrices),
//! per-vertex influences, and animations (Kavan et al. 2006, §6: "a triangular mesh, a
//! list L of rigid transformations, and weights for every vertex").

use crate::animation::Animation;
use crate::error::{same_count, Result, SkinError};
use chasles::{Mat4, Quat, Vec3};

/// A node's local transform: translation, rotation, scale (applied as T · R · S).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trs {
    /// Translation.
    pub translation: Vec3<f32>,
    /// Rotation, unit quaternion `[w, x, y, z]`.
    pub rotation: Quat<f32>,
    /// Scale per axis.
    pub scale: Vec3<f32>,
}

impl Default for Trs {
    fn default() -> Self {
        Trs {
            translation: Vec3::zero(),
            rotation: Quat::identity(),
            scale: Vec3::new(1.0, 1.0, 1.0),
        }
    }
}

impl Trs {
    /// The matrix `T · R · S`.
    pub fn matrix(&self) -> Mat4<f32> {
        let r = self.rotation.to_rotation_matrix();
        let s = self.scale.to_array();
        let m = chasles::Mat3::from_rows(core::array::from_fn(|i| {
            core::array::from_fn(|j| r.m[i][j] * s[j])
        }));
        Mat4::from_rotation_translation(&m, self.translation)
    }
}

/// A node of the scene hierarchy.
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    /// Its name ("" when unnamed).
    pub name: String,
    /// Its parent, if any.
    pub parent: Option<usize>,
    /// Rest (bind-scene) local transform.
    pub rest: Trs,
}

/// The triangle mesh in its bind pose.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3<f32>>,
    /// Vertex normals (unit; computed from the triangles when the file has none).
    pub normals: Vec<Vec3<f32>>,
    /// Triangles as vertex indices.
    pub triangles: Vec<[u32; 3]>,
}

/// Per-vertex influences, any number per vertex, in compressed rows: the influences of
/// vertex v are `joints[start[v]..start[v + 1]]` with `weights[…]`. Weights are
/// positive and sum to 1 per vertex (normalized on construction), heaviest first (ties in
/// the order given): the first influence is the pivot of the antipodality fix, and the
/// reference and fast paths sum in the same order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Influences {
    /// Row starts, one more than the vertex count.
    pub start: Vec<u32>,
    /// Joint indices (into the skin's joints).
    pub joints: Vec<u16>,
    /// Weights.
    pub weights: Vec<f32>,
}

/// A weight of a vertex's influence on `joint`: finite and not negative. The one check of a
/// weight, for [`Influences`] and for the fast path's layouts built by hand.
pub(crate) fn check_weight(vertex: usize, joint: usize, w: f32) -> Result<()> {
    if w.is_finite() && w >= 0.0 {
        return Ok(());
    }
    Err(SkinError::BadWeights {
        vertex,
        reason: format!("weight {w} for joint {joint} is negative or not finite"),
    })
}

/// One vertex's influences checked — every weight finite and not negative, every joint below
/// `joints` (with `every_joint` false, only those of a positive weight) — and their sum,
/// which must be above 0.
fn checked_sum(
    vertex: usize,
    pairs: impl Iterator<Item = (usize, f32)>,
    joints: usize,
    every_joint: bool,
) -> Result<f64> {
    let mut sum = 0.0f64;
    for (joint, w) in pairs {
        check_weight(vertex, joint, w)?;
        if (every_joint || w > 0.0) && joint >= joints {
            return Err(SkinError::JointOutOfRange {
                vertex,
                joint,
                joints,
            });
        }
        sum += f64::from(w);
    }
    if sum <= 0.0 {
        return Err(SkinError::BadWeights {
            vertex,
            reason: "the weights sum to zero (the vertex is bound to no joint)".into(),
        });
    }
    Ok(sum)
}

/// Sorts one vertex's influences by weight, heaviest first, ties keeping their order (an
/// insertion sort: a vertex has a handful).
fn sort_heaviest_first(joints: &mut [u16], weights: &mut [f32]) {
    for i in 1..weights.len() {
        let mut k = i;
        while k > 0 && weights[k - 1] < weights[k] {
            weights.swap(k - 1, k);
            joints.swap(k - 1, k);
            k -= 1;
        }
    }
}

impl Influences {
    /// Builds influences from per-vertex lists, dropping zero weights, sorting each
    /// vertex's by weight (heaviest first), checking joint
    /// indices and weights, and normalizing each vertex's weights to sum to 1. Errors name
    /// the vertex: a joint index out of range, a negative or non-finite weight, or weights
    /// that sum to zero.
    pub fn from_lists(lists: &[Vec<(usize, f32)>], joints: usize) -> Result<Self> {
        Self::from_rows(lists.iter().map(|l| l.iter().copied()), joints)
    }
    /// [`Influences::from_lists`] for rows given as iterators (say a vertex's slots of
    /// fixed-width joint and weight arrays, as glTF and numpy hold them), so that no list is
    /// made per vertex: the same checks, errors and numbers.
    pub fn from_rows<R>(rows: impl Iterator<Item = R>, joints: usize) -> Result<Self>
    where
        R: Iterator<Item = (usize, f32)> + Clone,
    {
        let mut out = Influences {
            start: Vec::with_capacity(rows.size_hint().0 + 1),
            joints: Vec::new(),
            weights: Vec::new(),
        };
        out.start.push(0);
        for (vertex, list) in rows.enumerate() {
            // Joints of weight 0 are dropped below, so only the others must exist.
            let sum = checked_sum(vertex, list.clone(), joints, false)?;
            let first = out.joints.len();
            for (joint, w) in list {
                if w > 0.0 {
                    out.joints.push(joint as u16);
                    out.weights.push((f64::from(w) / sum) as f32);
                }
            }
            sort_heaviest_first(&mut out.joints[first..], &mut out.weights[first..]);
            out.start.push(out.joints.len() as u32);
        }
        if joints > usize::from(u16::MAX) {
            return Err(SkinError::TooManyJoints { joints });
        }
        Ok(out)
    }
    /// Checks rows built by hand (the fields are public): starts from 0, never decreasing,
    /// ending at the number of joints and weights; every joint below `joints`; every weight
    /// finite and not negative, each vertex's summing above 0. `rig` names it in errors.
    pub fn check(&self, joints: usize, rig: &str) -> Result<()> {
        let total = self.joints.len();
        let rows_ok = self.start.first() == Some(&0)
            && self.start.windows(2).all(|w| w[0] <= w[1])
            && self.start.last().map(|&e| e as usize) == Some(total)
            && self.weights.len() == total;
        if !rows_ok {
            return Err(SkinError::Count {
                rig: rig.to_string(),
                what: "influences in the rows (start must run from 0 up to the joints and weights held)",
                expected: self.start.last().map_or(0, |&e| e as usize),
                got: total.min(self.weights.len()),
            });
        }
        for v in 0..self.vertices() {
            // Every stored joint is read by the kernels, whatever its weight.
            checked_sum(v, self.of(v), joints, true)?;
        }
        Ok(())
    }

    /// Number of vertices.
    pub fn vertices(&self) -> usize {
        self.start.len().saturating_sub(1)
    }
    /// The (joint, weight) pairs of vertex v.
    pub fn of(&self, v: usize) -> impl Iterator<Item = (usize, f32)> + '_ {
        let (a, b) = (self.start[v] as usize, self.start[v + 1] as usize);
        self.joints[a..b]
            .iter()
            .zip(&self.weights[a..b])
            .map(|(j, w)| (usize::from(*j), *w))
    }
    /// The largest number of influences of any vertex.
    pub fn max_per_vertex(&self) -> usize {
        self.start
            .windows(2)
            .map(|w| (w[1] - w[0]) as usize)
            .max()
            .unwrap_or(0)
    }
}

/// A rigged mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct Rig {
    /// A name for messages and picture titles: the file name (never its folder), or what
    /// built it.
    pub name: String,
    /// The bind-pose mesh.
    pub mesh: Mesh,
    /// All nodes of the hierarchy (joints and the nodes between them).
    pub nodes: Vec<Node>,
    /// The skin's joints, as node indices.
    pub joints: Vec<usize>,
    /// Inverse bind matrices, one per joint.
    pub inverse_bind: Vec<Mat4<f32>>,
    /// The influences of every vertex.
    pub influences: Influences,
    /// Animations of the nodes.
    pub animations: Vec<Animation>,
}

impl Rig {
    /// A rig from its parts, checked once (see [`Rig::validate`]): every loader builds its
    /// rig here, so a `Rig` from this crate is always consistent.
    pub fn new(
        name: String,
        mesh: Mesh,
        nodes: Vec<Node>,
        joints: Vec<usize>,
        inverse_bind: Vec<Mat4<f32>>,
        influences: Influences,
        animations: Vec<Animation>,
    ) -> Result<Rig> {
        let rig = Rig {
            name,
            mesh,
            nodes,
            joints,
            inverse_bind,
            influences,
            animations,
        };
        rig.validate()?;
        Ok(rig)
    }

    /// The index of the clip named `name` — or, when no clip has that name, of index
    /// `name` (`"0"`). Errors: [`SkinError::NoClip`], listing the clips there are.
    pub fn clip_index(&self, name: &str) -> Result<usize> {
        if let Some(i) = self.animations.iter().position(|a| a.name == name) {
            return Ok(i);
        }
        match name.parse::<usize>() {
            Ok(i) if i < self.animations.len() => Ok(i),
            _ => Err(SkinError::NoClip {
                rig: self.name.clone(),
                clip: name.to_string(),
                available: self.clip_list(),
            }),
        }
    }

    /// The clips' names, a clip without a name by its index as text.
    pub fn clip_names(&self) -> Vec<String> {
        self.animations
            .iter()
            .enumerate()
            .map(|(i, a)| {
                if a.name.is_empty() {
                    i.to_string()
                } else {
                    a.name.clone()
                }
            })
            .collect()
    }

    /// The clips, for messages: `Walk (0), Run (1)` (a clip without a name by its index),
    /// or `none`.
    pub fn clip_list(&self) -> String {
        if self.animations.is_empty() {
            return "none".to_string();
        }
        self.clip_names()
            .into_iter()
            .zip(&self.animations)
            .enumerate()
            .map(|(i, (n, a))| {
                if a.name.is_empty() {
                    n
                } else {
                    format!("{n} ({i})")
                }
            })
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Checks the rig's consistency: counts, indices, finite numbers, an acyclic hierarchy,
    /// playable animation channels. [`Rig::new`] runs it; run it again after changing the
    /// public fields by hand.
    pub fn validate(&self) -> Result<()> {
        let rig = || self.name.clone();
        let n = self.mesh.positions.len();
        let count = |what, expected, got| same_count(&self.name, what, expected, got);
        count("influence lists", n, self.influences.vertices())?;
        self.influences.check(self.joints.len(), &self.name)?;
        count("normals", n, self.mesh.normals.len())?;
        count(
            "inverse bind matrices",
            self.joints.len(),
            self.inverse_bind.len(),
        )?;
        if let Some((i, v)) = self.mesh.triangles.iter().enumerate().find_map(|(i, t)| {
            t.iter()
                .find(|v| **v as usize >= n)
                .map(|v| (i, *v as usize))
        }) {
            return Err(SkinError::OutOfRange {
                rig: rig(),
                what: format!("triangle {i}'s vertex"),
                index: v,
                count: n,
            });
        }
        if let Some(i) = self.mesh.positions.iter().position(|p| !p.is_finite()) {
            return Err(SkinError::NotFinite {
                rig: rig(),
                what: format!("the position of vertex {i}"),
            });
        }
        crate::reach::check_positions(&rig(), &self.mesh.positions)?;
        if let Some(i) = self.mesh.normals.iter().position(|p| !p.is_finite()) {
            return Err(SkinError::NotFinite {
                rig: rig(),
                what: format!("the normal of vertex {i}"),
            });
        }
        for (j, node) in self.joints.iter().enumerate() {
            if *node >= self.nodes.len() {
                return Err(SkinError::OutOfRange {
                    rig: rig(),
                    what: format!("joint {j}'s node"),
                    index: *node,
                    count: self.nodes.len(),
                });
            }
        }
        for (i, node) in self.nodes.iter().enumerate() {
            let mut seen = 0;
            let mut p = node.parent;
            while let Some(k) = p {
                if k >= self.nodes.len() || seen > self.nodes.len() {
                    return Err(SkinError::Hierarchy {
                        rig: rig(),
                        node: i,
                    });
                }
                p = self.nodes[k].parent;
                seen += 1;
            }
        }
        for (a, anim) in self.animations.iter().enumerate() {
            for (c, ch) in anim.channels.iter().enumerate() {
                ch.validate(self.nodes.len())
                    .map_err(|problem| SkinError::Channel {
                        rig: rig(),
                        animation: a,
                        channel: c,
                        node: ch.node,
                        problem,
                    })?;
            }
        }
        Ok(())
    }
}

/// Unit normals of a triangle mesh, area-weighted; a vertex in no triangle gets +z.
/// Triangles naming vertices out of range are skipped (validation reports them).
pub fn compute_normals(positions: &[Vec3<f32>], triangles: &[[u32; 3]]) -> Vec<Vec3<f32>> {
    let mut n = vec![Vec3::zero(); positions.len()];
    for t in triangles
        .iter()
        .filter(|t| t.iter().all(|i| (*i as usize) < positions.len()))
    {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let f = (b - a).cross(c - a);
        for i in t {
            n[*i as usize] += f;
        }
    }
    n.into_iter()
        .map(|v| v.normalize().unwrap_or(Vec3::new(0.0, 0.0, 1.0)))
        .collect()
}
