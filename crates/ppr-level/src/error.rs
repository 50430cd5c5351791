//! Why a level could not be loaded: each variant names the file and what in it is wrong.

use std::path::PathBuf;

/// A level that cannot be read. Every message is one line and names the file.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The file (or an external buffer) could not be read from disk.
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Neither a `.glb` container nor glTF JSON.
    #[error("{}: not a glTF file: {reason}", path.display())]
    NotGltf {
        /// The file.
        path: PathBuf,
        /// What was found instead.
        reason: String,
    },
    /// A `.glb` whose header or chunks promise more bytes than the file has.
    #[error("{}: truncated .glb: {reason}", path.display())]
    TruncatedGlb {
        /// The file.
        path: PathBuf,
        /// Which length does not fit.
        reason: String,
    },
    /// The glTF JSON breaks the specification.
    #[error("{}: invalid glTF: `{field}`: {reason}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// JSON path of the offending field, e.g. `meshes[0].primitives[1].indices`.
        field: String,
        /// What is wrong with it.
        reason: String,
    },
    /// `extensionsRequired` names an extension this build cannot read.
    #[error(
        "{}: requires glTF extension `{extension}`, which the level loader cannot read (supported: KHR_mesh_quantization, EXT_meshopt_compression, EXT_mesh_gpu_instancing, and the light, texture and material extensions that do not change geometry)",
        path.display()
    )]
    UnsupportedExtension {
        /// The file.
        path: PathBuf,
        /// The extension's name.
        extension: String,
    },
    /// An external buffer file (`buffers[i].uri`) is missing or unreadable.
    #[error("{}: buffers[{index}]: cannot read external buffer `{uri}`: {source}", path.display())]
    MissingBuffer {
        /// The glTF file.
        path: PathBuf,
        /// Index of the buffer.
        index: usize,
        /// The buffer's URI as written in the file.
        uri: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A buffer URI that is not a relative path inside the level's folder (absolute, with a
    /// `..` component or a scheme), or that names something other than a regular file.
    #[error("{}: buffers[{index}]: uri `{uri}` refused: {reason}", path.display())]
    UnsafeUri {
        /// The glTF file.
        path: PathBuf,
        /// Index of the buffer.
        index: usize,
        /// The URI as written in the file.
        uri: String,
        /// Why it is refused.
        reason: String,
    },
    /// A buffer is shorter than its `byteLength`, or has no data where data is needed.
    #[error("{}: buffers[{index}]: {reason}", path.display())]
    BadBuffer {
        /// The glTF file.
        path: PathBuf,
        /// Index of the buffer.
        index: usize,
        /// What is wrong with it.
        reason: String,
    },
    /// A buffer view or accessor reaches outside the data it reads.
    #[error("{}: {field} is out of range: {reason}", path.display())]
    OutOfRange {
        /// The glTF file.
        path: PathBuf,
        /// e.g. `accessors[3]` or `bufferViews[2]`.
        field: String,
        /// Which offset and length do not fit.
        reason: String,
    },
    /// An accessor with a type or component type that its use does not allow.
    #[error("{}: {field}: {reason}", path.display())]
    BadAccessor {
        /// The glTF file.
        path: PathBuf,
        /// e.g. `accessors[3]`.
        field: String,
        /// What is wrong.
        reason: String,
    },
    /// A vertex position (or a transform) that is NaN or infinite.
    #[error("{}: {field}: non-finite vertex position (NaN or infinity) {detail}", path.display())]
    NonFinitePosition {
        /// The glTF file.
        path: PathBuf,
        /// The accessor or node that holds it.
        field: String,
        /// Where in it.
        detail: String,
    },
    /// A world-space vertex farther from the origin than the reflector-set format allows
    /// (`ppr_format::MAX_COORDINATE` metres on any axis).
    #[error(
        "{}: nodes[{node}] ({name:?}): vertex {vertex} lies at {position:?} in world space, beyond the ±{limit} m that reflector sets allow; move the level nearer the origin",
        path.display()
    )]
    PositionOutOfRange {
        /// The glTF file.
        path: PathBuf,
        /// Index of the node that places the vertex.
        node: usize,
        /// The node's name, or `#index`.
        name: String,
        /// Index of the vertex in its mesh's primitive.
        vertex: usize,
        /// Where it lands, metres.
        position: [f64; 3],
        /// The limit, metres.
        limit: f64,
    },
    /// The level asks for more than the loader holds (node visits, triangles): the limit
    /// and what exceeded it are named.
    #[error("{}: {field}: {reason}", path.display())]
    TooLarge {
        /// The glTF file.
        path: PathBuf,
        /// What grew too large, e.g. `nodes` or `meshes[3]`.
        field: String,
        /// The size and the limit.
        reason: String,
    },
    /// `EXT_meshopt_compression` data that the decoder refused.
    #[error("{}: bufferViews[{view}]: EXT_meshopt_compression: {reason}", path.display())]
    Meshopt {
        /// The glTF file.
        path: PathBuf,
        /// The compressed buffer view.
        view: usize,
        /// What failed.
        reason: String,
    },
    /// `extras.ppr` that is not `{"reflector": bool, "kind": "opaque|transparent|water"}`.
    #[error("{}: {owner}: extras.ppr: {reason}", path.display())]
    BadExtras {
        /// The glTF file.
        path: PathBuf,
        /// e.g. `materials[2] ("Glass")`.
        owner: String,
        /// What is wrong.
        reason: String,
    },
}

impl LoadError {
    /// The file the error is about.
    pub fn path(&self) -> &std::path::Path {
        match self {
            Self::Read { path, .. }
            | Self::NotGltf { path, .. }
            | Self::TruncatedGlb { path, .. }
            | Self::Invalid { path, .. }
            | Self::UnsupportedExtension { path, .. }
            | Self::MissingBuffer { path, .. }
            | Self::UnsafeUri { path, .. }
            | Self::BadBuffer { path, .. }
            | Self::OutOfRange { path, .. }
            | Self::BadAccessor { path, .. }
            | Self::NonFinitePosition { path, .. }
            | Self::PositionOutOfRange { path, .. }
            | Self::TooLarge { path, .. }
            | Self::Meshopt { path, .. }
            | Self::BadExtras { path, .. } => path,
        }
    }
}
