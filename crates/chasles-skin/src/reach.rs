//! The range of numbers every skinning path keeps finite, and the checks that hold inputs
//! inside it.
//!
//! The reference ([`crate::skin_joints`]), the fast path ([`crate::fast`]) and the GPU
//! shaders compute the same formulas (Kavan et al. 2006, §6: LBS's `Σ wᵢCᵢ` with normals by
//! the cofactor of its 3×3 block; DQS's and DIB's normalized dual quaternions) in different
//! orders. Near the edge of f32 (about 3.4·10³⁸) one order overflows where another does not,
//! so without a common bound one path would refuse a pose the others skin. The bound:
//!
//! - every entry of a joint matrix's 3×3 block at most [`MAX_LINEAR`] = 2³⁰ (a joint scaled
//!   by 10⁹) in magnitude, every translation component and every dual-quaternion component
//!   at most [`MAX_REACH`] = 2⁶⁰ (1.2·10¹⁸), and every bind position at most [`MAX_REACH`].
//!
//! Inside it nothing overflows in any order: a skinned coordinate is at most
//! 3·2³⁰·2⁶⁰ + 2⁶⁰ < 2⁹³; a cofactor entry at most 2·2⁶⁰, a normal component before
//! normalization at most 3·2⁶¹, and the sum of their squares at most 27·2¹²² < 2¹²⁷ (unit
//! bind normals and convex weights, which the rig's checks give); DIB's update, whose dual
//! part is of the order of the joints' translations, squares to well under 2¹²⁸ (that is
//! why the reach is 2⁶⁰ and not 2⁶⁴: the f32 lanes square it). A pose
//! or a rig outside it is [`SkinError::OutOfReach`] (a NaN or an infinity
//! [`SkinError::NotFinite`]), named, on every path alike.

use crate::error::{Result, SkinError};
use chasles::{DualQuat, Mat4, Vec3};

/// The largest magnitude of an entry of a joint matrix's 3×3 block: 2³⁰.
pub const MAX_LINEAR: f32 = 1_073_741_824.0;

/// The largest magnitude of a joint translation, a dual-quaternion component or a bind
/// position's coordinate: 2⁶⁰.
pub const MAX_REACH: f32 = 1_152_921_504_606_846_976.0;

/// The first entry of `values` not within `±limit` (NaN included), with its index.
fn first_past(values: impl IntoIterator<Item = f32>, limit: f32) -> Option<(usize, f32)> {
    values
        .into_iter()
        .enumerate()
        .find(|(_, x)| x.is_nan() || x.abs() > limit)
}

/// The error for `value` of `what` past `limit`: [`SkinError::NotFinite`] for NaN and
/// infinities, else [`SkinError::OutOfReach`].
fn past(rig: &str, what: String, value: f32, limit: f32) -> SkinError {
    let rig = rig.to_string();
    if value.is_finite() {
        SkinError::OutOfReach {
            rig,
            what,
            value,
            limit,
        }
    } else {
        SkinError::NotFinite {
            rig,
            what: format!("{what} ({value})"),
        }
    }
}

/// Checks joint matrices (and, when given, their dual quaternions) of `rig` against the
/// bound: finite, 3×3 entries within [`MAX_LINEAR`], translations and dual-quaternion
/// components within [`MAX_REACH`]. (The last row, which skinning never reads, is not
/// checked.)
pub fn check_joints(
    rig: &str,
    matrices: &[Mat4<f32>],
    dual_quats: Option<&[DualQuat<f32>]>,
) -> Result<()> {
    for (j, m) in matrices.iter().enumerate() {
        let linear = (0..3).flat_map(|r| (0..3).map(move |c| m.m[r][c]));
        if let Some((k, x)) = first_past(linear, MAX_LINEAR) {
            let what = format!("joint {j}'s matrix entry ({}, {})", k / 3, k % 3);
            return Err(past(rig, what, x, MAX_LINEAR));
        }
        let rest = [m.m[0][3], m.m[1][3], m.m[2][3]];
        if let Some((k, x)) = first_past(rest, MAX_REACH) {
            return Err(past(
                rig,
                format!("joint {j}'s translation[{k}]"),
                x,
                MAX_REACH,
            ));
        }
    }
    for (j, d) in dual_quats.unwrap_or(&[]).iter().enumerate() {
        if let Some((k, x)) = first_past(d.to_array(), MAX_REACH) {
            let what = format!("joint {j}'s dual quaternion[{k}]");
            return Err(past(rig, what, x, MAX_REACH));
        }
    }
    Ok(())
}

/// Checks a fast-path palette's floats as laid out (`per` floats a joint): those at the
/// offsets in `linear` (a 3×4 matrix's 3×3 block) within [`MAX_LINEAR`], the others within
/// [`MAX_REACH`]; `what` names the joint data (`LBS joint`).
pub fn check_laid_out(
    rig: &str,
    what: &str,
    floats: &[f32],
    per: usize,
    linear: &[usize],
) -> Result<()> {
    for (i, &x) in floats.iter().enumerate() {
        let (j, k) = (i / per.max(1), i % per.max(1));
        let limit = if linear.contains(&k) {
            MAX_LINEAR
        } else {
            MAX_REACH
        };
        if x.is_nan() || x.abs() > limit {
            return Err(past(rig, format!("{what} {j}'s float {k}"), x, limit));
        }
    }
    Ok(())
}

/// Checks bind positions against [`MAX_REACH`].
pub fn check_positions(rig: &str, positions: &[Vec3<f32>]) -> Result<()> {
    for (i, p) in positions.iter().enumerate() {
        if let Some((k, x)) = first_past(p.to_array(), MAX_REACH) {
            let what = format!("the position of vertex {i} (coordinate {k})");
            return Err(past(rig, what, x, MAX_REACH));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bound_is_inclusive_and_names_what_passes_it() {
        let mut m = Mat4::<f32>::identity();
        m.m[1][2] = MAX_LINEAR;
        m.m[2][3] = -MAX_REACH;
        assert!(check_joints("r", &[m], None).is_ok());
        let mut big = m;
        big.m[1][2] = MAX_LINEAR * 2.0;
        let e = check_joints("r", &[Mat4::identity(), big], None).unwrap_err();
        assert!(matches!(e, SkinError::OutOfReach { .. }));
        assert_eq!(
            e.to_string(),
            "r: joint 1's matrix entry (1, 2) is 2.1474836e9, past ±1.0737418e9, the range in which every skinning path stays finite"
        );
        let mut far = m;
        far.m[0][3] = 1e30;
        let e = check_joints("r", &[far], None).unwrap_err().to_string();
        assert!(e.contains("joint 0's translation[0] is 1e30"), "{e}");
        let mut nan = m;
        nan.m[0][0] = f32::NAN;
        let e = check_joints("r", &[nan], None).unwrap_err();
        assert!(matches!(e, SkinError::NotFinite { .. }), "{e}");
        let mut d = DualQuat::<f32>::identity();
        d.dual.x = f32::INFINITY;
        let e = check_joints("r", &[m], Some(&[d])).unwrap_err().to_string();
        assert!(
            e.contains("joint 0's dual quaternion[5] (inf) is not finite"),
            "{e}"
        );
    }

    #[test]
    fn bind_positions_past_the_reach_are_named() {
        let ok = [Vec3::new(0.0, MAX_REACH, -MAX_REACH)];
        assert!(check_positions("r", &ok).is_ok());
        let far = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.0, -1e20)];
        let e = check_positions("r", &far).unwrap_err().to_string();
        assert!(
            e.contains("the position of vertex 1 (coordinate 2) is -1e20"),
            "{e}"
        );
    }
}
