//! Conversions between rotation representations (Dam et al. 1998, App. B):
//! [`euler`] (all 12 axis sequences, intrinsic and extrinsic; B.1, B.2, B.5),
//! [`matrix`] (quaternion ↔ 3×3/4×4 matrix; B.3, and Shepperd's method in place of B.4),
//! [`axis_angle`] (axis–angle and rotation vectors; Proposition 21).
//! Rigid transformations ↔ dual quaternions (Kavan et al. 2006, eq. 1) are methods of
//! [`crate::DualQuat`].
//!
//! Batches: [`euler::quats_to_euler`], [`matrix::quats_to_rotation_matrices`] and
//! [`matrix::quats_from_rotation_matrices`] convert slices at once, in loops without
//! branches or calls that the compiler vectorizes, and give the per-item functions' results
//! (the Euler angles to a few ulp, the matrices and quaternions bit for bit); they report
//! the first item that fails as a [`BatchError`] (so does [`crate::blend::dlb::dlb_batch`]).

pub mod axis_angle;
pub mod euler;
pub mod matrix;

use crate::Error;

/// Why a batch function stopped: the first item that failed (lowest index), with the error
/// its per-item function gives it. The items before `index` have been written. For inputs
/// of different lengths `error` is [`Error::BatchLengths`] and `index` the shorter length
/// (the first item one of them lacks), before anything is written.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("item {index}: {error}")]
pub struct BatchError {
    /// The index of the item in the batch.
    pub index: usize,
    /// What went wrong with it.
    #[source]
    pub error: Error,
}

/// `Ok` when every length equals the first one's; else the [`Error::BatchLengths`] of the
/// first that does not, naming `what[k]`.
pub(crate) fn same_lengths(
    lens: &[usize],
    what: &[&'static str],
) -> core::result::Result<(), BatchError> {
    for (k, len) in lens.iter().enumerate().skip(1) {
        if *len != lens[0] {
            return Err(BatchError {
                index: lens[0].min(*len),
                error: Error::BatchLengths {
                    what: what[k - 1],
                    a: lens[0],
                    b: *len,
                },
            });
        }
    }
    Ok(())
}

/// Items the batch functions run side by side in lanes, where they do: one array per
/// number, one lane per item, so that their arithmetic is one loop over the lanes, which the
/// compiler vectorizes.
pub(crate) const LANES: usize = 8;
