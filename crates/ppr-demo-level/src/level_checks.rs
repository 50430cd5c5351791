//! Tests of the generated level as a reader sees it: parsed by the `gltf` crate, checked against the ground truth and the committed assets.

use std::collections::BTreeSet;
use std::path::PathBuf;
use std::sync::LazyLock;

use glam::{DMat4, DVec3};
use serde_json::Value;

use crate::generated_level::{EXPECTED_FILE, GeneratedLevel, LEVEL_FILE};

/// One generation shared by all tests.
static LEVEL: LazyLock<GeneratedLevel> =
    LazyLock::new(|| GeneratedLevel::generate().expect("the demo level generates"));

/// The level parsed and validated by the `gltf` crate (buffers and images loaded).
static IMPORTED: LazyLock<(gltf::Document, Vec<gltf::buffer::Data>, Vec<gltf::image::Data>)> =
    LazyLock::new(|| gltf::import_slice(&LEVEL.glb).expect("the gltf crate accepts the level"));

static EXPECTED: LazyLock<Value> =
    LazyLock::new(|| serde_json::from_str(&LEVEL.expected_json).expect("the ground truth is JSON"));

const NODE_NAMES: [&str; 45] = [
    "room",
    "room_floor",
    "room_walls",
    "mirror_wall",
    "back_wall_frame",
    "glass_panel",
    "pane_frame",
    "stairs",
    "step_1",
    "step_2",
    "step_3",
    "step_4",
    "step_5",
    "leaning_stand",
    "leaning_stand_base",
    "leaning_stand_tilt",
    "tilted_mirror",
    "tilted_frame",
    "stone_basin",
    "basin_rim",
    "water_surface",
    "stone_pond",
    "pond_rim",
    "pond_water",
    "polished_floor",
    "brushed_metal_panel",
    "puddles",
    "puddle_a",
    "puddle_b",
    "puddle_c_mirrored",
    "puddle_c",
    "props",
    "pillar_red",
    "pillar_blue",
    "pillar_yellow",
    "box_orange",
    "box_cyan",
    "box_purple",
    "box_green",
    "table",
    "table_top",
    "table_legs",
    "cam_overview",
    "cam_mirror",
    "cam_steps",
];

fn document() -> &'static gltf::Document {
    &IMPORTED.0
}

fn node(name: &str) -> gltf::Node<'static> {
    document().nodes().find(|n| n.name() == Some(name)).unwrap_or_else(|| panic!("no node {name}"))
}

/// World matrices of every node, by index, composed in `f64` from the stored `f32` values.
fn world_matrices() -> Vec<DMat4> {
    fn visit(node: gltf::Node, parent: DMat4, out: &mut Vec<DMat4>) {
        let local = DMat4::from_cols_array_2d(&node.transform().matrix().map(|c| c.map(f64::from)));
        out[node.index()] = parent * local;
        for child in node.children() {
            visit(child, out[node.index()], out);
        }
    }
    let mut out = vec![DMat4::NAN; document().nodes().len()];
    for root in document().default_scene().expect("a default scene").nodes() {
        visit(root, DMat4::IDENTITY, &mut out);
    }
    out
}

/// World-space triangles of one primitive of a node's mesh.
fn world_triangles(node: &gltf::Node, primitive: usize) -> Vec<[DVec3; 3]> {
    let world = world_matrices()[node.index()];
    let mesh = node.mesh().expect("a mesh");
    let primitive = mesh.primitives().nth(primitive).expect("the primitive");
    let reader = primitive.reader(|buffer| Some(&IMPORTED.1[buffer.index()]));
    let positions: Vec<DVec3> = reader
        .read_positions()
        .expect("positions")
        .map(|p| world.transform_point3(DVec3::from_array(p.map(f64::from))))
        .collect();
    let indices: Vec<u32> = reader.read_indices().expect("indices").into_u32().collect();
    indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]].map(|i| positions[i as usize])).collect()
}

fn vec3(value: &Value) -> DVec3 {
    let array = value.as_array().expect("a 3-vector");
    DVec3::from_array([0, 1, 2].map(|k| array[k].as_f64().expect("a number")))
}

fn workspace_assets() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets")
}

#[test]
fn generation_is_deterministic() {
    let again = GeneratedLevel::generate().expect("generates");
    assert!(again.glb == LEVEL.glb, "two runs gave different .glb bytes");
    assert_eq!(again.expected_json, LEVEL.expected_json);
}

#[test]
fn committed_assets_equal_a_fresh_run() {
    let hint = "assets are stale: run `cargo run -p ppr-demo-level` and commit assets/";
    let glb = std::fs::read(workspace_assets().join(LEVEL_FILE)).expect(hint);
    assert!(glb == LEVEL.glb, "{hint} ({LEVEL_FILE} differs)");
    let expected = std::fs::read_to_string(workspace_assets().join(EXPECTED_FILE)).expect(hint);
    assert!(expected == LEVEL.expected_json, "{hint} ({EXPECTED_FILE} differs)");
}

#[test]
fn level_is_small() {
    assert!(LEVEL.glb.len() < 1024 * 1024, "{} bytes", LEVEL.glb.len());
}

#[test]
fn images_decode() {
    let images = &IMPORTED.2;
    assert_eq!(images.len(), 2);
    for image in images {
        assert_eq!((image.width, image.height), (128, 128));
        assert_eq!(image.format, gltf::image::Format::R8G8B8);
    }
    for texture in document().textures() {
        let sampler = texture.sampler();
        assert_eq!(sampler.wrap_s(), gltf::texture::WrappingMode::Repeat);
        assert!(sampler.mag_filter().is_some() && sampler.min_filter().is_some());
    }
}

#[test]
fn accessors_and_views_are_in_range() {
    let buffers = &IMPORTED.1;
    for accessor in document().accessors() {
        let view = accessor.view().expect("no sparse-only accessors");
        let element = accessor.size();
        let stride = view.stride().unwrap_or(element);
        let end = accessor.offset() + (accessor.count() - 1) * stride + element;
        assert!(end <= view.length(), "accessor {} overruns its view", accessor.index());
        assert!(view.offset() + view.length() <= view.buffer().length(), "view {}", view.index());
        assert!(view.buffer().length() <= buffers[view.buffer().index()].len());
        assert_eq!(view.offset() % 4, 0, "view {} is not 4-byte aligned", view.index());
    }
}

#[test]
fn every_primitive_has_positions_normals_uvs_and_valid_indices() {
    for mesh in document().meshes() {
        for primitive in mesh.primitives() {
            let context = format!("mesh {:?}", mesh.name());
            assert_eq!(primitive.mode(), gltf::mesh::Mode::Triangles);
            let reader = primitive.reader(|buffer| Some(&IMPORTED.1[buffer.index()]));
            let positions: Vec<[f32; 3]> = reader.read_positions().expect(&context).collect();
            let normals: Vec<[f32; 3]> = reader.read_normals().expect(&context).collect();
            let uvs = reader.read_tex_coords(0).expect(&context).into_f32().count();
            assert_eq!((normals.len(), uvs), (positions.len(), positions.len()), "{context}");
            for n in &normals {
                let length = DVec3::from_array(n.map(f64::from)).length();
                assert!((length - 1.0).abs() < 1e-5, "{context}: normal {n:?}");
            }

            let indices_accessor = primitive.indices().expect(&context);
            assert!(matches!(
                indices_accessor.data_type(),
                gltf::accessor::DataType::U16 | gltf::accessor::DataType::U32
            ));
            let indices: Vec<u32> = reader.read_indices().expect(&context).into_u32().collect();
            assert!(!indices.is_empty() && indices.len().is_multiple_of(3), "{context}");
            assert!(indices.iter().all(|&i| (i as usize) < positions.len()), "{context}: index out of range");

            let position_accessor = primitive.get(&gltf::Semantic::Positions).expect(&context);
            // The JSON holds the shortest text of each f32 bound; read it back as f32.
            let bound = |value: Option<Value>| -> Vec<f32> {
                let array = value.expect("POSITION has min and max").as_array().expect("array").clone();
                array.iter().map(|v| v.as_f64().expect("number") as f32).collect()
            };
            let (min, max) = (bound(position_accessor.min()), bound(position_accessor.max()));
            for k in 0..3 {
                let values = positions.iter().map(|p| p[k]);
                assert_eq!(values.clone().fold(f32::INFINITY, f32::min), min[k], "{context}: min");
                assert_eq!(values.fold(f32::NEG_INFINITY, f32::max), max[k], "{context}: max");
            }
        }
    }
}

#[test]
fn nodes_are_named_as_listed() {
    let names: Vec<&str> = document().nodes().map(|n| n.name().expect("every node is named")).collect();
    assert_eq!(names, NODE_NAMES);
    assert!(document().meshes().all(|m| m.name().is_some()), "every mesh is named");
    let scene = document().default_scene().expect("a default scene");
    let mut reachable = 0;
    let mut stack: Vec<gltf::Node> = scene.nodes().collect();
    while let Some(node) = stack.pop() {
        reachable += 1;
        stack.extend(node.children());
    }
    assert_eq!(reachable, NODE_NAMES.len(), "every node is in the scene exactly once");
}

#[test]
fn cameras_are_perspective_and_look_into_the_room() {
    let worlds = world_matrices();
    for name in ["cam_overview", "cam_mirror", "cam_steps"] {
        let node = node(name);
        let camera = node.camera().expect("a camera");
        let gltf::camera::Projection::Perspective(perspective) = camera.projection() else {
            panic!("{name} is not perspective");
        };
        assert!((perspective.yfov() - 60f32.to_radians()).abs() < 1e-4);
        let world = worlds[node.index()];
        let eye = world.transform_point3(DVec3::ZERO);
        let forward = world.transform_vector3(DVec3::NEG_Z);
        assert!(eye.x.abs() < 8.0 && eye.z.abs() < 6.0 && eye.y > 0.0 && eye.y < 5.0, "{name} at {eye}");
        assert!(forward.z < -0.3 && forward.y < 0.0, "{name} looks along {forward}");
        assert!(world.transform_vector3(DVec3::X).y.abs() < 1e-6, "{name} is rolled");
    }
}

#[test]
fn steps_instance_one_mesh() {
    let meshes: BTreeSet<usize> =
        (1..=5).map(|i| node(&format!("step_{i}")).mesh().expect("a mesh").index()).collect();
    assert_eq!(meshes.len(), 1);
}

#[test]
fn materials_are_reflective_or_clearly_rough() {
    let reflective =
        ["mirror", "puddle", "glass", "water", "polished_marble", "brushed_metal", "rough_water"];
    for material in document().materials() {
        let name = material.name().expect("named");
        let pbr = material.pbr_metallic_roughness();
        let (metallic, roughness) = (pbr.metallic_factor(), pbr.roughness_factor());
        let transmission = material.transmission().map(|t| t.transmission_factor());
        match name {
            "mirror" => assert_eq!((metallic, roughness), (1.0, 0.02)),
            "puddle" => assert_eq!((metallic, roughness), (0.0, 0.03)),
            "glass" => assert_eq!((metallic, roughness, transmission), (0.0, 0.0, Some(1.0))),
            "polished_marble" => assert_eq!((metallic, roughness), (0.0, 0.05)),
            "water" => assert!(roughness < 0.1),
            // Glossy: reflective, with a blurred reflection.
            "brushed_metal" => assert_eq!((metallic, roughness), (1.0, 0.3)),
            "rough_water" => assert_eq!((metallic, roughness), (0.0, 0.15)),
            "lacquered_wood" => assert_eq!(roughness, 0.2),
            _ => assert!(
                !reflective.contains(&name) && metallic == 0.0 && roughness >= 0.5 && transmission.is_none(),
                "{name} would look reflective"
            ),
        }
    }
    assert_eq!(document().extensions_used().collect::<Vec<_>>(), ["KHR_materials_transmission"]);
    assert_eq!(document().extensions_required().count(), 0);
}

#[test]
fn only_water_table_top_and_metal_panel_carry_ppr_extras() {
    for node in document().nodes() {
        let extras: Option<Value> =
            node.extras().as_ref().map(|raw| serde_json::from_str(raw.get()).expect("extras are JSON"));
        let expected = match node.name() {
            Some("water_surface" | "pond_water") => {
                Some(serde_json::json!({"ppr": {"reflector": true, "kind": "water"}}))
            }
            Some("table_top") => Some(serde_json::json!({"ppr": {"reflector": false}})),
            Some("brushed_metal_panel") => Some(serde_json::json!({"ppr": {"reflector": true}})),
            _ => None,
        };
        assert_eq!(extras, expected, "{:?}", node.name());
    }
}

#[test]
fn mirrored_puddle_keeps_its_reflecting_side_up() {
    let puddle = node("puddle_c");
    assert!(world_matrices()[puddle.index()].determinant() < 0.0);
    for [a, b, c] in world_triangles(&puddle, 0) {
        // Counter-clockwise winding points down; the negative determinant makes clockwise the front.
        assert!((b - a).cross(c - a).normalize().dot(DVec3::NEG_Y) > 0.999);
    }
}

#[test]
fn puddles_are_non_convex_star_fans() {
    for name in ["puddle_a", "puddle_b", "puddle_c"] {
        let mesh = node(name).mesh().expect("a mesh");
        let primitive = mesh.primitives().next().expect("a primitive");
        let reader = primitive.reader(|buffer| Some(&IMPORTED.1[buffer.index()]));
        let outline: Vec<DVec3> = reader
            .read_positions()
            .expect("positions")
            .skip(1)
            .map(|p| DVec3::from_array(p.map(f64::from)))
            .collect();
        assert!((16..=24).contains(&outline.len()), "{name}: {} vertices", outline.len());
        let n = outline.len();
        let reflex = (0..n)
            .filter(|&i| {
                let (prev, here, next) = (outline[(i + n - 1) % n], outline[i], outline[(i + 1) % n]);
                (here - prev).cross(next - here).y < 0.0
            })
            .count();
        assert!(reflex >= 2, "{name} has {reflex} reflex vertices");
    }
}

#[test]
fn polished_floor_shares_vertices_along_internal_edges() {
    let mesh = node("polished_floor").mesh().expect("a mesh");
    let primitive = mesh.primitives().next().expect("a primitive");
    let reader = primitive.reader(|buffer| Some(&IMPORTED.1[buffer.index()]));
    let positions: Vec<[f32; 3]> = reader.read_positions().expect("positions").collect();
    let unique: BTreeSet<[u32; 3]> = positions.iter().map(|p| p.map(f32::to_bits)).collect();
    assert_eq!(unique.len(), positions.len(), "no duplicated vertices");
    // 6 × 2 cells plus 2 × 3 cells on a 1 m lattice: 7·3 + 3·3 lattice points.
    assert_eq!(positions.len(), 30);
    assert!(reader.read_indices().expect("indices").into_u32().count() / 3 > 4);
}

/// Every vertex lies in the rectangle's plane and inside it, and every side of the
/// rectangle touches a vertex (so it is tight).
fn check_rectangle_encloses(name: &str, rectangle: &Value, points: &[DVec3]) {
    let center = vec3(&rectangle["center"]);
    let (u, v, n) = (vec3(&rectangle["axis_u"]), vec3(&rectangle["axis_v"]), vec3(&rectangle["normal"]));
    let half = rectangle["half_extents"].as_array().expect("half extents");
    let (hu, hv) = (half[0].as_f64().expect("hu"), half[1].as_f64().expect("hv"));
    assert!((u.cross(v) - n).length() < 1e-5, "{name}: axes are not right-handed");
    let tolerance = 1e-5;
    let mut touches = [false; 4];
    for p in points {
        let d = *p - center;
        let (du, dv) = (d.dot(u), d.dot(v));
        assert!(d.dot(n).abs() < tolerance, "{name}: {p} off the plane");
        assert!(du.abs() <= hu + tolerance && dv.abs() <= hv + tolerance, "{name}: {p} outside");
        touches[0] |= (du - hu).abs() < tolerance;
        touches[1] |= (du + hu).abs() < tolerance;
        touches[2] |= (dv - hv).abs() < tolerance;
        touches[3] |= (dv + hv).abs() < tolerance;
    }
    assert_eq!(touches, [true; 4], "{name}: rectangle is not tight");
}

#[test]
fn ground_truth_matches_the_geometry_read_back() {
    let reflectors = EXPECTED["reflectors"].as_array().expect("reflectors");
    let names: Vec<&str> = reflectors.iter().map(|r| r["name"].as_str().expect("name")).collect();
    assert_eq!(
        names,
        [
            "mirror_wall",
            "glass_panel",
            "step_1",
            "step_2",
            "step_3",
            "step_4",
            "step_5",
            "tilted_mirror",
            "water_surface",
            "pond_water",
            "polished_floor",
            "brushed_metal_panel",
            "puddle_a",
            "puddle_b",
            "puddle_c"
        ]
    );
    for reflector in reflectors {
        let name = reflector["name"].as_str().expect("name");
        let node = node(reflector["node"].as_str().expect("node"));
        let primitive = reflector["primitive"].as_u64().expect("primitive") as usize;
        let flip = world_matrices()[node.index()].determinant() < 0.0;
        let triangles = world_triangles(&node, primitive);
        let normal = vec3(&reflector["normal"]);
        let mut area = 0.0;
        for [a, b, c] in &triangles {
            let cross = (*b - *a).cross(*c - *a) * if flip { -1.0 } else { 1.0 };
            assert!((cross.normalize() - normal).length() < 1e-5, "{name}: normal");
            area += cross.length() * 0.5;
        }
        let expected_area = reflector["area"].as_f64().expect("area");
        assert!((area - expected_area).abs() < 1e-5 * expected_area.max(1.0), "{name}: area {area}");

        let points: Vec<DVec3> = triangles.iter().flatten().copied().collect();
        check_rectangle_encloses(name, &reflector["enclosing_rectangle"], &points);
        let rectangles = reflector["rectangles"].as_array().expect("rectangles");
        let rectangles_area: f64 = rectangles.iter().map(|r| r["area"].as_f64().expect("area")).sum();
        let coverage = reflector["coverage"].as_f64().expect("coverage");
        assert!((expected_area / rectangles_area - coverage).abs() < 1e-5, "{name}: coverage");
    }

    let floor = reflectors.iter().find(|r| r["name"] == "polished_floor").expect("the L floor");
    assert_eq!(floor["rectangles"].as_array().map(Vec::len), Some(2));
    assert_eq!(floor["coverage"], 1.0);
    assert_eq!(floor["enclosing_rectangle"]["half_extents"], serde_json::json!([3.0, 2.5]));
    let kinds: Vec<&str> = reflectors.iter().map(|r| r["kind"].as_str().expect("kind")).collect();
    assert_eq!(kinds.iter().filter(|k| **k == "transparent").count(), 1);
    assert_eq!(kinds.iter().filter(|k| **k == "water").count(), 2, "the basin and the pond");
    assert_eq!(EXPECTED["non_reflectors"][0]["node"], "table_top");
}

#[test]
fn reflective_words_name_only_reflective_nodes_and_meshes() {
    // Name-driven extractors treat every triangle under such a name as a candidate.
    let words = ["mirror", "glass", "water", "puddle", "chrome", "polished"];
    let reflective = ["mirror", "puddle", "glass", "water", "polished_marble", "rough_water"];
    for node in document().nodes() {
        let Some(mesh) = node.mesh() else { continue };
        let names = [node.name().expect("named"), mesh.name().expect("named")];
        if names.iter().any(|n| words.iter().any(|w| n.contains(w))) {
            for primitive in mesh.primitives() {
                let material = primitive.material().name().expect("named");
                assert!(reflective.contains(&material), "{names:?} holds non-reflective {material}");
            }
        }
    }
}
