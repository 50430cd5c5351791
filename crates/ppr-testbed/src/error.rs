//! Errors of the testbed library: loading levels, talking to the GPU, reading and writing images.

use std::path::PathBuf;

/// Why a testbed operation failed.
#[derive(Debug, thiserror::Error)]
pub enum TestbedError {
    /// No wgpu adapter could be found: GPU tests cannot run.
    #[error(
        "NO GPU ADAPTER FOUND ({0}). The testbed needs a wgpu adapter; on a machine without a GPU \
         install Mesa (llvmpipe, reached through wgpu's GL backend via EGL: Debian packages \
         libegl1 libegl-mesa0 libgl1-mesa-dri) or set WGPU_BACKEND to a backend that exists here"
    )]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("the adapter {adapter:?} refused to create a device: {reason}")]
    NoDevice { adapter: String, reason: String },
    /// A GPU buffer could not be mapped for reading.
    #[error("reading back {what} from the GPU failed: {reason}")]
    Readback { what: String, reason: String },
    /// A texture format the testbed cannot read back or convert.
    #[error("{what}: texture format {format:?} is not supported here")]
    UnsupportedFormat { what: String, format: wgpu::TextureFormat },
    /// `ppr-level` refused the glTF file (the message names the file and the field).
    #[error(transparent)]
    Level(#[from] ppr_level::LoadError),
    /// A glTF file was read but a field in it is not usable.
    #[error("{}: {field}: {reason}", path.display())]
    InvalidGltf { path: PathBuf, field: String, reason: String },
    /// An image could not be encoded or written.
    #[error("{}: cannot write image: {source}", path.display())]
    ImageWrite { path: PathBuf, source: image::ImageError },
    /// An image could not be read or decoded.
    #[error("{}: cannot read image: {source}", path.display())]
    ImageRead { path: PathBuf, source: image::ImageError },
    /// Two images that must have the same size do not.
    #[error("{what}: sizes differ ({a:?} vs {b:?})")]
    SizeMismatch { what: String, a: [u32; 2], b: [u32; 2] },
    /// The reflector set could not be loaded.
    #[error("reflector set: {0}")]
    ReflectorSet(Box<ppr_format::FormatError>),
    /// The set was extracted from other bytes than the level's (`source.hash`).
    #[error("{0}; to render with it anyway, accept the mismatch (ppr-render --accept-level-mismatch)")]
    SourceMismatch(#[from] ppr_format::SourceMismatch),
    /// A camera description could not be parsed.
    #[error("camera {text:?}: {reason}")]
    CameraSpec { text: String, reason: String },
}

impl From<ppr_format::FormatError> for TestbedError {
    fn from(e: ppr_format::FormatError) -> Self {
        Self::ReflectorSet(Box::new(e))
    }
}

impl From<ppr_scene_gpu::CameraSpecError> for TestbedError {
    fn from(e: ppr_scene_gpu::CameraSpecError) -> Self {
        Self::CameraSpec { text: e.text, reason: e.reason }
    }
}

impl From<ppr_scene_gpu::GpuInitError> for TestbedError {
    fn from(e: ppr_scene_gpu::GpuInitError) -> Self {
        match e {
            ppr_scene_gpu::GpuInitError::NoAdapter(reason) => Self::NoAdapter(reason),
            ppr_scene_gpu::GpuInitError::NoDevice { adapter, reason } => Self::NoDevice { adapter, reason },
        }
    }
}
