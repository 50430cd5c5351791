//! The record of manual edits saved beside a set (`room.ppr.json` → `room.ppr.edits.json`),
//! so that re-extracting after the set is reopened still keeps the artist's edits. The set
//! file stays what a game loads; this file is the inspector's own.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::DVec3;
use ppr_format::{Reflector, ReflectorSet};
use serde::{Deserialize, Serialize};

use crate::document::ReflectorRegion;
use crate::error::InspectorError;
use crate::manual_edits::{ManualEdits, Replacement};

/// The `format` field of an edits file.
pub const FORMAT: &str = "ppr-inspector-edits";
/// The version this build reads and writes.
pub const VERSION: u32 = 1;

#[derive(Serialize, Deserialize)]
struct EditsFile {
    format: String,
    version: u32,
    /// Ids whose properties or rectangle were edited by hand.
    edited: Vec<u32>,
    /// Splits and merges, in order.
    replacements: Vec<SavedReplacement>,
}

#[derive(Serialize, Deserialize)]
struct SavedReplacement {
    what: String,
    removed: Vec<u32>,
    created: Vec<SavedReflector>,
}

#[derive(Serialize, Deserialize)]
struct SavedReflector {
    reflector: Reflector,
    /// The region it was fitted to, when it came from an extraction (for re-fitting).
    region: Option<SavedRegion>,
}

#[derive(Serialize, Deserialize)]
struct SavedRegion {
    points: Vec<DVec3>,
    reflective_area: f64,
}

/// Where the edits of the set at `set_path` are kept: `.json` becomes `.edits.json`.
pub fn edits_path(set_path: &Path) -> PathBuf {
    let name = set_path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let stem = name.strip_suffix(".json").unwrap_or(&name);
    set_path.with_file_name(format!("{stem}.edits.json"))
}

/// Writes the edits beside the set (atomically), or removes a stale file when there are none.
///
/// # Errors
/// [`InspectorError::EditsFile`] naming the file when it cannot be written or removed.
pub fn save(set_path: &Path, edits: &ManualEdits) -> Result<(), InspectorError> {
    let path = edits_path(set_path);
    let fail = |reason: String| InspectorError::EditsFile { path: path.clone(), reason };
    if edits.is_empty() {
        return match std::fs::remove_file(&path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(fail(format!("cannot remove: {e}"))),
            _ => Ok(()),
        };
    }
    let file = EditsFile {
        format: FORMAT.to_owned(),
        version: VERSION,
        edited: edits.edited.iter().copied().collect(),
        replacements: edits
            .replacements
            .iter()
            .map(|r| SavedReplacement {
                what: r.what.clone(),
                removed: r.removed.clone(),
                created: r
                    .created
                    .iter()
                    .map(|(reflector, region)| SavedReflector {
                        reflector: reflector.clone(),
                        region: region.as_ref().map(|g| SavedRegion {
                            points: g.points.clone(),
                            reflective_area: g.reflective_area,
                        }),
                    })
                    .collect(),
            })
            .collect(),
    };
    let text = serde_json::to_string_pretty(&file).map_err(|e| fail(e.to_string()))?;
    ppr_format::write_atomically(&path, text.as_bytes()).map_err(|e| fail(format!("cannot write: {e}")))
}

/// Reads the edits kept beside the set at `set_path`: `None` when there is no such file.
/// Edited ids that neither the set nor a split or merge has are dropped (the set was
/// changed by another tool since).
///
/// # Errors
/// [`InspectorError::EditsFile`] naming the file and what is wrong (unreadable, not JSON,
/// another format or version, an invalid reflector).
pub fn load(set_path: &Path, set: &ReflectorSet) -> Result<Option<ManualEdits>, InspectorError> {
    let path = edits_path(set_path);
    let fail = |reason: String| InspectorError::EditsFile { path: path.clone(), reason };
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(fail(format!("cannot read: {e}"))),
    };
    let file: EditsFile = serde_json::from_str(&text).map_err(|e| fail(e.to_string()))?;
    if file.format != FORMAT || file.version != VERSION {
        return Err(fail(format!(
            "`format` {:?} version {} is not {FORMAT:?} version {VERSION}",
            file.format, file.version
        )));
    }
    let mut replacements = Vec::with_capacity(file.replacements.len());
    for (i, r) in file.replacements.into_iter().enumerate() {
        let mut created = Vec::with_capacity(r.created.len());
        for (j, c) in r.created.into_iter().enumerate() {
            let mut one = ReflectorSet::new(set.source.path.clone());
            one.reflectors.push(Reflector { occluders: Vec::new(), ..c.reflector.clone() });
            one.validate().map_err(|e| fail(format!("`replacements[{i}].created[{j}]`: {e}")))?;
            let region = c
                .region
                .map(|g| Arc::new(ReflectorRegion { points: g.points, reflective_area: g.reflective_area }));
            created.push((c.reflector, region));
        }
        replacements.push(Replacement { what: r.what, removed: r.removed, created });
    }
    let created: BTreeSet<u32> =
        replacements.iter().flat_map(|r| r.created.iter().map(|(c, _)| c.id)).collect();
    let edited =
        file.edited.into_iter().filter(|id| set.by_id(*id).is_some() || created.contains(id)).collect();
    Ok(Some(ManualEdits { edited, replacements }))
}
