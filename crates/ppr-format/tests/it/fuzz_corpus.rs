//! The `reflector_set` fuzz target's committed corpus and crash reproducers, replayed
//! through the same entry point (`ReflectorSet::from_json_str`, then `to_json_string` for
//! a set that loads): each input is refused or read without a panic, allocating at most a
//! fixed multiple of its size, and a set that loads writes back.

#[path = "../../../../fuzz/replay/corpus.rs"]
mod corpus;

use ppr_format::ReflectorSet;

#[test]
fn every_committed_set_input_parses_or_is_refused_in_bounded_work() {
    let seen = corpus::replay(
        "reflector_set",
        |len| (1 << 20) + 64 * len as u64,
        |bytes| {
            let Ok(set) = std::str::from_utf8(bytes).map(ReflectorSet::from_json_str) else { return false };
            set.map(|set| set.to_json_string().expect("a set that loads writes back")).is_ok()
        },
    );
    assert!(
        seen.accepted > 0 && seen.accepted < seen.total,
        "{seen:?}: some inputs are parsed, some refused"
    );
    assert!(seen.most_allocated > 0, "{seen:?}: the allocation meter counted nothing");
}
