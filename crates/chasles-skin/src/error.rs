//! Typed errors for rigs, poses and files: each names what is wrong and where.

use thiserror::Error;

/// What went wrong while loading, posing, skinning or writing.
#[derive(Debug, Error)]
pub enum SkinError {
    /// A file could not be read or written.
    #[error("{path}: {cause}")]
    Io {
        /// The file.
        path: String,
        /// The cause (in the message, not also a `source`: printed once).
        cause: std::io::Error,
    },
    /// A path that is not a regular file (a device, a folder, a pipe).
    #[error("{path}: not a regular file")]
    NotAFile {
        /// The path.
        path: String,
    },
    /// A file or stream past the size this kind of input may have.
    #[error("{path}: {size} bytes or more, past the limit of {limit} bytes for this input")]
    TooLarge {
        /// The file or stream.
        path: String,
        /// Its size (or the bytes read when it passed the limit).
        size: u64,
        /// The limit.
        limit: u64,
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
    /// A glTF file that parses but holds something that cannot be skinned, naming the item
    /// (`buffer 0`, `primitive 2`, `accessor 5 (POSITION)`, `skin`, `animation 1`).
    #[error("{file}: {item}: {problem}")]
    GltfContent {
        /// The file.
        file: String,
        /// The item of the file.
        item: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A file whose kind is not known from its extension.
    #[error("{path}: rigs are read from .gltf, .glb or .json files")]
    UnknownFormat {
        /// The file.
        path: String,
    },
    /// Two sizes that must agree and do not: `{got} {what}` where `{expected}` belong.
    #[error("{rig}: {got} {what}, expected {expected}")]
    Count {
        /// The rig (or what the data belongs to).
        rig: String,
        /// What was counted (`normals`, `joint transforms`, `output vertices`).
        what: &'static str,
        /// How many there should be.
        expected: usize,
        /// How many there are.
        got: usize,
    },
    /// An index past the end of what it indexes.
    #[error("{rig}: {what} {index} out of range (there are {count})")]
    OutOfRange {
        /// The rig.
        rig: String,
        /// What the index names (`vertex of triangle 3`, `node of joint 2`).
        what: String,
        /// The index.
        index: usize,
        /// How many there are.
        count: usize,
    },
    /// A number that must be finite and is not.
    #[error("{rig}: {what} is not finite")]
    NotFinite {
        /// The rig.
        rig: String,
        /// The number (`the position of vertex 7`, `time NaN`).
        what: String,
    },
    /// A number past the range every skinning path keeps finite ([`crate::reach`]).
    #[error("{rig}: {what} is {value:e}, past ±{limit:e}, the range in which every skinning path stays finite")]
    OutOfReach {
        /// The rig.
        rig: String,
        /// The number (`joint 3's translation[0]`).
        what: String,
        /// Its value.
        value: f32,
        /// The bound it passes.
        limit: f32,
    },
    /// A node whose parent chain is broken or a cycle.
    #[error("{rig}: node {node} has a broken or cyclic parent chain")]
    Hierarchy {
        /// The rig.
        rig: String,
        /// The node.
        node: usize,
    },
    /// A rig with more joints than 16-bit joint indices hold.
    #[error("{joints} joints: at most 65535 are supported")]
    TooManyJoints {
        /// The joint count.
        joints: usize,
    },
    /// A vertex with more influences than a fast-path layout holds.
    #[error("{rig}: a vertex has {most} influences; this layout holds {layout}")]
    TooManyInfluences {
        /// The rig.
        rig: String,
        /// The most influences of any vertex.
        most: usize,
        /// The layout's K.
        layout: usize,
    },
    /// An animation clip that does not exist.
    #[error("{rig}: no animation {clip} (there are {count})")]
    NoAnimation {
        /// The rig.
        rig: String,
        /// The clip asked for.
        clip: usize,
        /// How many clips there are.
        count: usize,
    },
    /// A clip asked for by a name (or index) the rig does not have.
    #[error("{rig}: no animation '{clip}'; there are: {available}")]
    NoClip {
        /// The rig.
        rig: String,
        /// The name asked for.
        clip: String,
        /// The clips there are, by name (and index).
        available: String,
    },
    /// A parameter out of its range (a blend weight outside [0, 1], a tolerance that is
    /// not positive, a NaN).
    #[error("{what} {value} {reason}")]
    Parameter {
        /// The parameter (`the weight`, `the tolerance`).
        what: &'static str,
        /// Its value, as given.
        value: String,
        /// What it must be.
        reason: &'static str,
    },
    /// An animation channel that cannot be played.
    #[error("{rig}: animation {animation}, channel {channel} (node {node}): {problem}")]
    Channel {
        /// The rig.
        rig: String,
        /// The clip's index.
        animation: usize,
        /// The channel's index in the clip.
        channel: usize,
        /// The node the channel targets.
        node: usize,
        /// What is wrong.
        problem: ChannelProblem,
    },
    /// An interleaved output whose stride is under 6 floats or does not divide its length.
    #[error("interleaved output: a stride of {stride} floats (at least 6: position, normal) does not fit its {floats} floats")]
    Stride {
        /// Floats per vertex.
        stride: usize,
        /// Floats in the buffer.
        floats: usize,
    },
    /// Skinning that produced a non-finite vertex (from non-finite or degenerate joints).
    #[error("{rig}: skinning with {method} produced a non-finite vertex ({vertex})")]
    NonFiniteOutput {
        /// The rig.
        rig: String,
        /// The method's name.
        method: &'static str,
        /// The first such vertex.
        vertex: usize,
    },
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
    #[error("{file}: accessor {accessor} ({what}) reads past the end of its buffer: needs {needed} bytes, the buffer view has {available}")]
    Truncated {
        /// The file.
        file: String,
        /// The accessor index.
        accessor: usize,
        /// What it holds.
        what: String,
        /// Bytes needed.
        needed: usize,
        /// Bytes available.
        available: usize,
    },
    /// A pool of worker threads could not be started.
    #[error("cannot start worker threads: {0}")]
    Threads(String),
    /// An error from the core algebra.
    #[error(transparent)]
    Math(#[from] chasles::Error),
}

/// What is wrong with an animation channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Error)]
pub enum ChannelProblem {
    /// It targets a node that does not exist.
    #[error("the node is out of range (there are {nodes})")]
    NodeOutOfRange {
        /// How many nodes there are.
        nodes: usize,
    },
    /// It has no keys.
    #[error("no keys")]
    NoKeys,
    /// Its key times are not finite and strictly increasing.
    #[error("key times must be finite and strictly increasing")]
    Times,
    /// Its values do not match its keys.
    #[error("{keys} keys but {values} values (expected {expected})")]
    Values {
        /// Keys.
        keys: usize,
        /// Values.
        values: usize,
        /// Values expected.
        expected: usize,
    },
    /// A value is not finite.
    #[error("values that are not finite")]
    NotFinite,
}

/// Result with [`SkinError`].
pub type Result<T> = std::result::Result<T, SkinError>;

/// `Ok` when `got` is `expected`, else the [`SkinError::Count`] naming `what` of `rig`.
pub(crate) fn same_count(rig: &str, what: &'static str, expected: usize, got: usize) -> Result<()> {
    if expected == got {
        Ok(())
    } else {
        Err(SkinError::Count {
            rig: rig.to_string(),
            what,
            expected,
            got,
        })
    }
}

/// The name the fast path's size errors give its rig.
pub(crate) const FAST_RIG: &str = "the fast rig";

/// A [`SkinError::GltfContent`] for `item` of `file`.
pub(crate) fn gltf_content(
    file: &str,
    item: impl Into<String>,
    problem: impl Into<String>,
) -> SkinError {
    SkinError::GltfContent {
        file: file.to_string(),
        item: item.into(),
        problem: problem.into(),
    }
}
