//! Reading and writing the manual-edits file beside a set (`room.ppr.edits.json`, format in
//! `ppr_format::edits`), and re-applying it to a fresh extraction written over that set.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use ppr_format::edits::{EditsFile, SavedReflector, SavedRegion, SavedReplacement, edits_path};
use ppr_format::{FormatError, Reflector, ReflectorSet};

use crate::manual_edits::{CarryReport, EditedSet, ManualEdits, ReflectorRegion, Replacement, carry_edits};

/// Why the edits beside a set could not be read, written or applied.
#[derive(Debug, thiserror::Error)]
pub enum EditsError {
    /// The edits file cannot be read, written or removed, or is not a valid edits file.
    #[error("{}: {reason}", path.display())]
    File {
        /// The edits file.
        path: PathBuf,
        /// What went wrong.
        reason: String,
    },
    /// There is an edits file but the set whose reflectors it names cannot be read.
    #[error("{}: the manual edits name reflectors of {}, which cannot be read: {source}", edits.display(), set.display())]
    SetUnreadable {
        /// The edits file.
        edits: PathBuf,
        /// The set it belongs to.
        set: PathBuf,
        /// Why the set cannot be read.
        source: Box<FormatError>,
    },
    /// The fresh set with the edits applied breaks an invariant of the format.
    #[error("{}: the fresh set with these manual edits applied is invalid: {source}", edits.display())]
    Refused {
        /// The edits file.
        edits: PathBuf,
        /// The format's complaint.
        source: Box<FormatError>,
    },
}

/// Writes `edits` beside the set at `set_path` (atomically), or removes a stale file when
/// there are none.
///
/// # Errors
/// [`EditsError::File`] naming the file when it cannot be written or removed.
pub fn save_edits(set_path: &Path, edits: &ManualEdits) -> Result<(), EditsError> {
    let path = edits_path(set_path);
    let fail = |reason: String| EditsError::File { path: path.clone(), reason };
    if edits.is_empty() {
        return match std::fs::remove_file(&path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(fail(format!("cannot remove: {e}"))),
            _ => Ok(()),
        };
    }
    let text = EditsFile::from(edits).to_json_string().map_err(fail)?;
    ppr_format::write_atomically(&path, text.as_bytes()).map_err(|e| fail(format!("cannot write: {e}")))
}

/// Reads the edits kept beside the set at `set_path`: `None` when there is no such file.
/// Edited ids that neither `set` nor a split or merge has are dropped (the set was changed
/// by another tool since).
///
/// # Errors
/// [`EditsError::File`] naming the file and what is wrong (unreadable, not JSON, another
/// format or version, an invalid reflector).
pub fn load_edits(set_path: &Path, set: &ReflectorSet) -> Result<Option<ManualEdits>, EditsError> {
    let path = edits_path(set_path);
    let fail = |reason: String| EditsError::File { path: path.clone(), reason };
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(fail(format!("cannot read: {e}"))),
    };
    parse_edits(&path, &text, set).map(Some)
}

/// Parses the text of an edits file (`path` only names it in errors) against `set`, as
/// [`load_edits`] does once it has read the file.
///
/// # Errors
/// [`EditsError::File`] naming `path` and what is wrong (not JSON, another format or
/// version, an invalid reflector).
pub fn parse_edits(path: &Path, text: &str, set: &ReflectorSet) -> Result<ManualEdits, EditsError> {
    let fail = |reason: String| EditsError::File { path: path.to_owned(), reason };
    let file = EditsFile::from_json_str(text).map_err(fail)?;
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
    Ok(ManualEdits { edited, replacements })
}

impl From<&ManualEdits> for EditsFile {
    fn from(edits: &ManualEdits) -> Self {
        EditsFile {
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
            ..EditsFile::new()
        }
    }
}

/// The manual edits of the set at `set_path` applied to `fresh`, the extraction about to
/// be written over it, with what was and was not applied; `fresh` unchanged and no report
/// when there is no edits file beside it.
///
/// # Errors
/// [`EditsError`] naming the file when the edits file or its set cannot be read, or when
/// the result is invalid; the caller should then write nothing.
pub fn reapply_edits(
    set_path: &Path,
    fresh: EditedSet,
) -> Result<(EditedSet, Option<CarryReport>), EditsError> {
    let edits_file = edits_path(set_path);
    if !edits_file.exists() {
        return Ok((fresh, None));
    }
    let current = ReflectorSet::load(set_path).map_err(|source| EditsError::SetUnreadable {
        edits: edits_file.clone(),
        set: set_path.to_owned(),
        source: Box::new(source),
    })?;
    let Some(edits) = load_edits(set_path, &current)? else {
        return Ok((fresh, None));
    };
    let (carried, report) = carry_edits(&current, &Default::default(), &edits, fresh)
        .map_err(|source| EditsError::Refused { edits: edits_file, source: Box::new(source) })?;
    Ok((carried, Some(report)))
}

/// Copies the set at `set_path` and its edits file to `<stem>.previous.json` and
/// `<stem>.previous.edits.json` beside it (a set the inspector can open), returning the
/// copy of the set.
///
/// # Errors
/// [`EditsError::File`] naming the file that could not be copied.
pub fn keep_previous(set_path: &Path) -> Result<PathBuf, EditsError> {
    let name = set_path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let stem = name.strip_suffix(".json").unwrap_or(&name);
    let previous = set_path.with_file_name(format!("{stem}.previous.json"));
    for (from, to) in [(set_path.to_owned(), previous.clone()), (edits_path(set_path), edits_path(&previous))]
    {
        if from.exists() {
            std::fs::copy(&from, &to).map_err(|e| EditsError::File {
                path: to.clone(),
                reason: format!("cannot copy {}: {e}", from.display()),
            })?;
        }
    }
    Ok(previous)
}
