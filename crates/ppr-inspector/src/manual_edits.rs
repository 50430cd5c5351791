//! The record of what the user changed by hand, and how it is carried over to a fresh
//! extraction: the extractor's (`ppr_extract::manual_edits`), so that `ppr-extract` and the
//! inspector re-apply edits alike; this adapts it to the inspector's [`Document`].

use crate::document::Document;
use crate::error::EditError;

use ppr_extract::manual_edits::EditedSet;
pub use ppr_extract::manual_edits::{CarryReport, ManualEdits, Replacement};

/// The fresh extraction `fresh` with the manual edits of `current` applied where their ids
/// are still produced. Occluder lists are recomputed; the result is validated.
///
/// # Errors
/// [`EditError`] when the combined set breaks an invariant (nothing is applied then).
pub fn carry_edits(current: &Document, fresh: Document) -> Result<(Document, CarryReport), EditError> {
    let fresh = EditedSet { set: fresh.set, regions: fresh.regions, edits: fresh.edits };
    let (out, report) =
        ppr_extract::manual_edits::carry_edits(&current.set, &current.regions, &current.edits, fresh)?;
    let doc = Document { set: out.set, regions: out.regions, edits: out.edits, revision: 0 };
    Ok((doc.renumbered(), report))
}
