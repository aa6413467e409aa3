//! # chasles-viz — seeing what each method does
//!
//! Dam et al. 1998, chapter 5: [`graph`] draws the angular velocity of a frame sequence
//! against the frame index with the key frames marked by asterisks (§5.2); [`sphere`]
//! plots a quaternion curve whose quaternions share one fixed coordinate on a shaded unit
//! sphere — first key larger, other keys medium, frames small — so that frames that leave
//! the unit sphere are visibly off its surface (§5.3, Figures 5.1–5.3).

#![warn(missing_docs)]

pub mod graph;
pub mod sphere;
