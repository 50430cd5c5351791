//! Why a bench run failed.

use std::path::PathBuf;

/// Errors of the bench library.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// The testbed failed (adapter, level loading, readback, images).
    #[error(transparent)]
    Testbed(#[from] ppr_testbed::TestbedError),
    /// A reflector set breaks an invariant of the format (names the reflector and field).
    #[error(transparent)]
    Format(#[from] ppr_format::FormatError),
    /// A level could not be read by the extractor.
    #[error("{}: {reason}", path.display())]
    Level { path: PathBuf, reason: String },
    /// A scene, technique or resolution on the command line is not understood.
    #[error("{0}")]
    Spec(String),
    /// A file could not be written.
    #[error("{}: {source}", path.display())]
    Io { path: PathBuf, source: std::io::Error },
    /// A CSV file read back (`goals`) lacks a column or holds a value that does not parse
    /// (the reason names the line and the field).
    #[error("{}: {reason}", path.display())]
    Csv { path: PathBuf, reason: String },
    /// A plot could not be drawn or saved.
    #[error("plot {}: {reason}", path.display())]
    Plot { path: PathBuf, reason: String },
    /// The GPU did something the bench cannot work with.
    #[error("GPU: {0}")]
    Gpu(String),
    /// `pipeline-stats`: no Vulkan device with pipeline statistics, or a Vulkan call failed.
    #[error(transparent)]
    PipelineStats(#[from] crate::pipeline_stats::PipelineStatsError),
}

impl BenchError {
    /// An I/O error at `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Self::Io { path: path.into(), source }
    }
}
