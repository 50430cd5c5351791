//! Malformed files built in code: every size and offset is checked before it is
//! allocated, unsafe URIs are refused, node trees are walked without recursion, and each
//! error names the file and the field.

use std::path::Path;

use ppr_level::gltf_builder::{GltfBuilder, PositionFormat, quad_xz};
use ppr_level::{LoadError, LoadParams, MAX_NODE_DEPTH, Scene, load_scene, load_scene_from_bytes};
use serde_json::{Value, json};

const NO_ROTATION: [f64; 4] = [0.0, 0.0, 0.0, 1.0];

/// A 1 m floor quad placed by node 0: accessor 0 is POSITION, 1 the indices.
fn floor() -> GltfBuilder {
    let mut b = GltfBuilder::new();
    let m = b.material("Marble", 0.1, 0.0, None);
    let (p, i) = quad_xz(-0.5, -0.5, 0.5, 0.5, 0.0);
    let mesh = b.mesh("Floor", &p, &i, m, PositionFormat::F32);
    b.node("floor", mesh, [0.0; 3], NO_ROTATION, [1.0; 3]);
    b
}

fn load(b: GltfBuilder) -> Result<Scene, LoadError> {
    load_scene_from_bytes(Path::new("bad.glb"), &b.glb(), Path::new("."), &LoadParams::render())
}

fn mutated(f: impl FnOnce(&mut Value)) -> Result<Scene, LoadError> {
    let mut b = floor();
    f(&mut b.json);
    load(b)
}

/// The load fails with an error whose message holds the file and every `expected` part.
fn assert_refused(result: Result<Scene, LoadError>, what: &str, expected: &[&str]) -> LoadError {
    let err = match result {
        Ok(_) => panic!("{what}: loaded"),
        Err(e) => e,
    };
    let text = err.to_string();
    assert!(text.contains("bad.glb"), "{what}: the file is not named: {text}");
    for part in expected {
        assert!(text.contains(part), "{what}: `{part}` missing from: {text}");
    }
    err
}

#[test]
fn the_floor_itself_loads() {
    let scene = load(floor()).expect("the unmutated floor");
    assert_eq!(scene.instances.len(), 1);
    assert_eq!(scene.meshes[0].primitives[0].indices.len(), 6);
}

#[test]
fn huge_counts_and_offsets_are_errors_before_any_allocation() {
    type Mutation = Box<dyn FnOnce(&mut Value)>;
    let cases: Vec<(&str, Mutation, &[&str])> = vec![
        (
            "count near 2^32",
            Box::new(|j| j["accessors"][0]["count"] = json!(4_000_000_000u64)),
            &["accessors[0]", "out of range", "count 4000000000"],
        ),
        (
            "count near 2^60",
            Box::new(|j| j["accessors"][0]["count"] = json!(1u64 << 60)),
            &["accessors[0]", "out of range"],
        ),
        (
            "accessor byteOffset",
            Box::new(|j| j["accessors"][0]["byteOffset"] = json!(1u64 << 62)),
            &["accessors[0]", "out of range"],
        ),
        (
            "index count",
            Box::new(|j| j["accessors"][1]["count"] = json!(u32::MAX)),
            &["accessors[1]", "out of range"],
        ),
        (
            "bufferView byteOffset",
            Box::new(|j| j["bufferViews"][0]["byteOffset"] = json!(u64::MAX - 3)),
            &["bufferViews[0]", "out of range"],
        ),
        (
            "bufferView byteLength",
            Box::new(|j| j["bufferViews"][1]["byteLength"] = json!(1u64 << 40)),
            &["bufferViews[1]", "out of range"],
        ),
        (
            "byteStride",
            Box::new(|j| j["bufferViews"][0]["byteStride"] = json!(252)),
            &["accessors[0]", "out of range"],
        ),
    ];
    for (what, f, expected) in cases {
        let err = assert_refused(mutated(f), what, expected);
        assert!(matches!(err, LoadError::OutOfRange { .. }), "{what}: {err:?}");
    }
}

#[test]
fn a_sparse_only_accessor_may_not_describe_more_than_the_file_holds() {
    let mut b = floor();
    // 2 sparse entries, indices (u8) and values (vec3 f32) in views of their own.
    let iv = b.view(&[0u8, 3, 0, 0]);
    let vv = b.view(&[0u8; 24]);
    let sparse = |count: u64| {
        json!({"componentType": 5126, "type": "VEC3", "count": count,
        "sparse": {"count": 2, "indices": {"bufferView": iv, "componentType": 5121}, "values": {"bufferView": vv}}})
    };
    let small = b.push("accessors", sparse(4));
    let huge = b.push("accessors", sparse(1 << 28));
    let mut ok = GltfBuilder { json: b.json.clone(), bin: b.bin.clone() };
    ok.json["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = json!(small);
    // A sparse NORMAL of zeros loads (zero normals read as +Y).
    let scene = load(ok).expect("a small sparse-only accessor");
    assert_eq!(scene.meshes[0].primitives[0].normals.len(), 4);
    b.json["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = json!(huge);
    let err = assert_refused(
        load(b),
        "sparse only",
        &[&format!("accessors[{huge}]"), "without a bufferView", "268435456"],
    );
    assert!(matches!(err, LoadError::OutOfRange { .. }), "{err:?}");
}

#[test]
fn meshopt_views_that_would_expand_beyond_the_codec_are_refused() {
    let mut b = floor();
    b.json["extensionsUsed"] = json!(["EXT_meshopt_compression"]);
    b.json["extensionsRequired"] = json!(["EXT_meshopt_compression"]);
    let v = b.view(&[0xa0; 16]);
    b.json["bufferViews"][v]["extensions"] = json!({"EXT_meshopt_compression":
        {"buffer": 0, "byteOffset": 0, "byteLength": 16, "byteStride": 16, "count": 1 << 26, "mode": "ATTRIBUTES"}});
    assert_refused(
        load(b),
        "meshopt bomb",
        &[&format!("bufferViews[{v}]"), "cannot come from 16 compressed bytes"],
    );
}

#[test]
fn buffer_uris_outside_the_levels_folder_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let inner = dir.path().join("level");
    std::fs::create_dir(&inner).unwrap();
    std::fs::write(dir.path().join("outside.bin"), [0u8; 256]).unwrap();
    for (uri, expected) in [
        ("/dev/zero", "absolute"),
        ("../outside.bin", "`..`"),
        ("sub/../../outside.bin", "`..`"),
        ("file:///dev/zero", "`file:`"),
        (".", "regular file"),
    ] {
        let path = floor().write_gltf(&inner, "level").unwrap();
        let mut json: Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
        json["buffers"][0]["uri"] = json!(uri);
        std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
        let err = load_scene(&path, &LoadParams::render()).expect_err(uri);
        let text = err.to_string();
        assert!(matches!(err, LoadError::UnsafeUri { .. }), "{uri}: {err:?}");
        assert!(
            text.contains("level.gltf") && text.contains("buffers[0]") && text.contains(expected),
            "{uri}: {text}"
        );
    }
    // A buffer file shorter than its byteLength.
    let path = floor().write_gltf(&inner, "short").unwrap();
    let bin = inner.join("short.bin");
    let len = std::fs::metadata(&bin).unwrap().len();
    std::fs::write(&bin, vec![0u8; len as usize - 4]).unwrap();
    let err = load_scene(&path, &LoadParams::render()).expect_err("short");
    assert!(matches!(err, LoadError::BadBuffer { .. }) && err.to_string().contains("truncated"), "{err}");
}

#[test]
fn node_trees_are_walked_without_recursion_and_limits_are_named() {
    // A chain deeper than the limit: refused by name, without overflowing the stack.
    let mut b = floor();
    let first = b.json["nodes"].as_array().unwrap().len();
    for k in 0..MAX_NODE_DEPTH + 10 {
        let n = b.push("nodes", json!({"name": format!("link{k}"), "children": [first + k + 1]}));
        assert_eq!(n, first + k);
    }
    b.push("nodes", json!({"name": "leaf", "mesh": 0}));
    b.push_root(first);
    let err = assert_refused(load(b), "deep chain", &["deeper than 1024 levels"]);
    assert!(matches!(err, LoadError::TooLarge { .. }), "{err:?}");
    // A chain just within the limit loads and places the mesh at its end.
    let mut b = floor();
    let first = b.json["nodes"].as_array().unwrap().len();
    for k in 0..MAX_NODE_DEPTH - 1 {
        b.push("nodes", json!({"children": [first + k + 1], "translation": [0.0, 0.001, 0.0]}));
    }
    b.push("nodes", json!({"name": "leaf", "mesh": 0}));
    b.push_root(first);
    let scene = load(b).expect("1024 levels");
    let leaf = scene.instances.iter().find(|i| i.node_name == "leaf").expect("leaf placed");
    let expected = f64::from(0.001f32) * (MAX_NODE_DEPTH - 1) as f64;
    assert!((leaf.world.w_axis.y - expected).abs() < 1e-9, "{}", leaf.world.w_axis.y);
    // Cycles, through the root's children and among nodes no root reaches.
    let err = assert_refused(
        mutated(|j| j["nodes"][0]["children"] = json!([0])),
        "self cycle",
        &["nodes[0].children", "cycle"],
    );
    assert!(matches!(err, LoadError::Invalid { .. }));
    assert_refused(
        mutated(|j| {
            j["nodes"].as_array_mut().unwrap().extend([json!({"children": [2]}), json!({"children": [1]})]);
            j["scenes"][0]["nodes"] = json!([0, 1]);
        }),
        "two-node cycle",
        &["children", "cycle"],
    );
}

#[test]
fn required_extensions_are_tolerated_when_they_keep_geometry_and_refused_by_name_otherwise() {
    let with = |ext: &[&str]| {
        mutated(|j| {
            j["extensionsUsed"] = json!(ext);
            j["extensionsRequired"] = json!(ext);
        })
    };
    with(&[
        "KHR_lights_punctual",
        "KHR_materials_variants",
        "KHR_texture_transform",
        "EXT_lights_image_based",
    ])
    .expect("lights and material extensions");
    for ext in ["KHR_draco_mesh_compression", "KHR_mesh_quantization_v2", "EXT_unknown"] {
        let err = assert_refused(with(&[ext]), ext, &[&format!("`{ext}`")]);
        assert!(matches!(err, LoadError::UnsupportedExtension { .. }), "{err:?}");
    }
}

#[test]
fn positions_beyond_the_set_formats_range_name_the_node() {
    let err = assert_refused(
        mutated(|j| j["nodes"][0]["translation"] = json!([2.0e7, 0.0, 0.0])),
        "far",
        &["nodes[0]", "\"floor\"", "beyond"],
    );
    assert!(matches!(err, LoadError::PositionOutOfRange { node: 0, .. }), "{err:?}");
    // Just inside loads.
    mutated(|j| j["nodes"][0]["translation"] = json!([9.0e6, 0.0, 0.0])).expect("9000 km");
}

#[test]
fn bad_extras_name_their_owner() {
    assert_refused(
        mutated(|j| j["nodes"][0]["extras"] = json!({"ppr": {"kind": "lava"}})),
        "node extras",
        &["nodes[0] (\"floor\")", "unknown reflector kind `lava`"],
    );
    let scene = mutated(|j| j["meshes"][0]["extras"] = json!({"ppr": {"reflector": false}})).unwrap();
    assert_eq!(scene.meshes[0].ppr.reflector, Some(false));
}
