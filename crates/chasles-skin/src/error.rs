//! Typed errors for rigs, poses and files: each names what is wrong and where.

use thiserror::Error;

/// What went wrong while loading, posing, skinning or writing.
#[derive(Debug, Error)]
pub enum SkinError {
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// A glTF file that does not parse.
    #[error("{path}: not a valid glTF file: {reason}")]
    Gltf {
        /// The file.
        path: String,
        /// The parser's message.
        reason: String,
    },
    /// A field of a JSON file (rig or pose) of the wrong shape or with a value that cannot
    /// be used, named by its path (`joints[2].rotation`).
    #[error("{file}: {path}: {reason}")]
    Field {
        /// The file.
        file: String,
        /// The field's path in the file (`.` for the whole document).
        path: String,
        /// What is wrong.
        reason: String,
    },
    /// Something missing or malformed in a rig, naming the item.
    #[error("{0}")]
    Invalid(String),
    /// A vertex influence naming a joint that does not exist.
    #[error("vertex {vertex}: joint index {joint} out of range (the skin has {joints} joints)")]
    JointOutOfRange {
        /// The vertex.
        vertex: usize,
        /// The joint index given.
        joint: usize,
        /// How many joints there are.
        joints: usize,
    },
    /// Vertex weights that are negative, not finite, or sum to zero.
    #[error("vertex {vertex}: {reason}")]
    BadWeights {
        /// The vertex.
        vertex: usize,
        /// What is wrong.
        reason: String,
    },
    /// A buffer too short for the data an accessor claims.
    #[error("accessor {accessor} ({what}) reads past the end of its buffer: needs {needed} bytes, the buffer view has {available}")]
    Truncated {
        /// The accessor index.
        accessor: usize,
        /// What it holds.
        what: String,
        /// Bytes needed.
        needed: usize,
        /// Bytes available.
        available: usize,
    },
    /// An error from the core algebra.
    #[error(transparent)]
    Math(#[from] chasles::Error),
}

/// Result with [`SkinError`].
pub type Result<T> = std::result::Result<T, SkinError>;

pub(crate) fn invalid<T>(msg: impl Into<String>) -> Result<T> {
    Err(SkinError::Invalid(msg.into()))
}
