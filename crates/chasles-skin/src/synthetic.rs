//! Synthetic rigs for benchmarks: n vertices with random positions and normals, 4 (or K)
//! random distinct joints per vertex with random convex weights, and random rigid joint
//! transforms within 60° of the identity (as in skinning; [`joints`]) or with rotations
//! uniform over all of them ([`uniform_joints`]: far apart, half their quaternions with a
//! negative scalar, the worst case for DQS's antipodality signs and DIB's iteration).
//! Deterministic for a seed.

use crate::fast::{FastRig, Vertex};
use crate::pose::JointTransforms;
use chasles::{DualQuat, Quat, Vec3};

/// A tiny deterministic generator (SplitMix64) — benchmarks need speed and repeatability,
/// not statistical quality.
struct Mix(u64);
impl Mix {
    fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// A fast-path rig of `n` vertices and `joints` joints (4 influences per vertex).
pub fn rig(n: usize, joints: usize, seed: u64) -> FastRig<4> {
    rig_with(n, joints, seed)
}

/// A fast-path rig of `n` vertices and `joints` (at least K) joints with K influences per
/// vertex (random convex weights, the first the heaviest on average); for K = 4 the same
/// as [`rig`].
pub fn rig_with<const K: usize>(n: usize, joints: usize, seed: u64) -> FastRig<K> {
    let mut r = Mix(seed);
    let vertices = (0..n)
        .map(|_| {
            let p = [
                r.next() * 2.0 - 1.0,
                r.next() * 2.0 - 1.0,
                r.next() * 2.0 - 1.0,
            ];
            let nn = Vec3::new(r.next() - 0.5, r.next() - 0.5, r.next() - 0.5)
                .normalize()
                .unwrap_or(Vec3::new(0.0, 0.0, 1.0));
            let mut j = [0u16; K];
            for k in 0..K {
                loop {
                    let c = ((r.next() * joints as f32) as usize).min(joints - 1) as u16;
                    if !j[..k].contains(&c) {
                        j[k] = c;
                        break;
                    }
                }
            }
            let mut w: [f32; K] = core::array::from_fn(|k| match k {
                0 => r.next() + 0.1,
                1..=3 => r.next() * [0.5, 0.3, 0.1][k - 1],
                _ => r.next() * 0.05 + 1e-3,
            });
            let s: f32 = w.iter().sum();
            w.iter_mut().for_each(|x| *x /= s);
            Vertex {
                p,
                n: nn.to_array(),
                j,
                w,
            }
        })
        .collect();
    // Bind origins in and around the mesh's cube.
    let centres = (0..joints)
        .map(|_| {
            Vec3::new(
                r.next() * 3.0 - 1.5,
                r.next() * 3.0 - 1.5,
                r.next() * 3.0 - 1.5,
            )
        })
        .collect();
    FastRig::from_vertices(vertices, centres)
        .unwrap_or_else(|_| unreachable!("indices are drawn below `joints`"))
}

/// `rig` with the influences in the slots that `keep(i, k)` picks for vertex `i` (slot 0
/// alone where it picks none), their weights scaled to sum to 1 and the others' made 0, in
/// place: how a method's cost or result goes with the count (and the slots) of a vertex's
/// influences, for tests and examples.
pub fn with_influences<const K: usize>(
    rig: &FastRig<K>,
    keep: impl Fn(usize, usize) -> bool,
) -> FastRig<K> {
    let vertices = rig
        .vertices()
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let mut v = *v;
            let w: [f32; K] = core::array::from_fn(|k| if keep(i, k) { v.w[k] } else { 0.0 });
            let s: f32 = w.iter().sum();
            v.w = if s > 0.0 {
                w.map(|x| x / s)
            } else {
                core::array::from_fn(|k| if k == 0 { 1.0 } else { 0.0 })
            };
            v
        })
        .collect();
    FastRig::from_vertices(vertices, rig.centres().to_vec())
        .unwrap_or_else(|_| unreachable!("the joints are the rig's own"))
}

/// Random rigid joint transforms within 60° of the identity.
pub fn joints(joints: usize, seed: u64) -> JointTransforms {
    posed(joints, Mix(seed ^ 0xABCD), |r| {
        let axis = Vec3::new(r.next() - 0.5, r.next() - 0.5, r.next() - 0.5);
        Quat::from_axis_angle(axis, r.next() * 1.0).unwrap_or(Quat::identity())
    })
}

/// `joints` rigid transforms, each a rotation drawn by `rotation` and then a translation in
/// the unit cube, from the generator `r`.
fn posed(joints: usize, mut r: Mix, rotation: impl Fn(&mut Mix) -> Quat<f32>) -> JointTransforms {
    let dual_quats: Vec<DualQuat<f32>> = (0..joints)
        .map(|_| {
            let q = rotation(&mut r);
            DualQuat::from_rotation_translation(q, Vec3::new(r.next(), r.next(), r.next()))
        })
        .collect();
    JointTransforms {
        matrices: dual_quats.iter().map(|d| d.to_matrix4()).collect(),
        dual_quats,
        non_rigidity: 0.0,
    }
}

/// Random rigid joint transforms whose rotations are uniform over all rotations (Shoemake's
/// method: `[√(1−u₁) sin 2πu₂, √(1−u₁) cos 2πu₂, √u₁ sin 2πu₃, √u₁ cos 2πu₃]` for three
/// uniform numbers, the Haar measure on the unit quaternions; the scalar part's sign is
/// either), translations in the unit cube as [`joints`]'.
pub fn uniform_joints(joints: usize, seed: u64) -> JointTransforms {
    use std::f32::consts::TAU;
    posed(joints, Mix(seed ^ 0x5EED_0F50), |r| {
        let (u1, u2, u3) = (r.next(), r.next(), r.next());
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        let q = Quat::new(
            b * (TAU * u3).cos(),
            a * (TAU * u2).sin(),
            a * (TAU * u2).cos(),
            b * (TAU * u3).sin(),
        );
        q.normalize().unwrap_or(Quat::identity())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The uniform joints are unit, rigid and spread over every angle (the Haar measure
    /// turns 0.61 of the rotations by more than 2π/3), half with a negative scalar part,
    /// the same for a seed; [`joints`] stay within 60°.
    #[test]
    fn uniform_joints_cover_every_angle_and_near_ones_stay_near() {
        let u = uniform_joints(2000, 3);
        let angle = |d: &DualQuat<f32>| 2.0 * d.real.w.abs().min(1.0).acos();
        let far = u
            .dual_quats
            .iter()
            .filter(|d| angle(d) > 2.0 * std::f32::consts::FRAC_PI_3)
            .count();
        let negative = u.dual_quats.iter().filter(|d| d.real.w < 0.0).count();
        assert!(u
            .dual_quats
            .iter()
            .all(|d| (d.real.norm() - 1.0).abs() < 1e-5));
        // P(angle > 2π/3) = 1 − (2π/3 − sin(2π/3))/π = 0.609.
        assert!((1100..1330).contains(&far), "{far} of 2000 beyond 120°");
        assert!(
            (900..1100).contains(&negative),
            "{negative} of 2000 with w < 0"
        );
        assert_eq!(u.dual_quats, uniform_joints(2000, 3).dual_quats);
        assert_ne!(u.dual_quats, uniform_joints(2000, 4).dual_quats);
        let n = joints(2000, 3);
        assert!(n.dual_quats.iter().all(|d| angle(d) <= 1.0 + 1e-6));
    }
}
