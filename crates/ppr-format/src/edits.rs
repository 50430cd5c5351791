//! The manual-edits file kept beside a set (`room.ppr.json` → `room.ppr.edits.json`): which
//! reflectors an artist edited by hand and which were split or merged, so that a
//! re-extraction (the inspector's or `ppr-extract`'s) keeps them. The set file stays what a
//! game loads; the edited reflectors themselves are in the set, this file names them.

use std::path::{Path, PathBuf};

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::Reflector;

/// The `format` field of an edits file.
pub const EDITS_FORMAT_NAME: &str = "ppr-inspector-edits";
/// The version this build reads and writes.
pub const EDITS_FORMAT_VERSION: u32 = 1;

/// The edits file as stored.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EditsFile {
    /// Always [`EDITS_FORMAT_NAME`].
    pub format: String,
    /// Always [`EDITS_FORMAT_VERSION`].
    pub version: u32,
    /// Ids whose properties or rectangle were edited by hand (the set holds the result).
    pub edited: Vec<u32>,
    /// Splits and merges, in order.
    pub replacements: Vec<SavedReplacement>,
}

/// A split or merge: reflectors that replaced others.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SavedReplacement {
    /// What was done, for reports (`split "floor"`).
    pub what: String,
    /// Ids that were replaced.
    pub removed: Vec<u32>,
    /// The reflectors made, as made.
    pub created: Vec<SavedReflector>,
}

/// One reflector made by a split or merge.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SavedReflector {
    /// The reflector as made.
    pub reflector: Reflector,
    /// The region it was fitted to, when it came from an extraction (for re-fitting).
    pub region: Option<SavedRegion>,
}

/// A region's points and reflective area.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SavedRegion {
    /// World-space vertices of the region's polygons.
    pub points: Vec<DVec3>,
    /// Reflective area, square metres.
    pub reflective_area: f64,
}

impl EditsFile {
    /// An empty record of the current format and version.
    pub fn new() -> Self {
        Self {
            format: EDITS_FORMAT_NAME.to_owned(),
            version: EDITS_FORMAT_VERSION,
            edited: Vec::new(),
            replacements: Vec::new(),
        }
    }

    /// Parses an edits file, checking its format name and version.
    ///
    /// # Errors
    /// A message saying what is wrong (not JSON, another format or version).
    pub fn from_json_str(text: &str) -> Result<Self, String> {
        let file: EditsFile = serde_json::from_str(text).map_err(|e| e.to_string())?;
        if file.format != EDITS_FORMAT_NAME || file.version != EDITS_FORMAT_VERSION {
            return Err(format!(
                "`format` {:?} version {} is not {EDITS_FORMAT_NAME:?} version {EDITS_FORMAT_VERSION}",
                file.format, file.version
            ));
        }
        Ok(file)
    }

    /// The file's text.
    ///
    /// # Errors
    /// When a number cannot be written as JSON (a non-finite coordinate).
    pub fn to_json_string(&self) -> Result<String, String> {
        serde_json::to_string_pretty(self).map_err(|e| e.to_string())
    }
}

impl Default for EditsFile {
    fn default() -> Self {
        Self::new()
    }
}

/// Where the edits of the set at `set_path` are kept: `.json` becomes `.edits.json`.
pub fn edits_path(set_path: &Path) -> PathBuf {
    let name = set_path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let stem = name.strip_suffix(".json").unwrap_or(&name);
    set_path.with_file_name(format!("{stem}.edits.json"))
}
