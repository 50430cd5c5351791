//! The record of what an artist changed by hand in a set (in the inspector), and how it is
//! carried over to a fresh extraction: matched by stable id (`stable_id.rs`); an edit whose
//! ids are no longer produced is reported by name, never dropped silently. The inspector
//! and `ppr-extract` both re-extract through [`carry_edits`].

use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;

use glam::DVec3;
use ppr_format::{FormatError, Reflector, ReflectorSet};

use crate::occluders::{OccluderRule, ranked_occluder_lists};
use crate::{ExtractParams, Extraction};

/// The reflective region a reflector encloses, as the extractor found it.
#[derive(Clone, Debug, PartialEq)]
pub struct ReflectorRegion {
    /// World-space vertices of the region's polygons (their outline is not kept).
    pub points: Vec<DVec3>,
    /// Reflective area, square metres (coverage × rectangle area at extraction).
    pub reflective_area: f64,
}

/// Regions by reflector id; cheap to clone (shared values).
pub type RegionTable = BTreeMap<u32, Arc<ReflectorRegion>>;

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

    /// How many edits there are (edited reflectors plus splits and merges).
    pub fn len(&self) -> usize {
        self.edited.len() + self.replacements.len()
    }

    /// Ids of the reflectors made by splits and merges.
    pub fn created_ids(&self) -> BTreeSet<u32> {
        self.replacements.iter().flat_map(|r| r.created.iter().map(|(c, _)| c.id)).collect()
    }
}

/// A set with the regions of its reflectors and its manual edits.
#[derive(Clone, Debug, PartialEq)]
pub struct EditedSet {
    /// The reflectors.
    pub set: ReflectorSet,
    /// Regions of the reflectors that came from an extraction.
    pub regions: RegionTable,
    /// What was changed by hand.
    pub edits: ManualEdits,
}

impl EditedSet {
    /// A fresh extraction: the set and each reflector's region, no edits.
    pub fn from_extraction(x: &Extraction) -> Self {
        let regions = x
            .set
            .reflectors
            .iter()
            .zip(&x.regions)
            .map(|(r, points)| {
                let region =
                    ReflectorRegion { points: points.clone(), reflective_area: r.coverage * r.area() };
                (r.id, Arc::new(region))
            })
            .collect();
        Self { set: x.set.clone(), regions, edits: ManualEdits::default() }
    }
}

/// What happened to the manual edits over a re-extraction.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CarryReport {
    /// Edits applied to the fresh set.
    pub kept: Vec<String>,
    /// Edits not applied because an id they need is no longer produced.
    pub not_applicable: Vec<String>,
}

/// The fresh extraction `fresh` with the manual edits `edits` of the set `current` (and its
/// `regions`) applied where their ids are still produced. Occluder lists are recomputed;
/// the result is validated.
///
/// # Errors
/// The format's error when the combined set breaks an invariant (nothing is applied then).
pub fn carry_edits(
    current: &ReflectorSet,
    regions: &RegionTable,
    edits: &ManualEdits,
    fresh: EditedSet,
) -> Result<(EditedSet, CarryReport), FormatError> {
    let mut out = fresh;
    out.edits = ManualEdits::default();
    let mut report = CarryReport::default();
    let created = edits.created_ids();
    let index_of = |set: &ReflectorSet, id: u32| set.reflectors.iter().position(|r| r.id == id);

    for &id in &edits.edited {
        if created.contains(&id) {
            continue; // carried with its split or merge
        }
        let Some(user) = current.by_id(id) else {
            continue; // replaced since: the replacement carries it
        };
        match index_of(&out.set, id) {
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

    for rep in &edits.replacements {
        let missing: Vec<u32> =
            rep.removed.iter().copied().filter(|&id| index_of(&out.set, id).is_none()).collect();
        if !missing.is_empty() {
            report.not_applicable.push(format!(
                "{} no longer applies: id {} is not produced any more",
                rep.what,
                missing.iter().map(u32::to_string).collect::<Vec<_>>().join(", ")
            ));
            continue;
        }
        let at = rep
            .removed
            .iter()
            .filter_map(|&id| index_of(&out.set, id))
            .min()
            .unwrap_or(out.set.reflectors.len());
        let group = out.set.reflectors.get(at).map_or(0, |r| r.parallel_group);
        out.set.reflectors.retain(|r| !rep.removed.contains(&r.id));
        for id in &rep.removed {
            out.regions.remove(id);
        }
        let mut carried = rep.clone();
        for (k, (made, made_region)) in rep.created.iter().enumerate() {
            let mut r = current.by_id(made.id).cloned().unwrap_or_else(|| made.clone());
            let region = regions.get(&made.id).cloned().or_else(|| made_region.clone());
            if index_of(&out.set, r.id).is_some() {
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
        recompute_occluders(&mut out.set);
    }
    out.set.validate()?;
    Ok((out, report))
}

/// Recomputes every occluder list of `set` with the extractor's rule and the tolerances it
/// recorded in `set.extractor.params` (its defaults for any that is missing).
pub fn recompute_occluders(set: &mut ReflectorSet) {
    let (lo, hi) = set
        .reflectors
        .iter()
        .flat_map(|r| r.corners())
        .fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        });
    let origin = if lo.x <= hi.x { (lo + hi) * 0.5 } else { DVec3::ZERO };
    let params = ExtractParams::from_record(&set.extractor.params);
    let rule = OccluderRule {
        epsilon: params.distance_tolerance_m,
        reach: params.reach_m.unwrap_or(f64::INFINITY),
        max_per_list: params.max_occluders,
    };
    let lists = ranked_occluder_lists(&set.reflectors, origin, &rule);
    for (r, list) in set.reflectors.iter_mut().zip(lists.lists) {
        r.occluders = list;
    }
}

/// `count` ids unused in `set`, above the largest one in use (31-bit like the extractor's).
pub fn fresh_ids(set: &ReflectorSet, count: usize) -> Vec<u32> {
    let used: BTreeSet<u32> = set.reflectors.iter().map(|r| r.id).collect();
    let mut next = set.next_id() & 0x7FFF_FFFF;
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        if !used.contains(&next) && !out.contains(&next) {
            out.push(next);
        }
        next = (next + 1) & 0x7FFF_FFFF;
    }
    out
}
