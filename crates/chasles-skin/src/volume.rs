//! Where linear blend skinning loses volume (Kavan et al. 2006, §1 and §6): at each vertex
//! LBS applies the weighted sum of its joints' matrices, whose 3×3 part has determinant
//! below 1 where the joints turn apart — the local volume kept. Rigid blends (DQS, DIB)
//! keep exactly 1, so the smallest determinant over a clip measures LBS's loss.

use crate::{joint_transforms, Pose, Result, Rig};
use chasles::Mat3;

/// The determinant of LBS's blended 3×3 at every vertex of `rig` in `pose`.
pub fn lbs_determinants(rig: &Rig, pose: &Pose) -> Result<Vec<f32>> {
    let jt = joint_transforms(rig, pose)?;
    Ok((0..rig.mesh.positions.len())
        .map(|v| {
            let mut a = Mat3::from_rows([[0.0f32; 3]; 3]);
            for (j, w) in rig.influences.of(v) {
                let m = jt.matrices[j].linear_part();
                for (row, mrow) in a.m.iter_mut().zip(m.m.iter()) {
                    for (e, x) in row.iter_mut().zip(mrow) {
                        *e += x * w;
                    }
                }
            }
            a.determinant()
        })
        .collect())
}

/// The vertex where LBS keeps the least volume in `pose`, and that determinant
/// (`(0, +∞)` for a mesh without vertices).
pub fn lbs_worst_vertex(rig: &Rig, pose: &Pose) -> Result<(usize, f32)> {
    Ok(lbs_determinants(rig, pose)?
        .into_iter()
        .enumerate()
        .fold((0, f32::INFINITY), |a, b| if b.1 < a.1 { b } else { a }))
}

/// The smallest determinant of LBS's blended 3×3 over the vertices of `rig` in `pose`.
pub fn lbs_min_determinant(rig: &Rig, pose: &Pose) -> Result<f32> {
    Ok(lbs_worst_vertex(rig, pose)?.1)
}

/// [`lbs_min_determinant`] at `samples + 1` evenly spaced times of clip `clip`, as
/// `(time, smallest determinant)`.
pub fn lbs_volume_over_clip(rig: &Rig, clip: usize, samples: usize) -> Result<Vec<(f32, f32)>> {
    let duration = rig
        .animations
        .get(clip)
        .map(|a| a.duration())
        .ok_or_else(|| crate::SkinError::NoAnimation {
            rig: rig.name.clone(),
            clip,
            count: rig.animations.len(),
        })?;
    let n = samples.max(1);
    (0..=n)
        .map(|k| {
            let t = duration * k as f32 / n as f32;
            Ok((t, lbs_min_determinant(rig, &Pose::animated(rig, clip, t)?)?))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cylinder::{self, Motion};

    #[test]
    fn twist_keeps_cos_squared_of_half_the_angle() {
        // Halfway across the joint the weights are ½ and ½: det((I + Rx(θ))/2) = cos²(θ/2).
        let rig = cylinder::twisted_cylinder();
        for deg in [0.0f32, 60.0, 90.0, 150.0, 180.0] {
            let th = deg.to_radians();
            let d = lbs_min_determinant(&rig, &cylinder::pose(&rig, Motion::Twist, th)).unwrap();
            let want = (th / 2.0).cos().powi(2);
            assert!((d - want).abs() < 1e-5, "{deg}°: {d} vs {want}");
        }
        assert!(
            lbs_volume_over_clip(&rig, 0, 4).is_err(),
            "the cylinder has no clips"
        );
    }
}
