//! Every shared scene (`../shared/scenes/`) opens in the walkthrough as in the extractor:
//! both read it through `ppr-level`.

use std::path::Path;

use ppr_walkthrough::gltf_level::LevelData;

#[test]
fn every_shared_scene_opens() {
    let files =
        ppr_level::shared_scene_files(Path::new(env!("CARGO_MANIFEST_DIR")), 5).expect("shared scenes");
    for path in files {
        let level = LevelData::load(&path).unwrap_or_else(|e| panic!("{}: {e:#}", path.display()));
        let drawn: usize = level
            .instances
            .iter()
            .map(|i| level.meshes[i.mesh].iter().map(|p| p.indices.len() / 3).sum::<usize>())
            .sum();
        let extracted = ppr_extract::load_level(&path).expect("the extractor's view");
        assert_eq!(drawn, extracted.triangles.len(), "{}", path.display());
        assert!(level.bounds().is_some(), "{}", path.display());
    }
}
