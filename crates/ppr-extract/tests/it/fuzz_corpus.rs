//! The `edits_file` fuzz target's committed corpus and crash reproducers, replayed through
//! the same entry point (`edits_file::parse_edits` against an empty set): each input is
//! refused or read without a panic, allocating at most a fixed multiple of its size.

#[path = "../../../../fuzz/replay/corpus.rs"]
mod corpus;

use std::path::Path;

use ppr_extract::edits_file::parse_edits;
use ppr_format::ReflectorSet;

#[test]
fn every_committed_edits_input_parses_or_is_refused_in_bounded_work() {
    let set = ReflectorSet::new("room.glb");
    let seen = corpus::replay(
        "edits_file",
        |len| (1 << 20) + 64 * len as u64,
        |bytes| {
            std::str::from_utf8(bytes)
                .is_ok_and(|text| parse_edits(Path::new("room.ppr.edits.json"), text, &set).is_ok())
        },
    );
    assert!(
        seen.accepted > 0 && seen.accepted < seen.total,
        "{seen:?}: some inputs are parsed, some refused"
    );
    assert!(seen.most_allocated > 0, "{seen:?}: the allocation meter counted nothing");
}
