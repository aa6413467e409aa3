//! Typed errors for everything in the core crate that can be asked something impossible.
//!
//! Every fallible function returns [`Result<T>`](crate::Result); nothing in the crate panics
//! on a NaN, an infinity, a zero quaternion or a non-rigid matrix.

use thiserror::Error;

/// What went wrong. Each variant names the problem and, where useful, the offending value
/// (as `f64`, so that the error type is not generic).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Error {
    /// An input contains NaN or ±∞.
    #[error("{what} is not finite (contains NaN or infinity)")]
    NonFinite {
        /// Which input.
        what: &'static str,
    },
    /// A quaternion, vector or axis of zero length where a direction or an inverse is needed.
    #[error("{what} has zero length and cannot be normalized or inverted")]
    ZeroNorm {
        /// Which input.
        what: &'static str,
    },
    /// A dual number with zero real part has no inverse (Kavan et al. 2006, §3).
    #[error("the dual number {re} + ε{du} is purely dual (real part 0) and has no inverse")]
    PurelyDual {
        /// Real part.
        re: f64,
        /// Dual part.
        du: f64,
    },
    /// The square root of a dual number needs a positive real part (Kavan et al. 2006, §3).
    #[error("the square root of the dual number {re} + ε{du} is undefined: the real part must be positive")]
    NonPositiveSqrt {
        /// Real part.
        re: f64,
        /// Dual part.
        du: f64,
    },
    /// The logarithm of a dual number needs a positive real part.
    #[error("the logarithm of the dual number {re} + ε{du} is undefined: the real part must be positive")]
    NonPositiveLog {
        /// Real part.
        re: f64,
        /// Dual part.
        du: f64,
    },
    /// A matrix that should be a rotation (orthonormal, determinant +1) is not.
    #[error("the matrix is not a rotation: {reason} (deviation {deviation:e})")]
    NotRotation {
        /// What check failed.
        reason: &'static str,
        /// The size of the failure.
        deviation: f64,
    },
    /// A 4×4 matrix that should be a rigid transformation is not.
    #[error("the 4x4 matrix is not a rigid transformation: {reason} (deviation {deviation:e})")]
    NotRigid {
        /// What check failed.
        reason: &'static str,
        /// The size of the failure.
        deviation: f64,
    },
    /// A dual quaternion that should be unit is not.
    #[error("the dual quaternion is not unit: |q0| - 1 = {norm_deviation:e}, <q0, qe> = {dot:e}")]
    NotUnit {
        /// |q0| − 1.
        norm_deviation: f64,
        /// ⟨q0, qε⟩ (must be 0).
        dot: f64,
    },
    /// A quaternion that should be unit is not.
    #[error("the quaternion is not unit: its norm is {norm}")]
    NotUnitQuat {
        /// ‖q‖.
        norm: f64,
    },
    /// Too few key frames for a method.
    #[error("{what} needs at least {needed} key frames, got {got}")]
    TooFewKeys {
        /// Which method or operation.
        what: &'static str,
        /// The minimum.
        needed: usize,
        /// How many were given.
        got: usize,
    },
    /// Fewer output frames than key frames: every key must appear as a frame.
    #[error("{frames} frames cannot hold {keys} key frames: ask for at least {keys}")]
    TooFewFrames {
        /// Frames asked for.
        frames: usize,
        /// Key frames.
        keys: usize,
    },
    /// Key times that are not finite or not strictly increasing.
    #[error("key time {index} ({value}) must be finite and greater than the previous one")]
    BadKeyTime {
        /// Index of the offending key.
        index: usize,
        /// Its time.
        value: f64,
    },
    /// A key frame that is not a usable rotation.
    #[error("key frame {index}: {source}")]
    BadKey {
        /// Index of the key.
        index: usize,
        /// What is wrong with it.
        #[source]
        source: Box<Error>,
    },
    /// More frames than memory can hold (the allocation was refused, not attempted blind).
    #[error("cannot hold {frames} frames in memory")]
    TooManyFrames {
        /// The frames asked for.
        frames: usize,
    },
    /// An iteration that did not settle within its cap.
    #[error("{what} did not converge in {iterations} iterations")]
    NotConverged {
        /// What was iterated.
        what: &'static str,
        /// The iterations run.
        iterations: usize,
    },
    /// A parameter outside its allowed range.
    #[error("{what} must be {rule}, got {value}")]
    BadParameter {
        /// Which parameter.
        what: &'static str,
        /// The rule, in words.
        rule: &'static str,
        /// The value given.
        value: f64,
    },
    /// A blending weight that is negative or not finite.
    #[error("weight {index} is {value}: weights must be finite and non-negative")]
    BadWeight {
        /// Index of the weight.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// Weights whose sum is not positive.
    #[error("the weights sum to {sum}: they must sum to a positive number (they are then scaled to sum to 1)")]
    WeightSum {
        /// The sum.
        sum: f64,
    },
    /// A count mismatch between transforms and weights, or too few transforms.
    #[error("{what}")]
    BlendInput {
        /// What is wrong.
        what: String,
    },
    /// The wrong number of values for a representation.
    #[error("{what} needs {expected} numbers, got {got}")]
    WrongLength {
        /// Which representation.
        what: &'static str,
        /// Accepted counts, in words.
        expected: &'static str,
        /// How many were given.
        got: usize,
    },
    /// Batch inputs of different lengths.
    #[error("{what}: {a} and {b} values, which must be as many")]
    BatchLengths {
        /// Which batch.
        what: &'static str,
        /// The first input's length.
        a: usize,
        /// The other's.
        b: usize,
    },
    /// A key's angular velocity that a method cannot honour where it is.
    #[error("key frame {index}'s angular velocity: {why}")]
    KeyVelocity {
        /// The key.
        index: usize,
        /// Why it cannot be honoured.
        why: &'static str,
    },
    /// Unknown name for an Euler-angle order.
    #[error("unknown Euler order {0:?}: use three of x, y, z with no two neighbours equal, lower case for extrinsic (fixed axes, e.g. \"xyz\"), upper case for intrinsic (e.g. \"XYZ\")")]
    UnknownEulerOrder(String),
}

/// Result with the crate's [`Error`](enum@Error).
pub type Result<T> = core::result::Result<T, Error>;

/// Returns `Err(NonFinite)` unless every value is finite.
pub(crate) fn check_finite<T: crate::Real>(what: &'static str, values: &[T]) -> Result<()> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFinite { what })
    }
}
