//! Metallic-roughness textures: their green channel and sampler reach the material and
//! the level (with each triangle's UVs) in every load but `Skip`; a texture that does not
//! decode is a note and changes nothing else.

use std::path::Path;

use ppr_level::gltf_builder::{GltfBuilder, PositionFormat, quad_xz};
use ppr_level::{Level, LoadParams, TextureLoading, Wrap, load_scene_from_bytes};

const NO_ROTATION: [f64; 4] = [0.0, 0.0, 0.0, 1.0];

/// A floor quad with UVs over [0, 2]² and a 2 × 1 roughness texture (green 0 and 255),
/// mirrored by its node (so the winding, and the UVs with it, flip).
fn textured_floor() -> GltfBuilder {
    let mut b = GltfBuilder::new();
    let m = b.material("Brushed", 0.5, 1.0, None);
    let (p, i) = quad_xz(-1.0, -1.0, 1.0, 1.0, 0.0);
    let mesh = b.mesh("Floor", &p, &i, m, PositionFormat::F32);
    b.uvs(mesh, &[[0.0, 0.0], [0.0, 2.0], [2.0, 2.0], [2.0, 0.0]]);
    b.roughness_texture(m, 2, 1, &[0, 255], 33071);
    b.node("floor", mesh, [0.0; 3], NO_ROTATION, [-1.0, 1.0, 1.0]);
    b
}

fn level(b: GltfBuilder, params: LoadParams) -> Level {
    let scene = load_scene_from_bytes(Path::new("t.glb"), &b.glb(), Path::new("."), &params).unwrap();
    Level::from_scene(&scene).unwrap()
}

#[test]
fn the_roughness_map_and_uvs_reach_the_level() {
    let render = level(textured_floor(), LoadParams::render());
    let geometry = level(textured_floor(), LoadParams::geometry());
    assert_eq!(render, geometry, "the extractor's load and a renderer's give the same level");
    let map = geometry.materials[0].roughness_map.as_ref().expect("decoded");
    assert_eq!((map.width, map.height, map.green.clone()), (2, 1, vec![0, 255]));
    assert_eq!(map.wrap, [Wrap::ClampToEdge; 2]);
    assert_eq!(map.at([0.2, 0.5]), 0.0);
    assert_eq!(map.at([1.7, 0.5]), 1.0);
    assert_eq!(geometry.materials[0].roughness, 0.5, "the factor is kept apart");
    geometry.validate().unwrap();
    assert_eq!(geometry.uvs.len(), geometry.triangles.len());
    // The node mirrors x: corners b and c swap, and their UVs with them.
    assert_eq!(geometry.uvs[0], [[0.0, 0.0], [2.0, 2.0], [0.0, 2.0]]);
    let skipped =
        level(textured_floor(), LoadParams { textures: TextureLoading::Skip, ..LoadParams::default() });
    assert!(skipped.materials[0].roughness_map.is_none() && skipped.uvs.is_empty());
}

#[test]
fn a_texture_that_does_not_decode_is_a_note() {
    let mut b = textured_floor();
    let view = b.json["images"][0]["bufferView"].as_u64().unwrap() as usize;
    let offset = b.json["bufferViews"][view]["byteOffset"].as_u64().unwrap() as usize;
    b.bin[offset + 20] ^= 0xFF; // inside the PNG header chunk
    let scene = load_scene_from_bytes(Path::new("t.glb"), &b.glb(), Path::new("."), &LoadParams::geometry())
        .expect("a broken image is not an error");
    assert!(scene.materials[0].roughness_map.is_none());
    assert!(scene.notes.iter().any(|n| n.contains("roughness factor used alone")), "{:?}", scene.notes);
    let level = Level::from_scene(&scene).unwrap();
    assert!(level.uvs.is_empty(), "no map, no UVs kept");
}
