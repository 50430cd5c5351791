//! Every shared scene (`../shared/scenes/`) opens as a bench scene (drawn by the testbed,
//! extracted by the extractor, from one `ppr-level` read), as it does in `ppr-extract`.

use std::path::PathBuf;

use ppr_bench::scene::{BenchScene, SceneOptions, SceneSpec};

#[test]
fn every_shared_scene_opens() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = root.join("../shared/scenes");
    let files = ppr_level::level_files(&dir);
    assert!(files.len() >= 5, "the shared scenes are missing from {}: {files:?}", dir.display());
    for path in files {
        let spec = SceneSpec::parse(&path.to_string_lossy(), &root, &dir).expect("a glTF path");
        let scene = BenchScene::load(&spec, &SceneOptions::default())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let extracted = ppr_level::load_level(&path).expect("the extractor's view");
        assert_eq!(scene.level.triangle_count(), extracted.triangles.len(), "{}", path.display());
    }
}
