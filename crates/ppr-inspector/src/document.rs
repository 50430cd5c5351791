//! The document the inspector edits: a reflector set, the regions its reflectors were
//! fitted to, and the record of manual edits; each state carries a revision number.

use std::sync::atomic::{AtomicU64, Ordering};

use ppr_extract::Extraction;
use ppr_extract::manual_edits::{EditedSet, ManualEdits};
use ppr_format::ReflectorSet;

pub use ppr_extract::manual_edits::{ReflectorRegion, RegionTable};

/// One state of the edited set. States are values: the edit history keeps them whole.
#[derive(Clone, Debug, PartialEq)]
pub struct Document {
    /// The reflectors (always valid: every change is validated before it is applied).
    pub set: ReflectorSet,
    /// Regions of the reflectors that came from an extraction (none for a loaded file).
    pub regions: RegionTable,
    /// What the user changed by hand, replayed after a re-extraction.
    pub edits: ManualEdits,
    /// Unique number of this state (a saved revision tells whether there are unsaved changes).
    pub revision: u64,
}

static NEXT_REVISION: AtomicU64 = AtomicU64::new(1);

/// A revision number never handed out before.
pub fn next_revision() -> u64 {
    NEXT_REVISION.fetch_add(1, Ordering::Relaxed)
}

impl Document {
    /// A document for a set loaded from a file: no regions, no edits.
    pub fn from_set(set: ReflectorSet) -> Self {
        Self { set, regions: RegionTable::new(), edits: ManualEdits::default(), revision: next_revision() }
    }

    /// A document for a fresh extraction: the set and each reflector's region.
    pub fn from_extraction(x: &Extraction) -> Self {
        let fresh = EditedSet::from_extraction(x);
        Self { set: fresh.set, regions: fresh.regions, edits: fresh.edits, revision: next_revision() }
    }

    /// The same content under a new revision number (after a change).
    pub fn renumbered(mut self) -> Self {
        self.revision = next_revision();
        self
    }

    /// Index of the reflector with `id` in the set.
    pub fn index_of(&self, id: u32) -> Option<usize> {
        self.set.reflectors.iter().position(|r| r.id == id)
    }
}
