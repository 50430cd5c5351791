//! Every shared third-party scene (`../shared/scenes/`) loads as a scene and as a level,
//! textures decoded, and both views of it agree.

use std::path::PathBuf;

use ppr_level::{Level, LoadParams, Scene, level_files, load_scene};

/// The shared scenes folder; fails (never skips) when it is missing.
fn scenes_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    assert!(dir.join("README.md").is_file(), "the shared scenes are missing: looked for {}", dir.display());
    dir
}

fn triangles_placed(scene: &Scene) -> usize {
    scene
        .instances
        .iter()
        .map(|i| scene.meshes[i.mesh].primitives.iter().map(|p| p.indices.len() / 3).sum::<usize>())
        .sum()
}

#[test]
fn every_shared_scene_loads_as_a_scene_and_a_level() {
    let files = level_files(&scenes_dir());
    let names: Vec<String> =
        files.iter().map(|p| p.file_name().unwrap().to_string_lossy().into_owned()).collect();
    for expected in [
        "collision-world.glb",
        "fps_mine_sketch_compressed.glb",
        "kitchen.gltf",
        "pool_day_baked.glb",
        "small.glb",
    ] {
        assert!(names.iter().any(|n| n == expected), "{expected} not found among {names:?}");
    }
    for path in &files {
        let name = path.display();
        let scene = load_scene(path, &LoadParams::render()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(scene.hash.starts_with("blake3:"), "{name}");
        assert!(!scene.instances.is_empty(), "{name}: nothing placed");
        for note in &scene.notes {
            assert!(!note.contains("does not decode"), "{name}: {note}");
        }
        for (m, mesh) in scene.meshes.iter().enumerate() {
            for p in &mesh.primitives {
                assert_eq!(p.normals.len(), p.positions.len(), "{name}: meshes[{m}] normals");
                assert!(p.uvs.is_empty() || p.uvs.len() == p.positions.len(), "{name}: meshes[{m}] uvs");
                assert!(p.indices.iter().all(|&i| (i as usize) < p.positions.len()), "{name}: meshes[{m}]");
                assert!(p.material < scene.materials.len(), "{name}: meshes[{m}] material");
                assert!(
                    p.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-3),
                    "{name}: meshes[{m}] unit normals"
                );
            }
        }
        for m in &scene.materials {
            if let Some(t) = m.base_color_texture {
                let t = &scene.textures[t];
                assert_eq!(t.rgba8.len(), t.width as usize * t.height as usize * 4, "{name}: {}", t.name);
            }
        }
        let level = Level::from_scene(&scene).unwrap_or_else(|e| panic!("{name}: {e}"));
        level.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(level.triangles.len(), triangles_placed(&scene), "{name}");
        assert_eq!(level.materials.len(), scene.materials.len(), "{name}");
        // The geometry-only load is the same level.
        let geometry = load_scene(path, &LoadParams::geometry()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(geometry.textures.is_empty());
        assert_eq!(Level::from_scene(&geometry).unwrap(), level, "{name}");
    }
}

#[test]
fn scenes_with_textures_skins_and_compression_read_them() {
    let dir = scenes_dir();
    // Meshopt-compressed and quantized, with JPEG textures and two skins.
    let mine = load_scene(dir.join("fps_mine_sketch_compressed.glb"), &LoadParams::render()).unwrap();
    assert!(!mine.textures.is_empty(), "{:?}", mine.notes);
    assert!(mine.materials.iter().any(|m| m.base_color_texture.is_some()));
    // The pool's glass is alpha-blended.
    let pool = load_scene(dir.join("pool_day_baked.glb"), &LoadParams::render()).unwrap();
    assert!(pool.materials.iter().any(|m| m.alpha_mode == ppr_level::AlphaMode::Blend));
    assert!(pool.materials.iter().any(|m| m.unlit));
    // The kitchen's clearcoat is read as written.
    let kitchen = load_scene(dir.join("kitchen/kitchen.gltf"), &LoadParams::geometry()).unwrap();
    assert!(kitchen.materials.iter().any(|m| m.clearcoat > 0.0));
}
