//! # chasles-viz — seeing what each method does
//!
//! Dam et al. 1998, chapter 5, and the pictures of Kavan et al. 2006: [`graph`] draws the
//! angular velocity of a frame sequence against the frame index with the key frames marked
//! by asterisks (§5.2); [`sphere`] plots a quaternion curve whose quaternions share one
//! fixed coordinate on a shaded unit sphere — first key larger, other keys medium, frames
//! small — so that frames that leave the unit sphere are visibly off its surface (§5.3,
//! Figures 5.1–5.3); [`letter`] turns an extruded R by every frame and [`raster`] draws it
//! into an animated GIF, the direct visualisation of §5.1; [`panels`] draws one mesh posed
//! by several skinning methods side by side (Kavan et al. §6, Figure 1); [`plot`] draws the
//! measured claims as line plots (Kavan et al. §4, Figure 7), [`grid`] Table 1's measured
//! deviations and [`bars`] DIB's iteration counts. [`image`] holds the pictures
//! and writes PNG and GIF; [`font`] labels them.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod bars;
pub mod font;
pub mod graph;
pub mod grid;
pub mod image;
pub mod letter;
pub mod panels;
pub mod plot;
pub mod raster;
pub mod rigid;
pub mod sphere;
mod svg;

pub use image::{gif, EncodeError, Image};
