//! The shipped demo level (`assets/demo_room.glb`): loads, lists its cameras, renders.

use std::path::PathBuf;

use glam::{DVec2, DVec3};
use ppr_format::{Reflector, ReflectorKind, ReflectorSet};
use ppr_testbed::camera_spec::{ProjectionChoice, pick_camera};
use ppr_testbed::{FrameImages, Level, LevelRenderer, ReflectedPointClass};

use crate::common::{gpu, timed};

pub fn asset(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets").join(name)
}

/// The demo level's reflectors, from the exact rectangles of `demo_room.expected.json`
/// (directions re-orthonormalised: the file rounds them to 1e-6).
pub fn demo_reflectors() -> ReflectorSet {
    let text = std::fs::read_to_string(asset("demo_room.expected.json")).expect("expected.json");
    let doc: serde_json::Value = serde_json::from_str(&text).expect("json");
    let v3 = |v: &serde_json::Value| {
        let a: Vec<f64> = v.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect();
        DVec3::new(a[0], a[1], a[2])
    };
    let mut set = ReflectorSet::new("assets/demo_room.glb");
    for r in doc["reflectors"].as_array().expect("reflectors") {
        let kind: ReflectorKind = r["kind"].as_str().expect("kind").parse().expect("kind");
        for (k, rect) in r["rectangles"].as_array().expect("rectangles").iter().enumerate() {
            let n = v3(&rect["normal"]).normalize();
            let u = v3(&rect["axis_u"]);
            let u = (u - n * n.dot(u)).normalize();
            let he = rect["half_extents"].as_array().expect("half extents");
            let half = DVec2::new(he[0].as_f64().expect("x"), he[1].as_f64().expect("y"));
            let id = set.next_id();
            let name = format!("{}#{k}", r["name"].as_str().expect("name"));
            let reflector = Reflector::new(id, name, kind, v3(&rect["center"]), n, u, half);
            set.reflectors.push(reflector);
        }
    }
    set.assign_parallel_groups();
    set.validate().expect("demo set is valid");
    set
}

#[test]
fn demo_level_loads_with_its_cameras() {
    let level = Level::load_gltf(asset("demo_room.glb")).expect("demo level");
    let names: Vec<&str> = level.cameras.iter().map(|c| c.name.as_str()).collect();
    for expected in ["cam_overview", "cam_mirror", "cam_steps"] {
        assert!(names.contains(&expected), "camera {expected} missing from {names:?}");
    }
    assert!(level.triangle_count() > 100, "{} triangles", level.triangle_count());
    assert!(!level.textures.is_empty(), "the demo level has base colour textures");
    let (lo, hi) = level.bounds().expect("bounds");
    assert!(lo.x <= -7.9 && hi.x >= 7.9 && hi.y >= 4.9, "bounds {lo} {hi}");
    // The table top is glossy but marked `{"ppr": {"reflector": false}}`.
    let table = level.instances.iter().find(|i| i.node_name == "table_top").expect("table_top");
    assert_eq!(table.reflector_hint, Some(false));
}

/// Every camera of the demo level sees reflectors; the mirror camera's reflection is
/// mostly on screen or background (a mirror facing the room).
#[test]
fn demo_level_renders_reflections_from_every_camera() {
    timed("demo_level_renders_reflections_from_every_camera", || {
        let level = Level::load_gltf(asset("demo_room.glb")).expect("demo level");
        let set = demo_reflectors();
        let g = gpu();
        let _guard = g.lock();
        let (device, queue) = (&g.ctx.device, &g.ctx.queue);
        let mut renderer = LevelRenderer::new(device, queue, &level, &set);
        for name in ["cam_overview", "cam_mirror", "cam_steps"] {
            let camera = pick_camera(&level, Some(name), ProjectionChoice::default()).expect("camera");
            let summary = renderer.render(device, queue, &camera, [192, 108]);
            let frame = FrameImages::read(device, queue, &renderer).expect("readback");
            let reflectors = frame.reflector_mask().count();
            let on = frame.on_screen_mask().count();
            let unclassified = frame
                .reflector_mask()
                .bits
                .iter()
                .zip(&frame.reference_class.data)
                .filter(|(r, c)| {
                    **r && ReflectedPointClass::from_u32(**c) == ReflectedPointClass::NotReflector
                })
                .count();
            eprintln!(
                "{name}: {} of {} planes rendered, {reflectors} reflector pixels, {on} on screen",
                summary.rendered_planes.len(),
                summary.planes
            );
            assert!(reflectors > 500, "{name}: only {reflectors} reflector pixels");
            assert!(on > 100, "{name}: only {on} on-screen reflector pixels");
            assert_eq!(unclassified, 0, "{name}: reflector pixels without a rendered plane");
        }
    });
}
