//! Conversions between rotation representations (Dam et al. 1998, App. B):
//! [`euler`] (all 12 axis sequences, intrinsic and extrinsic; B.1, B.2, B.5),
//! [`matrix`] (quaternion ↔ 3×3/4×4 matrix; B.3, and Shepperd's method in place of B.4),
//! [`axis_angle`] (axis–angle and rotation vectors; Proposition 21).
//! Rigid transformations ↔ dual quaternions (Kavan et al. 2006, eq. 1) are methods of
//! [`crate::DualQuat`].

pub mod axis_angle;
pub mod euler;
pub mod matrix;
