//! glTF loading through small files written in a temporary folder: transforms, mirroring,
//! instancing, quantization, extras, external buffers, and the errors for bad input.

use glam::DVec3;
use ppr_extract::{ExtractParams, LoadError, extract, load_level, load_level_from_bytes};
use ppr_format::ReflectorKind;
use serde_json::json;

use crate::checks::assert_encloses_regions;
use ppr_level::gltf_builder::{GltfBuilder, PositionFormat, quad_xz};

const IDENTITY_ROTATION: [f64; 4] = [0.0, 0.0, 0.0, 1.0];

fn floor_builder(format: PositionFormat) -> (GltfBuilder, usize) {
    let mut b = GltfBuilder::new();
    let m = b.material("Marble", 0.1, 0.0, None);
    let (p, i) = quad_xz(-0.5, -0.25, 0.5, 0.25, 0.0);
    let mesh = b.mesh("Floor", &p, &i, m, format);
    (b, mesh)
}

fn load_bytes(bytes: &[u8]) -> Result<ppr_extract::Level, LoadError> {
    load_level_from_bytes(std::path::Path::new("test.glb"), bytes, std::path::Path::new("."))
}

#[test]
fn hierarchy_mirroring_and_instancing() {
    let (mut b, mesh) = floor_builder(PositionFormat::F32);
    b.node("plain", mesh, [0.0, 0.0, 0.0], IDENTITY_ROTATION, [4.0, 1.0, 4.0]);
    // Mirrored in x: the winding flips back, the floor still faces up.
    b.node("mirrored", mesh, [10.0, 1.0, 0.0], IDENTITY_ROTATION, [-4.0, 1.0, 4.0]);
    // Upside down (rotated 180° about x): faces down.
    b.node("flipped", mesh, [0.0, 3.0, 10.0], [1.0, 0.0, 0.0, 0.0], [4.0, 1.0, 4.0]);
    // A child inherits its parent's transform.
    let child = b.node("child", mesh, [0.0, 0.5, 0.0], IDENTITY_ROTATION, [1.0, 1.0, 1.0]);
    b.json["scenes"][0]["nodes"].as_array_mut().unwrap().retain(|n| n != &json!(child));
    let parent = b.json["nodes"].as_array().unwrap().len();
    b.json["nodes"].as_array_mut().unwrap().push(json!({"name": "parent", "translation": [-10.0, 0.0, 0.0], "scale": [2.0, 2.0, 2.0], "children": [child]}));
    b.json["scenes"][0]["nodes"].as_array_mut().unwrap().push(json!(parent));
    let level = load_bytes(&b.glb()).unwrap();
    assert_eq!(level.triangles.len(), 8);
    let x = extract(&level, &ExtractParams::default(), &|_, _| {});
    assert_encloses_regions(&x, 1e-6, "hierarchy");
    let find = |node: &str| {
        x.set.reflectors.iter().find(|r| r.source.nodes == [node]).unwrap_or_else(|| panic!("{node}"))
    };
    assert!(find("plain").normal.dot(DVec3::Y) > 0.999_999);
    assert!(find("mirrored").normal.dot(DVec3::Y) > 0.999_999);
    assert!(find("flipped").normal.dot(DVec3::NEG_Y) > 0.999_999);
    let child = find("child");
    assert!((child.center - DVec3::new(-10.0, 1.0, 0.0)).length() < 1e-9, "{:?}", child.center);
    assert!((child.area() - 0.5 * 4.0).abs() < 1e-6, "child area {}", child.area());
    assert!((find("plain").area() - 8.0).abs() < 1e-6);
}

#[test]
fn quantized_positions_read_like_floats() {
    let area = |format| {
        let (mut b, mesh) = floor_builder(format);
        if format == PositionFormat::NormalizedI16 {
            b.json["extensionsUsed"] = json!(["KHR_mesh_quantization"]);
            b.json["extensionsRequired"] = json!(["KHR_mesh_quantization"]);
        }
        b.node("n", mesh, [1e4, 0.0, 0.0], IDENTITY_ROTATION, [8.0, 1.0, 8.0]);
        let level = load_bytes(&b.glb()).unwrap();
        let x = extract(&level, &ExtractParams::default(), &|_, _| {});
        assert_encloses_regions(&x, 1e-6, "quantized");
        assert_eq!(x.set.reflectors.len(), 1);
        x.set.reflectors[0].area()
    };
    let (f, q) = (area(PositionFormat::F32), area(PositionFormat::NormalizedI16));
    assert!((f - 32.0).abs() < 1e-6 && (q - f).abs() < 1e-3 * f, "f32 {f} vs quantized {q}");
}

#[test]
fn extras_override_selection_and_kind() {
    let mut b = GltfBuilder::new();
    let rough = b.material("Concrete", 0.9, 0.0, None);
    let vetoed = b.material("Chrome", 0.0, 1.0, Some(json!({"ppr": {"reflector": false}})));
    let (p, i) = quad_xz(0.0, 0.0, 1.0, 1.0, 0.0);
    let m1 = b.mesh("a", &p, &i, rough, PositionFormat::F32);
    let m2 = b.mesh("b", &p, &i, vetoed, PositionFormat::F32);
    let m3 = b.mesh("c", &p, &i, rough, PositionFormat::F32);
    let pool = b.node("pool", m1, [0.0, 0.0, 0.0], IDENTITY_ROTATION, [1.0, 1.0, 1.0]);
    b.json["nodes"][pool]["extras"] = json!({"ppr": {"reflector": true, "kind": "water"}});
    b.node("chrome", m2, [5.0, 0.0, 0.0], IDENTITY_ROTATION, [1.0, 1.0, 1.0]);
    b.node("wall", m3, [10.0, 0.0, 0.0], IDENTITY_ROTATION, [1.0, 1.0, 1.0]);
    let level = load_bytes(&b.glb()).unwrap();
    let x = extract(&level, &ExtractParams::default(), &|_, _| {});
    assert_eq!(x.set.reflectors.len(), 1, "{:#?}", x.set.reflectors);
    assert_eq!(x.set.reflectors[0].kind, ReflectorKind::Water);
    assert_eq!(x.set.reflectors[0].source.nodes, vec!["pool".to_owned()]);
    // --all-planar takes the wall too, but the veto still holds.
    let x = extract(&level, &ExtractParams::all_planar(), &|_, _| {});
    assert_eq!(x.set.reflectors.len(), 2);
    let mut bad = GltfBuilder::new();
    bad.material("m", 0.1, 0.0, Some(json!({"ppr": {"kind": "lava"}})));
    let err = load_bytes(&bad.glb()).unwrap_err();
    assert!(err.to_string().contains("unknown reflector kind `lava`"), "{err}");
}

#[test]
fn gltf_with_external_buffer_and_its_errors() {
    let dir = tempfile::tempdir().unwrap();
    let (mut b, mesh) = floor_builder(PositionFormat::F32);
    b.node("n", mesh, [0.0; 3], IDENTITY_ROTATION, [1.0; 3]);
    let path = b.write_gltf(dir.path(), "level").unwrap();
    let level = load_level(&path).unwrap();
    assert_eq!(level.triangles.len(), 2);
    assert!(level.hash.starts_with("blake3:"));
    std::fs::remove_file(dir.path().join("level.bin")).unwrap();
    let err = load_level(&path).unwrap_err();
    assert!(matches!(err, LoadError::MissingBuffer { .. }), "{err}");
    assert!(err.to_string().contains("level.bin"), "{err}");
}

fn mutated(f: impl FnOnce(&mut serde_json::Value)) -> Result<ppr_extract::Level, LoadError> {
    let (mut b, mesh) = floor_builder(PositionFormat::F32);
    b.node("n", mesh, [0.0; 3], IDENTITY_ROTATION, [1.0; 3]);
    f(&mut b.json);
    load_bytes(&b.glb())
}

#[test]
fn bad_input_gives_errors_that_name_the_culprit() {
    type Mutation = Box<dyn FnOnce(&mut serde_json::Value)>;
    let cases: Vec<(&str, Mutation, &str)> = vec![
        (
            "required extension",
            Box::new(|j| j["extensionsRequired"] = json!(["KHR_draco_mesh_compression"])),
            "`KHR_draco_mesh_compression`",
        ),
        (
            "accessor out of range",
            Box::new(|j| j["accessors"][0]["count"] = json!(4000)),
            "accessors[0] is out of range",
        ),
        (
            "index out of range",
            Box::new(|j| j["accessors"][0]["count"] = json!(3)),
            "is not below the vertex count 3",
        ),
        (
            "missing accessor",
            Box::new(|j| j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(99)),
            "attributes.POSITION",
        ),
        ("bad node index", Box::new(|j| j["scenes"][0]["nodes"] = json!([42])), "scenes[0].nodes[0]"),
        ("cycle", Box::new(|j| j["nodes"][0]["children"] = json!([0])), "cycle"),
        (
            "NaN transform",
            Box::new(|j| j["nodes"][0]["matrix"] = json!([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])),
            "",
        ),
    ];
    for (what, f, expected) in cases {
        match mutated(f) {
            Err(e) => assert!(e.to_string().contains(expected), "{what}: {e}"),
            Ok(_) if expected.is_empty() => {}
            Ok(_) => panic!("{what}: loaded"),
        }
    }
    // NaN positions: patch the first float of the position data.
    let (mut b, mesh) = floor_builder(PositionFormat::F32);
    b.node("n", mesh, [0.0; 3], IDENTITY_ROTATION, [1.0; 3]);
    b.bin[0..4].copy_from_slice(&f32::NAN.to_le_bytes());
    let err = load_bytes(&b.glb()).unwrap_err();
    assert!(
        matches!(err, LoadError::NonFinitePosition { .. }) && err.to_string().contains("accessors[0]"),
        "{err}"
    );
    // Truncated and foreign files.
    let (mut b, mesh) = floor_builder(PositionFormat::F32);
    b.node("n", mesh, [0.0; 3], IDENTITY_ROTATION, [1.0; 3]);
    let glb = b.glb();
    let err = load_bytes(&glb[..glb.len() - 10]).unwrap_err();
    assert!(matches!(err, LoadError::TruncatedGlb { .. }), "{err}");
    let err = load_bytes(b"\x89PNG\r\n\x1a\n").unwrap_err();
    assert!(matches!(err, LoadError::NotGltf { .. }), "{err}");
    let err = load_bytes(b"{\"asset\": ").unwrap_err();
    assert!(matches!(err, LoadError::NotGltf { .. }), "{err}");
}
