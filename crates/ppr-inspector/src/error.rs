//! Errors of the inspector's operations: every one ends up as a message in the UI.

use std::path::PathBuf;

use ppr_format::{FormatError, InvalidField};

/// Why an edit was refused (the set is left as it was).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EditError {
    /// The command names a reflector the set does not have.
    #[error("no reflector with id {0}")]
    UnknownId(u32),
    /// The edited set breaks an invariant of the format (`ReflectorSet::validate`).
    #[error("edit refused: {0}")]
    Invalid(InvalidField),
    /// The edited set failed validation for another reason.
    #[error("edit refused: {0}")]
    Refused(String),
    /// Two reflectors that cannot become one rectangle.
    #[error("cannot merge {a:?} and {b:?}: {reason}")]
    NotMergeable {
        /// Name of the first reflector.
        a: String,
        /// Name of the second reflector.
        b: String,
        /// Why not.
        reason: String,
    },
    /// A split that makes no sense (position outside the rectangle, empty part).
    #[error("cannot split {name:?}: {reason}")]
    NotSplittable {
        /// Name of the reflector.
        name: String,
        /// Why not.
        reason: String,
    },
    /// Re-fitting needs the reflector's region from an extraction.
    #[error("cannot re-fit {name:?}: {reason}")]
    NoRegion {
        /// Name of the reflector.
        name: String,
        /// Why not.
        reason: String,
    },
}

impl From<FormatError> for EditError {
    fn from(e: FormatError) -> Self {
        match e.invalid_field() {
            Some(field) => EditError::Invalid(field.clone()),
            None => EditError::Refused(e.to_string()),
        }
    }
}

/// Why an operation of the inspector failed.
#[derive(Debug, thiserror::Error)]
pub enum InspectorError {
    /// Loading or saving a reflector set (names the file and the field).
    #[error("{0}")]
    Format(#[from] FormatError),
    /// The level could not be loaded for extraction.
    #[error("{0}")]
    LoadLevel(#[from] ppr_extract::LoadError),
    /// The level could not be loaded or rendered by the testbed.
    #[error("{0}")]
    Testbed(#[from] ppr_testbed::TestbedError),
    /// A level that breaks the testbed's invariants.
    #[error("{}: level cannot be rendered: {reason}", path.display())]
    InvalidLevel {
        /// The level file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// An edit was refused.
    #[error("{0}")]
    Edit(#[from] EditError),
    /// Extraction parameters out of range.
    #[error("extraction parameters: {0}")]
    Params(String),
    /// An operation that needs something the inspector does not have yet.
    #[error("{0}")]
    Missing(String),
    /// The extraction thread stopped without a result.
    #[error("extraction failed: {0}")]
    Extraction(String),
    /// The GPU refused work (validation or out of memory), caught in an error scope.
    #[error("GPU error: {0}")]
    Gpu(String),
    /// The manual-edit record beside a set (`*.edits.json`) could not be read or written.
    #[error("{}: manual-edit record: {reason}", path.display())]
    EditsFile {
        /// The edits file.
        path: PathBuf,
        /// What went wrong.
        reason: String,
    },
    /// Writing an image (screenshot) failed.
    #[error("{}: cannot write image: {reason}", path.display())]
    Image {
        /// The image file.
        path: PathBuf,
        /// What went wrong.
        reason: String,
    },
}
