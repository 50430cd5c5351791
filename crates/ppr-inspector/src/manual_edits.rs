//! The record of what the user changed by hand, and how it is carried over to a fresh
//! extraction: matched by stable id; an edit whose ids are no longer produced is reported.

use std::collections::BTreeSet;
use std::sync::Arc;

use ppr_format::Reflector;

use crate::document::{Document, ReflectorRegion};
use crate::error::EditError;
use crate::set_tolerances::{SetTolerances, fresh_ids};

/// Reflectors that replaced others (a split or a merge).
#[derive(Clone, Debug, PartialEq)]
pub struct Replacement {
    /// What was done, for reports (`split "floor"`).
    pub what: String,
    /// Ids that were replaced.
    pub removed: Vec<u32>,
    /// The reflectors made, as made (later edits to them are read from the current set).
    pub created: Vec<(Reflector, Option<Arc<ReflectorRegion>>)>,
}

/// Everything changed by hand since the set was extracted or loaded.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ManualEdits {
    /// Ids whose properties or rectangle were edited (the current set holds the result).
    pub edited: BTreeSet<u32>,
    /// Splits and merges, in order.
    pub replacements: Vec<Replacement>,
}

impl ManualEdits {
    /// Whether nothing was changed by hand.
    pub fn is_empty(&self) -> bool {
        self.edited.is_empty() && self.replacements.is_empty()
    }

    fn created_ids(&self) -> BTreeSet<u32> {
        self.replacements.iter().flat_map(|r| r.created.iter().map(|(c, _)| c.id)).collect()
    }
}

/// What happened to the manual edits over a re-extraction.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CarryReport {
    /// Edits applied to the fresh set.
    pub kept: Vec<String>,
    /// Edits dropped because an id they need is no longer produced.
    pub not_applicable: Vec<String>,
}

/// The fresh extraction `fresh` with the manual edits of `current` applied where their ids
/// are still produced. Occluder lists are recomputed; the result is validated.
///
/// # Errors
/// [`EditError`] when the combined set breaks an invariant (nothing is applied then).
pub fn carry_edits(current: &Document, fresh: Document) -> Result<(Document, CarryReport), EditError> {
    let mut out = fresh;
    out.edits = ManualEdits::default();
    let mut report = CarryReport::default();
    let created = current.edits.created_ids();

    for &id in &current.edits.edited {
        if created.contains(&id) {
            continue; // carried with its split or merge
        }
        let Some(user) = current.set.by_id(id) else {
            continue; // replaced since: the replacement carries it
        };
        match out.index_of(id) {
            Some(i) => {
                let fresh_r = &out.set.reflectors[i];
                let kept = Reflector {
                    parallel_group: fresh_r.parallel_group,
                    source: fresh_r.source.clone(),
                    occluders: Vec::new(),
                    ..user.clone()
                };
                out.set.reflectors[i] = kept;
                out.edits.edited.insert(id);
                report.kept.push(format!("edit of {:?} (id {id})", user.name));
            }
            None => report.not_applicable.push(format!(
                "edit of {:?} (id {id}) no longer applies: the extractor does not produce id {id} any more",
                user.name
            )),
        }
    }

    for rep in &current.edits.replacements {
        let missing: Vec<u32> =
            rep.removed.iter().copied().filter(|&id| out.index_of(id).is_none()).collect();
        if !missing.is_empty() {
            report.not_applicable.push(format!(
                "{} no longer applies: id {} is not produced any more",
                rep.what,
                missing.iter().map(u32::to_string).collect::<Vec<_>>().join(", ")
            ));
            continue;
        }
        let at =
            rep.removed.iter().filter_map(|&id| out.index_of(id)).min().unwrap_or(out.set.reflectors.len());
        let group = out.set.reflectors.get(at).map_or(0, |r| r.parallel_group);
        out.set.reflectors.retain(|r| !rep.removed.contains(&r.id));
        for id in &rep.removed {
            out.regions.remove(id);
        }
        let mut carried = rep.clone();
        for (k, (made, made_region)) in rep.created.iter().enumerate() {
            let mut r = current.set.by_id(made.id).cloned().unwrap_or_else(|| made.clone());
            let region = current.regions.get(&made.id).cloned().or_else(|| made_region.clone());
            if out.index_of(r.id).is_some() {
                let new_id = fresh_ids(&out.set, 1).first().copied().unwrap_or(r.id);
                report
                    .kept
                    .push(format!("{}: id {} was taken by the extractor, now {new_id}", rep.what, r.id));
                r.id = new_id;
                carried.created[k].0.id = new_id;
            }
            r.parallel_group = group;
            r.occluders = Vec::new();
            if let Some(region) = region {
                out.regions.insert(r.id, region);
            }
            let pos = (at + k).min(out.set.reflectors.len());
            out.set.reflectors.insert(pos, r);
        }
        report.kept.push(rep.what.clone());
        out.edits.replacements.push(carried);
    }

    if !out.edits.is_empty() {
        for r in &mut out.set.reflectors {
            r.occluders.clear();
        }
        out.set.validate()?; // occluder lists are emptied above: checks the geometry first
        SetTolerances::of(&out.set).recompute_occluders(&mut out.set);
    }
    out.set.validate()?;
    Ok((out.renumbered(), report))
}
