//! # chasles — rotations and rigid motions
//!
//! The core crate: quaternion and dual-quaternion algebra and the conversions between
//! rotation representations, generic over `f32` and `f64` through the [`Real`] trait. No
//! I/O. It implements
//!
//! * Dam, Koch & Lillholm (1998), *Quaternions, Interpolation and Animation*: §3.3
//!   (quaternions: [`Quat`]), App. A (conventions) and App. B (conversions: [`convert`]);
//! * Kavan, Collins, Žára & O'Sullivan (2006), *Dual Quaternions for Rigid Transformation
//!   Blending*: §3 ([`Dual`], [`DualQuat`], eq. 1–2, [`screw`]) and Lemma 1;
//! * Kavan et al. §2–5 and Appendices A–B: blending of rigid transformations ([`blend`]:
//!   Lin, Dec, Log, iterative Log, QLB, ScLERP, DLB, DIB; their properties, the paper's
//!   Table 1, are measured by the `chasles-paper` crate);
//! * Dam et al. chapters 5–7: interpolation along key frames ([`interp`]: LinEuler, LinMat,
//!   Lerp, Slerp, Squad, Spring) and the measures that compare them ([`analysis`]).
//!
//! ## Conventions
//! * Quaternions are `[w, x, y, z]` (scalar first, as both papers write `[s, v]`) in every
//!   array; glam and nalgebra store `x, y, z, w` in memory — the `From` conversions behind
//!   the `glam`, `nalgebra` and `mint` features take care of that.
//! * Unit dual quaternion `q0 + ε qε` with `qε = ½ t q0`; as 8 numbers
//!   `[w, x, y, z, wε, xε, yε, zε]`.
//! * Right-handed coordinates, counter-clockwise positive rotations (Dam et al. App. A);
//!   matrices are row-major and act on column vectors.
//! * A unit quaternion `[cos θ, sin θ n]` rotates by `2θ`; `log` returns `[0, θ n]`.
//! * Functions that pick one of `q`/`−q` say so ("positive hemisphere", "principal value").
//!
//! ## Example
//! ```
//! use chasles::{DualQuat, EulerOrder, Quat, Vec3};
//!
//! // Dam et al.'s convention: about x by 0.1, then y by 0.2, then z by 0.3 (fixed axes).
//! let q = Quat::<f64>::from_euler(EulerOrder::DAM, [0.1, 0.2, 0.3]);
//! let back = q.to_euler(EulerOrder::DAM).unwrap();
//! assert!((back.angles[2] - 0.3).abs() < 1e-12);
//!
//! // A rigid motion as a unit dual quaternion (Kavan et al. eq. 1), and its screw.
//! let t = Vec3::new(1.0, 2.0, 3.0);
//! let dq = DualQuat::from_rotation_translation(q, t);
//! let p = dq.transform_point(Vec3::new(1.0, 0.0, 0.0));
//! let m = dq.to_matrix4().transform_point(Vec3::new(1.0, 0.0, 0.0));
//! assert!((p - m).norm() < 1e-12);
//! let screw = dq.to_screw().unwrap();
//! let again = DualQuat::from_screw(&screw).unwrap();
//! assert!((again.translation() - t).norm() < 1e-12);
//!
//! // Half of the motion, along the same screw: q̂^½.
//! let half = dq.powf(0.5).unwrap();
//! assert!(((half * half).translation() - t).norm() < 1e-12);
//! ```

#![forbid(unsafe_code)]
#![warn(missing_docs)]

// The integration tests' helpers (tests/common: tolerances, random inputs), for the unit
// tests too; they name this crate `chasles`.
#[cfg(test)]
extern crate self as chasles;
#[cfg(test)]
#[path = "../tests/common/mod.rs"]
mod test_common;

pub mod analysis;
mod banded;
pub mod blend;
pub mod convert;
pub mod dual;
pub mod dualquat;
pub mod error;
pub mod frame;
pub mod interop;
pub mod interp;
pub mod matrix;
pub mod quat;
pub mod real;
pub mod screw;
pub(crate) mod trig;
pub mod vec3;

pub use convert::euler::{EulerAngles, EulerOrder};
pub use dual::Dual;
pub use dualquat::DualQuat;
pub use error::{Error, Result};
pub use matrix::{Mat, Mat3, Mat4};
pub use quat::Quat;
pub use real::{default_tolerance, Real};
pub use screw::Screw;
pub use vec3::Vec3;

/// The README's examples, compiled and run as doc tests.
#[doc = include_str!("../../../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
