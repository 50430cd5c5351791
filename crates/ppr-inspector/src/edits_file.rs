//! The record of manual edits saved beside a set (`room.ppr.json` → `room.ppr.edits.json`),
//! so that re-extracting after the set is reopened still keeps the artist's edits. The file
//! format is `ppr_format::edits`; reading and writing it is the extractor's
//! (`ppr_extract::edits_file`), which `ppr-extract` uses to re-apply the same edits.

use std::path::Path;

use ppr_extract::edits_file::{EditsError, load_edits, save_edits};
use ppr_format::ReflectorSet;

use crate::error::InspectorError;
use crate::manual_edits::ManualEdits;

pub use ppr_format::edits::{EDITS_FORMAT_NAME as FORMAT, EDITS_FORMAT_VERSION as VERSION, edits_path};

fn inspector_error(e: EditsError, set_path: &Path) -> InspectorError {
    match e {
        EditsError::File { path, reason } => InspectorError::EditsFile { path, reason },
        other => InspectorError::EditsFile { path: edits_path(set_path), reason: other.to_string() },
    }
}

/// Writes the edits beside the set (atomically), or removes a stale file when there are none.
///
/// # Errors
/// [`InspectorError::EditsFile`] naming the file when it cannot be written or removed.
pub fn save(set_path: &Path, edits: &ManualEdits) -> Result<(), InspectorError> {
    save_edits(set_path, edits).map_err(|e| inspector_error(e, set_path))
}

/// Reads the edits kept beside the set at `set_path`: `None` when there is no such file.
/// Edited ids that neither the set nor a split or merge has are dropped (the set was
/// changed by another tool since).
///
/// # Errors
/// [`InspectorError::EditsFile`] naming the file and what is wrong (unreadable, not JSON,
/// another format or version, an invalid reflector).
pub fn load(set_path: &Path, set: &ReflectorSet) -> Result<Option<ManualEdits>, InspectorError> {
    load_edits(set_path, set).map_err(|e| inspector_error(e, set_path))
}
