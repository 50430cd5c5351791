//! What the `gltf_loader` fuzzer found, as named cases: a node listed under many parents
//! multiplies placed triangles past the limit (refused before any instance is
//! transformed), and an image with neither `uri` nor `bufferView` (a note, not a panic).

use std::path::Path;

use ppr_level::gltf_builder::{GltfBuilder, PositionFormat};
use ppr_level::{LoadError, LoadParams, load_scene_from_bytes};
use serde_json::json;

const NO_ROTATION: [f64; 4] = [0.0, 0.0, 0.0, 1.0];

/// One triangle listed `primitives` times in one mesh, placed by a chain of `levels` nodes
/// each listing the next `fan_out` times: `fan_out^levels × primitives` triangles.
fn node_fan(levels: usize, fan_out: usize, primitives: usize) -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let m = b.material("Paint", 0.5, 0.0, None);
    let tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
    let mesh = b.mesh("Tri", &tri, &[0, 2, 1], m, PositionFormat::F32);
    let prim = b.json["meshes"][mesh]["primitives"][0].clone();
    b.json["meshes"][mesh]["primitives"] = json!(vec![prim; primitives]);
    let first = b.json["nodes"].as_array().map_or(0, Vec::len);
    for k in 0..levels {
        b.push("nodes", json!({"children": vec![first + k + 1; fan_out]}));
    }
    b.push("nodes", json!({"name": "leaf", "mesh": mesh}));
    b.push_root(first);
    b.glb()
}

fn load(bytes: &[u8], max_triangles: usize) -> Result<ppr_level::Scene, LoadError> {
    let params = LoadParams { max_triangles, ..LoadParams::render() };
    load_scene_from_bytes(Path::new("fan.glb"), bytes, Path::new("."), &params)
}

#[test]
fn nodes_listed_under_many_parents_cannot_place_more_than_the_limit() {
    // 16^4 paths × 64 triangles = 2^22 triangles from a file of a few kilobytes.
    let bytes = node_fan(4, 16, 64);
    assert!(bytes.len() < 16 << 10, "{} bytes", bytes.len());
    let err = load(&bytes, 1 << 20).expect_err("2^22 placed triangles over a limit of 2^20");
    assert!(matches!(err, LoadError::TooLarge { .. }), "{err:?}");
    assert!(err.to_string().contains("nodes[") && err.to_string().contains("1048576"), "{err}");
    // Within the limit the same shape loads, every path an instance.
    let scene = load(&node_fan(2, 16, 64), 1 << 20).expect("2^14 placed triangles");
    assert_eq!(scene.instances.len(), 256);
}

#[test]
fn an_image_without_a_source_is_a_note_not_a_panic() {
    let mut b = GltfBuilder::new();
    let m = b.material("Tiles", 0.5, 0.0, None);
    let tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
    let mesh = b.mesh("Tri", &tri, &[0, 2, 1], m, PositionFormat::F32);
    b.node("floor", mesh, [0.0; 3], NO_ROTATION, [1.0; 3]);
    b.json["images"] = json!([{"name": "nowhere"}]);
    b.json["textures"] = json!([{"source": 0}]);
    b.json["materials"][m]["pbrMetallicRoughness"]["baseColorTexture"] = json!({"index": 0});
    b.json["materials"][m]["pbrMetallicRoughness"]["metallicRoughnessTexture"] = json!({"index": 0});
    let scene = load(&b.glb(), 1 << 20).expect("a missing image is not an error");
    assert!(scene.textures.is_empty());
    let notes = scene.notes.join("\n");
    assert!(notes.contains("nowhere") && notes.contains("neither `uri` nor `bufferView`"), "{notes}");
}
