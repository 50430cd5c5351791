//! Errors of loading, validating and saving a reflector set.

use std::fmt;
use std::path::PathBuf;

use crate::{FORMAT_VERSION, OLDEST_READABLE_VERSION};

/// Which reflector an error is about.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReflectorRef {
    /// Position in the set's `reflectors` list.
    pub index: usize,
    /// The reflector's stable id.
    pub id: u32,
    /// The reflector's name.
    pub name: String,
}

impl fmt::Display for ReflectorRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "reflectors[{}] (id {}, {:?})", self.index, self.id, self.name)
    }
}

/// A field that breaks an invariant of the format.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InvalidField {
    /// The reflector the field belongs to; `None` for set-level fields.
    pub reflector: Option<ReflectorRef>,
    /// The field's name as written in the file, e.g. `axis_u` or `occluders[2]`.
    pub field: String,
    /// What is wrong with it.
    pub reason: String,
}

impl fmt::Display for InvalidField {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.reflector {
            Some(r) => write!(f, "{r}: field `{}`: {}", self.field, self.reason),
            None => write!(f, "field `{}`: {}", self.field, self.reason),
        }
    }
}

/// Why a reflector set could not be loaded or saved.
#[derive(Debug, thiserror::Error)]
pub enum FormatError {
    /// The file could not be read.
    #[error("{}: cannot read: {source}", path.display())]
    Read { path: PathBuf, source: std::io::Error },
    /// The file could not be written (nothing was left behind).
    #[error("{}: cannot write: {source}", path.display())]
    Write { path: PathBuf, source: std::io::Error },
    /// The text is not JSON.
    #[error("not JSON: {0}")]
    Json(#[from] serde_json::Error),
    /// The JSON is not shaped like a reflector set: `path` names the field
    /// (e.g. `reflectors[2].coverage`).
    #[error("field `{path}`: {source}")]
    Shape { path: String, source: serde_json::Error },
    /// The document's `format` field is missing or not [`crate::FORMAT_NAME`].
    #[error("not a reflector set: field `format` is {found}, expected \"ppr-reflector-set\"")]
    WrongFormat { found: String },
    /// The document's `version` is not one this build reads.
    #[error(
        "unsupported reflector-set version {found} (this build reads versions {OLDEST_READABLE_VERSION} to {FORMAT_VERSION})"
    )]
    UnknownVersion { found: String },
    /// A field breaks an invariant.
    #[error("{0}")]
    Invalid(InvalidField),
    /// An error in a named file.
    #[error("{}: {source}", path.display())]
    InFile { path: PathBuf, source: Box<FormatError> },
}

impl FormatError {
    /// The invalid field, if that is what this error is about (looking through `InFile`).
    pub fn invalid_field(&self) -> Option<&InvalidField> {
        // (`Shape` errors carry a path instead: see [`FormatError::field_path`].)
        match self {
            Self::Invalid(f) => Some(f),
            Self::InFile { source, .. } => source.invalid_field(),
            _ => None,
        }
    }

    /// The path of the offending field, for shape and invariant errors: `reflectors[2].coverage`.
    pub fn field_path(&self) -> Option<String> {
        match self {
            Self::Shape { path, .. } => Some(path.clone()),
            Self::Invalid(f) => Some(match &f.reflector {
                Some(r) => format!("reflectors[{}].{}", r.index, f.field),
                None => f.field.clone(),
            }),
            Self::InFile { source, .. } => source.field_path(),
            _ => None,
        }
    }

    pub(crate) fn in_file(self, path: impl Into<PathBuf>) -> Self {
        match self {
            e @ (Self::Read { .. } | Self::Write { .. } | Self::InFile { .. }) => e,
            e => Self::InFile { path: path.into(), source: Box::new(e) },
        }
    }
}
