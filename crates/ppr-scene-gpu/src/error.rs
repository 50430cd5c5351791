//! Errors of the shared scene pieces: opening a GPU device, reading a camera description.

/// Why no device could be opened.
#[derive(Debug, thiserror::Error)]
pub enum GpuInitError {
    /// No wgpu adapter could be found.
    #[error("no GPU adapter: {0}")]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("the adapter {adapter:?} refused to create a device: {reason}")]
    NoDevice {
        /// The adapter's name.
        adapter: String,
        /// What wgpu said.
        reason: String,
    },
}

/// A camera description (`--camera`) that does not parse or names nothing.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("camera {text:?}: {reason}")]
pub struct CameraSpecError {
    /// The text as given.
    pub text: String,
    /// What is wrong with it.
    pub reason: String,
}
