//! Fuzz target: any bytes as a `.glb` or `.gltf` file through `ppr-level`'s loader, as a
//! renderer loads it (textures decoded) and then flattened to the extractor's `Level`.
//! External buffers and images resolve in an empty folder, so nothing outside it is read.

#![no_main]

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use ppr_level::{Level, LoadParams, load_scene_from_bytes};

/// An empty folder that stands for the level's folder: relative URIs find nothing there.
fn empty_dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("ppr-fuzz-empty-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("the temp folder is writable");
        dir
    })
}

/// The most triangles a fuzzed scene may place: a level of this size stays well inside the
/// `-malloc_limit_mb=512` the fuzzer runs under (`LoadParams::max_triangles`).
const MAX_TRIANGLES: usize = 1 << 20;

fuzz_target!(|data: &[u8]| {
    let path = empty_dir().join("fuzz.glb");
    let params = LoadParams { max_triangles: MAX_TRIANGLES, ..LoadParams::render() };
    if let Ok(scene) = load_scene_from_bytes(&path, data, empty_dir(), &params) {
        let _ = Level::from_scene(&scene);
    }
});
