//! Posing a rig: node local transforms → world transforms → the skinning transform of
//! every joint, `C_j = World(joint_j) · InverseBind_j` (glTF 2.0 §3.7.3; Kavan et al. 2006
//! §6: "the list L of joint displacements from the reference to the animated skeleton").

use crate::error::{same_count, Result, SkinError};
use crate::rig::{Node, Rig, Trs};
use chasles::{DualQuat, Mat4, Quat};

/// A pose: the local transform of every node.
#[derive(Debug, Clone, PartialEq)]
pub struct Pose {
    /// One per node of the rig.
    pub local: Vec<Trs>,
}

impl Pose {
    /// The rest pose (every node at its rest transform).
    pub fn rest(rig: &Rig) -> Self {
        Pose {
            local: rig.nodes.iter().map(|n| n.rest).collect(),
        }
    }
    /// Clip `animation` (by index) at time `t`.
    pub fn animated(rig: &Rig, animation: usize, t: f32) -> Result<Self> {
        let Some(a) = rig.animations.get(animation) else {
            return Err(SkinError::NoAnimation {
                rig: rig.name.clone(),
                clip: animation,
                count: rig.animations.len(),
            });
        };
        if !t.is_finite() {
            return Err(SkinError::NotFinite {
                rig: rig.name.clone(),
                what: format!("the time {t} in clip {animation}"),
            });
        }
        Ok(Pose {
            local: a.sample(&Pose::rest(rig).local, t),
        })
    }
}

/// The skinning transforms of a pose, as matrices and as unit dual quaternions.
#[derive(Debug, Clone, PartialEq)]
pub struct JointTransforms {
    /// `C_j` as 4×4 matrices.
    pub matrices: Vec<Mat4<f32>>,
    /// `C_j` as unit dual quaternions (of the rotation part of C_j's 3×3 block and its
    /// translation; see [`joint_transforms`]).
    pub dual_quats: Vec<DualQuat<f32>>,
    /// The largest `‖AᵀA − I‖` of the 3×3 blocks: 0 for rigid joints.
    pub non_rigidity: f32,
}

impl JointTransforms {
    /// Every joint at its bind pose (`C_j = I`): skinning returns the bind mesh.
    pub fn identity(joints: usize) -> Self {
        JointTransforms {
            matrices: vec![Mat4::identity(); joints],
            dual_quats: vec![DualQuat::identity(); joints],
            non_rigidity: 0.0,
        }
    }
}

/// World transforms of all nodes (parents before children is not assumed).
pub fn world(rig: &Rig, pose: &Pose) -> Result<Vec<Mat4<f32>>> {
    let (nodes, given) = (rig.nodes.len(), pose.local.len());
    same_count(&rig.name, "node transforms in the pose", nodes, given)?;
    Ok(world_of(&rig.nodes, &pose.local))
}

/// World transforms of `nodes` with these local transforms (one per node). A parent out
/// of range, or a chain longer than the node count (a cycle), ends the chain there;
/// [`Rig::new`] refuses both.
pub(crate) fn world_of(nodes: &[Node], local: &[Trs]) -> Vec<Mat4<f32>> {
    fn get(
        i: usize,
        nodes: &[Node],
        local: &[Trs],
        done: &mut [Option<Mat4<f32>>],
        depth: usize,
    ) -> Mat4<f32> {
        if let Some(m) = done[i] {
            return m;
        }
        let l = local[i].matrix();
        let m = match nodes[i].parent {
            Some(p) if p < local.len() && depth < nodes.len() => {
                get(p, nodes, local, done, depth + 1) * l
            }
            _ => l,
        };
        done[i] = Some(m);
        m
    }
    let mut done: Vec<Option<Mat4<f32>>> = vec![None; nodes.len()];
    (0..nodes.len().min(local.len()))
        .map(|i| get(i, nodes, local, &mut done, 0))
        .collect()
}

/// `C_j = World(joint_j) · InverseBind_j` for every joint: the matrices alone (what LBS
/// reads; [`crate::fast::Palette::update`] makes any method's palette from them).
pub fn skinning_matrices(rig: &Rig, pose: &Pose) -> Result<Vec<Mat4<f32>>> {
    let w = world(rig, pose)?;
    Ok(rig
        .joints
        .iter()
        .zip(&rig.inverse_bind)
        .map(|(n, ib)| w[*n] * *ib)
        .collect())
}

/// The unit dual quaternion of a skinning matrix — its 3×3 block's nearest rotation
/// (Shepperd's method on the block, normalized) and its translation — and how far the block
/// was from a rotation (`max |AᵀA − I|`).
pub fn rigid_of(m: &Mat4<f32>) -> (DualQuat<f32>, f32) {
    let a = m.linear_part();
    let off = (a.transpose() * a).max_abs_diff(&chasles::Mat3::identity());
    (
        DualQuat::from_rotation_translation(
            Quat::from_rotation_matrix_unchecked(&a),
            m.translation(),
        ),
        off,
    )
}

/// `C_j = World(joint_j) · InverseBind_j` for every joint. For the dual quaternions, a
/// 3×3 block that is not a rotation (scaled joints) contributes its nearest rotation
/// (Shepperd's method on the block, normalized); `non_rigidity` says how far off it was.
pub fn joint_transforms(rig: &Rig, pose: &Pose) -> Result<JointTransforms> {
    let matrices = skinning_matrices(rig, pose)?;
    let mut non_rigidity = 0.0f32;
    let dual_quats = matrices
        .iter()
        .map(|m| {
            let (d, off) = rigid_of(m);
            non_rigidity = non_rigidity.max(off);
            d
        })
        .collect();
    Ok(JointTransforms {
        matrices,
        dual_quats,
        non_rigidity,
    })
}
