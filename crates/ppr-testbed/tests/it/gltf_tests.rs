//! Loading glTF files written here: hierarchy flattening, instancing, negative scale,
//! materials, textures, cameras, external buffers and required extensions.

use std::path::Path;

use glam::{DVec3, Vec3};
use ppr_runtime::DepthMode;
use ppr_testbed::camera_spec::{ProjectionChoice, parse_camera, pick_camera};
use ppr_testbed::level::is_reflective;
use ppr_testbed::shape_meshes::{cuboid, floor_quad};
use ppr_testbed::{Level, TestbedError};
use serde_json::json;

/// A tiny glTF: a floor and a box mesh, a box instanced twice under a scaled parent and
/// once with a negative scale, a camera, a polished and a textured material.
struct TestGltf {
    json: serde_json::Value,
    bin: Vec<u8>,
}

fn push_f32(bin: &mut Vec<u8>, values: impl IntoIterator<Item = f32>) {
    for v in values {
        bin.extend_from_slice(&v.to_le_bytes());
    }
}

impl TestGltf {
    fn new() -> Self {
        let mut bin = Vec::new();
        let mut views = Vec::new();
        let mut accessors = Vec::new();
        let mut meshes = Vec::new();
        for (k, prim) in [floor_quad(3.0, 3.0, 1.0, 0), cuboid(Vec3::splat(0.25), 1)].into_iter().enumerate()
        {
            let first = accessors.len();
            let positions: Vec<Vec3> = prim.vertices.iter().map(|v| Vec3::from(v.position)).collect();
            let lo = positions.iter().fold(Vec3::splat(f32::MAX), |a, b| a.min(*b));
            let hi = positions.iter().fold(Vec3::splat(f32::MIN), |a, b| a.max(*b));
            let n = prim.vertices.len();
            for (attr, comps) in [("POSITION", 3usize), ("NORMAL", 3), ("TEXCOORD_0", 2)] {
                let offset = bin.len();
                for v in &prim.vertices {
                    match attr {
                        "POSITION" => push_f32(&mut bin, v.position),
                        "NORMAL" => push_f32(&mut bin, v.normal),
                        _ => push_f32(&mut bin, v.uv),
                    }
                }
                views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": n * comps * 4}));
                let mut acc = json!({
                    "bufferView": views.len() - 1, "componentType": 5126, "count": n,
                    "type": if comps == 3 { "VEC3" } else { "VEC2" }
                });
                if attr == "POSITION" {
                    acc["min"] = json!(lo.to_array());
                    acc["max"] = json!(hi.to_array());
                }
                accessors.push(acc);
            }
            let offset = bin.len();
            for i in &prim.indices {
                bin.extend_from_slice(&i.to_le_bytes());
            }
            views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": prim.indices.len() * 4}));
            accessors.push(json!({
                "bufferView": views.len() - 1, "componentType": 5125, "count": prim.indices.len(), "type": "SCALAR"
            }));
            meshes.push(json!({
                "name": if k == 0 { "floor" } else { "box" },
                "primitives": [{
                    "attributes": {"POSITION": first, "NORMAL": first + 1, "TEXCOORD_0": first + 2},
                    "indices": first + 3, "material": k
                }]
            }));
        }
        // 45° about Y, then 30° down about X: the camera at (4, 3, 4) looks at the origin-ish.
        let rot = glam::Quat::from_rotation_y(45f32.to_radians())
            * glam::Quat::from_rotation_x(-30f32.to_radians());
        let json = json!({
            "asset": {"version": "2.0", "generator": "ppr-testbed tests"},
            "scene": 0,
            "scenes": [{"nodes": [0, 1, 4, 5]}],
            "nodes": [
                {"name": "floor", "mesh": 0},
                {"name": "group", "translation": [0.0, 0.0, -1.0], "scale": [2.0, 2.0, 2.0], "children": [2, 3]},
                {"name": "box_a", "mesh": 1, "translation": [1.0, 0.25, 0.0], "extras": {"ppr": {"reflector": false}}},
                {"name": "box_b", "mesh": 1, "translation": [-1.0, 0.25, 0.0]},
                {"name": "box_mirrored", "mesh": 1, "translation": [0.0, 0.25, 1.0], "scale": [-1.0, 1.0, 1.0]},
                {"name": "cam_node", "camera": 0, "translation": [4.0, 3.0, 4.0], "rotation": rot.to_array()}
            ],
            "cameras": [{"name": "cam_test", "type": "perspective",
                         "perspective": {"yfov": 0.9, "znear": 0.1, "zfar": 80.0}}],
            "meshes": meshes,
            "materials": [
                {"name": "polished", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.2, 0.25, 1.0],
                  "metallicFactor": 0.0, "roughnessFactor": 0.05}},
                {"name": "textured", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                  "metallicFactor": 0.0, "roughnessFactor": 0.8}}
            ],
            "textures": [{"source": 0}],
            "images": [{"name": "green", "uri": "green.png"}],
            "accessors": accessors,
            "bufferViews": views,
            "buffers": [{"byteLength": bin.len(), "uri": "level.bin"}]
        });
        Self { json, bin }
    }

    /// Writes `level.gltf` + `level.bin` + `green.png` into `dir`.
    fn write_gltf(&self, dir: &Path) -> std::path::PathBuf {
        std::fs::write(dir.join("level.bin"), &self.bin).expect("write bin");
        image::RgbaImage::from_pixel(2, 2, image::Rgba([0, 200, 0, 255]))
            .save(dir.join("green.png"))
            .expect("png");
        let path = dir.join("level.gltf");
        std::fs::write(&path, serde_json::to_vec_pretty(&self.json).expect("json")).expect("write gltf");
        path
    }

    /// Writes `level.glb` (buffer embedded, the image still external) into `dir`.
    fn write_glb(&self, dir: &Path) -> std::path::PathBuf {
        image::RgbaImage::from_pixel(2, 2, image::Rgba([0, 200, 0, 255]))
            .save(dir.join("green.png"))
            .expect("png");
        let mut json = self.json.clone();
        json["buffers"] = json!([{"byteLength": self.bin.len()}]);
        let mut text = serde_json::to_vec(&json).expect("json");
        while !text.len().is_multiple_of(4) {
            text.push(b' ');
        }
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let total = 12 + 8 + text.len() + 8 + bin.len();
        let mut glb = Vec::with_capacity(total);
        glb.extend_from_slice(b"glTF");
        glb.extend_from_slice(&2u32.to_le_bytes());
        glb.extend_from_slice(&(total as u32).to_le_bytes());
        glb.extend_from_slice(&(text.len() as u32).to_le_bytes());
        glb.extend_from_slice(b"JSON");
        glb.extend_from_slice(&text);
        glb.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        glb.extend_from_slice(b"BIN\0");
        glb.extend_from_slice(&bin);
        let path = dir.join("level.glb");
        std::fs::write(&path, glb).expect("write glb");
        path
    }
}

fn check_level(level: &Level) {
    assert!(level.warnings.is_empty(), "{:?}", level.warnings);
    assert_eq!(level.meshes.len(), 2);
    let names: Vec<&str> = level.instances.iter().map(|i| i.node_name.as_str()).collect();
    assert_eq!(names, ["floor", "box_a", "box_b", "box_mirrored"]);
    let by_name = |n: &str| level.instances.iter().find(|i| i.node_name == n).expect("instance");
    // Parent: translate (0, 0, -1), scale 2; child translate (1, 0.25, 0).
    let a = by_name("box_a");
    assert!((a.world.w_axis.truncate() - DVec3::new(2.0, 0.5, -1.0)).length() < 1e-9);
    assert!((a.world.x_axis.truncate().length() - 2.0).abs() < 1e-9);
    assert_eq!(a.mesh, by_name("box_b").mesh, "instances share the mesh");
    assert_eq!(a.reflector_hint, Some(false));
    assert!(!a.flips_winding());
    assert!(by_name("box_mirrored").flips_winding());
    let polished = &level.materials[0];
    assert!(is_reflective(polished) && (polished.roughness - 0.05).abs() < 1e-6);
    let textured = &level.materials[1];
    assert!(!is_reflective(textured));
    let tex = &level.textures[textured.base_color_texture.expect("texture")];
    assert_eq!((tex.width, tex.height, &tex.rgba8[..4]), (2, 2, &[0u8, 200, 0, 255][..]));
    assert_eq!(level.cameras.len(), 1);
    let cam = &level.cameras[0];
    assert_eq!(cam.name, "cam_test");
    assert!((cam.yfov - 0.9).abs() < 1e-6 && cam.zfar == Some(80.0));
    let rc = cam.to_runtime_camera(ProjectionChoice::default());
    assert!((rc.position - DVec3::new(4.0, 3.0, 4.0)).length() < 1e-6);
    // -Z rotated 45° about Y points to (-0.707, 0, -0.707), tilted 30° down.
    let expected =
        Vec3::new(-0.5f32.sqrt() * 30f32.to_radians().cos(), -0.5, -0.5f32.sqrt() * 30f32.to_radians().cos());
    assert!((rc.forward() - expected).length() < 1e-4, "{}", rc.forward());
}

#[test]
fn gltf_with_external_buffer_and_image_loads() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = TestGltf::new().write_gltf(dir.path());
    check_level(&Level::load_gltf(&path).expect("load"));
}

#[test]
fn glb_loads_the_same_level() {
    let dir = tempfile::tempdir().expect("tempdir");
    let gltf = TestGltf::new();
    let mut a = Level::load_gltf(gltf.write_gltf(dir.path())).expect("gltf");
    let mut b = Level::load_gltf(gltf.write_glb(dir.path())).expect("glb");
    check_level(&b);
    // The two files differ in bytes, so in hash; everything loaded from them is the same.
    assert!(a.source_hash.starts_with("blake3:") && a.source_hash != b.source_hash);
    a.source_hash.clear();
    b.source_hash.clear();
    assert_eq!(a, b);
}

#[test]
fn required_extensions_that_keep_geometry_load_and_others_are_refused_by_name() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut gltf = TestGltf::new();
    let harmless = ["KHR_lights_punctual", "KHR_materials_clearcoat", "KHR_texture_transform"];
    gltf.json["extensionsUsed"] = json!(harmless);
    gltf.json["extensionsRequired"] = json!(harmless);
    gltf.json["extensions"] =
        json!({"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 5.0}]}});
    check_level(
        &Level::load_gltf(gltf.write_gltf(dir.path())).expect("lights and materials do not change geometry"),
    );
    gltf.json["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
    gltf.json["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    let err = Level::load_gltf(gltf.write_gltf(dir.path())).expect_err("must refuse");
    assert!(matches!(err, TestbedError::Level(ppr_level::LoadError::UnsupportedExtension { .. })), "{err:?}");
    let text = err.to_string();
    assert!(text.contains("KHR_draco_mesh_compression") && text.contains("level.gltf"), "{text}");
}

#[test]
fn missing_files_name_the_path() {
    let err = Level::load_gltf("/nonexistent/level.glb").expect_err("missing");
    assert!(err.to_string().contains("/nonexistent/level.glb"), "{err}");
}

#[test]
fn cameras_from_names_and_descriptions() {
    let dir = tempfile::tempdir().expect("tempdir");
    let level = Level::load_gltf(TestGltf::new().write_gltf(dir.path())).expect("load");
    let reversed = ProjectionChoice { depth: DepthMode::Reversed, infinite_far: true };
    let first = pick_camera(&level, None, reversed).expect("first camera");
    assert_eq!(first.projection.depth, DepthMode::Reversed);
    assert_eq!(first.projection.far, None);
    assert_eq!(pick_camera(&level, Some("cam_test"), reversed).expect("by name"), first);
    let err = pick_camera(&level, Some("cam_nope"), reversed).expect_err("unknown");
    assert!(err.to_string().contains("cam_test"), "lists the cameras: {err}");
    let cam = parse_camera("eye=0,2,5; target=0,0,0; fov=60", ProjectionChoice::default()).expect("parse");
    assert!((cam.projection.fov_y - 60f32.to_radians()).abs() < 1e-6);
    assert!((cam.forward() - Vec3::new(0.0, -2.0, -5.0).normalize()).length() < 1e-6);
    for bad in [
        "eye=0,2;target=0,0,0",
        "eye=0,2,5",
        "eye=1,1,1;target=1,1,1",
        "eye=0,2,5;target=0,0,0;fov=0",
        "zoom=3",
    ] {
        assert!(parse_camera(bad, ProjectionChoice::default()).is_err(), "{bad} must not parse");
    }
}

/// Every shared scene (`../shared/scenes/`) opens in the testbed (and so in `ppr-render`),
/// as it does in the extractor: both read it through `ppr-level`.
#[test]
fn every_shared_scene_opens() {
    let files =
        ppr_level::shared_scene_files(Path::new(env!("CARGO_MANIFEST_DIR")), 5).expect("shared scenes");
    for path in files {
        let level = Level::load_gltf(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        level.validate().unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let extracted = ppr_level::load_level(&path).expect("the extractor's view");
        assert_eq!(level.triangle_count(), extracted.triangles.len(), "{}", path.display());
    }
}

/// The testbed draws `ppr-level`'s materials themselves: nothing of a material the loader
/// read (alpha mode and cutoff, clearcoat, normal map, `extras.ppr`) is dropped on the way.
#[test]
fn the_levels_materials_are_the_loaders_whole() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/demo_room.glb");
    let scene = ppr_level::load_scene(&path, &ppr_level::LoadParams::render()).expect("demo scene");
    let level = Level::from_scene(&scene).expect("demo level");
    assert_eq!(level.materials, scene.materials);
    let glass = level.materials.iter().find(|m| m.name == "glass").expect("glass");
    assert_eq!(glass.alpha_mode, ppr_level::AlphaMode::Blend);
}
