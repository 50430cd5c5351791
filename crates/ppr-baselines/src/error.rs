//! Errors of the baselines (reading GPU data back for tests and tools).

/// What can go wrong outside the recording of passes.
#[derive(Debug, thiserror::Error)]
pub enum BaselineError {
    /// Mapping a readback buffer or waiting for the device failed.
    #[error("reading back {what}: {reason}")]
    Readback {
        /// What was read.
        what: String,
        /// The device's reason.
        reason: String,
    },
    /// A Hi-Z level that the pyramid does not have.
    #[error("Hi-Z level {level} out of range (the pyramid has {levels})")]
    NoSuchLevel {
        /// The level asked for.
        level: u32,
        /// Levels of the pyramid.
        levels: u32,
    },
    /// A technique was asked for frame data before [`ppr_testbed::ReflectionTechnique::prepare`].
    #[error("{0} has no prepared frame")]
    NotPrepared(&'static str),
}
