//! Edits as commands: each takes a document and returns the edited one, validated with
//! `ReflectorSet::validate` before the inspector applies it (a refused edit changes nothing).

use std::sync::Arc;

use ppr_format::{ReflectorKind, ReflectorSet};

use crate::document::Document;
use crate::error::EditError;
use crate::manual_edits::Replacement;
use crate::reflector_geometry::{self, Placement, SplitAxis};
use crate::set_tolerances::{SetTolerances, fresh_ids};

/// One edit of the reflector set.
#[derive(Clone, Debug, PartialEq)]
pub enum EditCommand {
    /// Switch a reflector on or off.
    SetEnabled {
        /// Reflector id.
        id: u32,
        /// New state.
        enabled: bool,
    },
    /// Change how a reflector is shaded.
    SetKind {
        /// Reflector id.
        id: u32,
        /// New kind.
        kind: ReflectorKind,
    },
    /// Set a reflector's perceptual roughness (0 mirror to 1 fully rough).
    SetRoughness {
        /// Reflector id.
        id: u32,
        /// New roughness (the document refuses values outside `[0, 1]`).
        roughness: f64,
    },
    /// Rename a reflector.
    Rename {
        /// Reflector id.
        id: u32,
        /// New name.
        name: String,
    },
    /// Move, rotate or resize a rectangle within its plane.
    Place {
        /// Reflector id.
        id: u32,
        /// New placement.
        placement: Placement,
    },
    /// Cut a rectangle in two.
    Split {
        /// Reflector id.
        id: u32,
        /// Which axis the cut goes across.
        axis: SplitAxis,
        /// Where, as a fraction of the length along that axis (0 < at < 1).
        at: f64,
    },
    /// Make one rectangle of two coplanar ones.
    Merge {
        /// The reflector whose kind, frame and settings the result keeps.
        id: u32,
        /// The one merged into it.
        other: u32,
    },
    /// Fit the rectangle to its region again (minimum area).
    Refit {
        /// Reflector id.
        id: u32,
    },
}

/// An applied command: the new document and what to select.
#[derive(Clone, Debug)]
pub struct EditOutcome {
    /// The edited document (validated, with a new revision).
    pub doc: Document,
    /// The reflector to select afterwards.
    pub select: Option<u32>,
}

fn name_of(set: &ReflectorSet, id: u32) -> String {
    set.by_id(id).map_or_else(|| format!("#{id}"), |r| format!("{:?}", r.name))
}

impl EditCommand {
    /// A short description for the history and messages (`rename "floor"`).
    pub fn describe(&self, set: &ReflectorSet) -> String {
        match self {
            Self::SetEnabled { id, enabled } => {
                format!("{} {}", if *enabled { "enable" } else { "disable" }, name_of(set, *id))
            }
            Self::SetKind { id, kind } => format!("make {} {kind}", name_of(set, *id)),
            Self::SetRoughness { id, roughness } => {
                format!("set the roughness of {} to {roughness:.3}", name_of(set, *id))
            }
            Self::Rename { id, name } => format!("rename {} to {name:?}", name_of(set, *id)),
            Self::Place { id, .. } => format!("move/resize {}", name_of(set, *id)),
            Self::Split { id, axis, .. } => format!("split {} across {axis:?}", name_of(set, *id)),
            Self::Merge { id, other } => format!("merge {} with {}", name_of(set, *id), name_of(set, *other)),
            Self::Refit { id } => format!("re-fit {}", name_of(set, *id)),
        }
    }

    /// The reflector the command is about.
    pub fn target(&self) -> u32 {
        match self {
            Self::SetEnabled { id, .. }
            | Self::SetKind { id, .. }
            | Self::SetRoughness { id, .. }
            | Self::Rename { id, .. }
            | Self::Place { id, .. }
            | Self::Split { id, .. }
            | Self::Merge { id, .. }
            | Self::Refit { id } => *id,
        }
    }

    /// Applies the command to `doc`, returning the edited document.
    ///
    /// # Errors
    /// [`EditError`] when a reflector is unknown, the operation is impossible, or the
    /// result breaks an invariant of the format.
    pub fn apply(&self, doc: &Document) -> Result<EditOutcome, EditError> {
        let id = self.target();
        let index = doc.index_of(id).ok_or(EditError::UnknownId(id))?;
        let mut out = doc.clone();
        let tolerances = SetTolerances::of(&doc.set);
        let mut select = Some(id);
        let mut geometry_changed = false;
        match self {
            Self::SetEnabled { enabled, .. } => out.set.reflectors[index].enabled = *enabled,
            Self::SetKind { kind, .. } => out.set.reflectors[index].kind = *kind,
            Self::SetRoughness { roughness, .. } => out.set.reflectors[index].roughness = *roughness,
            Self::Rename { name, .. } => out.set.reflectors[index].name = name.clone(),
            Self::Place { placement, .. } => {
                let r = &doc.set.reflectors[index];
                let area = reflector_geometry::reflective_area(r, doc.regions.get(&id).map(Arc::as_ref));
                let mut placed = reflector_geometry::place(r, placement);
                placed.coverage = reflector_geometry::coverage_of(area, &placed);
                out.set.reflectors[index] = placed;
                geometry_changed = true;
            }
            Self::Refit { .. } => {
                let r = &doc.set.reflectors[index];
                out.set.reflectors[index] =
                    reflector_geometry::refit(r, doc.regions.get(&id).map(Arc::as_ref))?;
                geometry_changed = true;
            }
            Self::Split { axis, at, .. } => {
                let r = &doc.set.reflectors[index];
                let parts = reflector_geometry::split(r, doc.regions.get(&id).map(Arc::as_ref), *axis, *at)?;
                let ids = fresh_ids(&doc.set, 2);
                out.set.reflectors.remove(index);
                out.regions.remove(&id);
                let mut created = Vec::new();
                for (k, (mut part, region)) in parts.into_iter().enumerate() {
                    part.id = ids[k];
                    let region = region.map(Arc::new);
                    if let Some(g) = &region {
                        out.regions.insert(part.id, g.clone());
                    }
                    out.set.reflectors.insert(index + k, part.clone());
                    created.push((part, region));
                }
                out.edits.edited.remove(&id);
                out.edits.replacements.push(Replacement {
                    what: self.describe(&doc.set),
                    removed: vec![id],
                    created,
                });
                select = ids.first().copied();
                geometry_changed = true;
            }
            Self::Merge { other, .. } => {
                let other_index = doc.index_of(*other).ok_or(EditError::UnknownId(*other))?;
                let (a, b) = (&doc.set.reflectors[index], &doc.set.reflectors[other_index]);
                let (mut merged, region) = reflector_geometry::merge(
                    a,
                    doc.regions.get(&id).map(Arc::as_ref),
                    b,
                    doc.regions.get(other).map(Arc::as_ref),
                    tolerances.coplanar(),
                )?;
                merged.id = fresh_ids(&doc.set, 1).first().copied().ok_or(EditError::UnknownId(id))?;
                let region = region.map(Arc::new);
                out.set.reflectors[index] = merged.clone();
                out.set.reflectors.remove(other_index);
                out.regions.remove(&id);
                out.regions.remove(other);
                if let Some(g) = &region {
                    out.regions.insert(merged.id, g.clone());
                }
                out.edits.edited.remove(&id);
                out.edits.edited.remove(other);
                out.edits.replacements.push(Replacement {
                    what: self.describe(&doc.set),
                    removed: vec![id, *other],
                    created: vec![(merged.clone(), region)],
                });
                select = Some(merged.id);
                geometry_changed = true;
            }
        }
        if !matches!(self, Self::Split { .. } | Self::Merge { .. }) {
            out.edits.edited.insert(id);
        }
        if geometry_changed {
            // Validate the geometry before the occluder BVH sees it (it rejects NaN), with
            // the old lists out of the way (their indices may be stale after a split or merge).
            for r in &mut out.set.reflectors {
                r.occluders.clear();
            }
            out.set.validate()?;
            tolerances.recompute_occluders(&mut out.set);
        }
        out.set.validate()?;
        Ok(EditOutcome { doc: out.renumbered(), select })
    }
}
