//! Every shared third-party scene (`../shared/scenes/`, see its README) finishes and gives
//! a valid set in which every rectangle encloses its region's vertices and lies in their
//! plane, with the material rule and with `--all-planar`.

use std::path::PathBuf;

use ppr_extract::{ExtractParams, extract, load_level};

use crate::checks::assert_encloses_regions;

/// The shared scenes folder; fails (never skips) when it is missing.
pub fn scenes_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    assert!(
        dir.join("README.md").is_file(),
        "the shared scenes are missing: looked for {} (the project's `shared/scenes/` beside the repository)",
        dir.display()
    );
    dir
}

const SCENES: [&str; 5] = [
    "collision-world.glb",
    "kitchen/kitchen.gltf",
    "pool_day_baked.glb",
    "small.glb",
    "fps_mine_sketch_compressed.glb",
];

#[test]
fn every_shared_scene_extracts_a_valid_enclosing_set() {
    let dir = scenes_dir();
    for name in SCENES {
        let level = load_level(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(!level.triangles.is_empty(), "{name}: no triangles");
        for (preset, params) in ExtractParams::presets() {
            let x = extract(&level, &params, &|_, _| {});
            // Near-planar merges may leave vertices up to half the error bound off the plane.
            let plane_tol = (3.0 * params.distance_tolerance_m).max(params.max_reflection_error_m / 2.0);
            assert_encloses_regions(&x, plane_tol, &format!("{name} ({preset})"));
            if preset == "all_planar" {
                assert!(!x.set.reflectors.is_empty(), "{name}: --all-planar finds no planar area");
            }
        }
    }
}

#[test]
fn scene_specifics() {
    let dir = scenes_dir();
    // One material for everything: nothing by material, plenty with --all-planar.
    let level = load_level(dir.join("collision-world.glb")).unwrap();
    assert!(extract(&level, &ExtractParams::default(), &|_, _| {}).set.reflectors.is_empty());
    // small.glb: KHR_materials_transmission gives transparent reflectors.
    let level = load_level(dir.join("small.glb")).unwrap();
    let x = extract(&level, &ExtractParams::default(), &|_, _| {});
    assert!(x.set.reflectors.iter().any(|r| r.kind == ppr_format::ReflectorKind::Transparent));
    // The kitchen: .gltf with an external buffer, 283 nodes; metal and glass candidates.
    let level = load_level(dir.join("kitchen/kitchen.gltf")).unwrap();
    assert!(level.triangles.len() > 50_000, "{}", level.triangles.len());
    let x = extract(&level, &ExtractParams::default(), &|_, _| {});
    assert!(x.set.reflectors.len() >= 10);
    // meshopt + quantization decode to plausible geometry (a first-person rig about 3 m wide).
    let level = load_level(dir.join("fps_mine_sketch_compressed.glb")).unwrap();
    let (lo, hi) = level.bounds().unwrap();
    let diag = (hi - lo).length();
    assert!(
        level.triangles.len() > 9_000 && diag > 0.1 && diag < 100.0,
        "{} triangles, diagonal {diag}",
        level.triangles.len()
    );
}
