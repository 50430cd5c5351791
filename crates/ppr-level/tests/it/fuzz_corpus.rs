//! The `gltf_loader` fuzz target's committed corpus and crash reproducers, replayed through
//! the same entry point (`load_scene_from_bytes` with textures and the fuzzer's 2^20 placed triangles at
//! most, then `Level::from_scene`),
//! external buffers resolved in an empty folder: each input is refused or read without a
//! panic, within a bound on the bytes it allocates.

#[path = "../../../../fuzz/replay/corpus.rs"]
mod corpus;

use ppr_level::{Level, LoadParams, load_scene_from_bytes};

/// What one input may allocate in all: the `-malloc_limit_mb` the fuzzer ran under.
const MAX_BYTES: u64 = 512 << 20;

#[test]
fn every_committed_gltf_input_loads_or_is_refused_in_bounded_work() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fuzz.glb");
    let seen = corpus::replay(
        "gltf_loader",
        |_| MAX_BYTES,
        |bytes| {
            let params = LoadParams { max_triangles: 1 << 20, ..LoadParams::render() };
            load_scene_from_bytes(&path, bytes, dir.path(), &params)
                .and_then(|scene| Level::from_scene(&scene))
                .is_ok()
        },
    );
    // The corpus keeps real levels (the demo room, the shared small scene): some load.
    assert!(
        seen.accepted > 0 && seen.accepted < seen.total,
        "{seen:?}: some inputs are loaded, some refused"
    );
    assert!(seen.most_allocated > 0, "{seen:?}: the allocation meter counted nothing");
}
