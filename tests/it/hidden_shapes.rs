//! Hidden-shape culling (`shaders/hidden_shapes.wgsl`): reflectors behind a wall are
//! skipped, those seen through its doorway or in front of it are not, and the frame is the
//! same bit for bit under every culling variant.

use glam::{DVec3, Vec3};
use ppr_runtime::{Camera, Choice, Projection, ReflectionRenderer, TestedEntry};

use ppr_tests::gpu::read_buffer;
use ppr_tests::harness::{GpuFrame, Output, renderer, run, validated};
use ppr_tests::scene::{Albedo, AnalyticScene};

const SIZE: [u32; 2] = [128, 96];

/// Names of the mirrors no pixel shows (behind the wall, away from its doorway).
const HIDDEN: [&str; 7] =
    ["behind 0", "behind 1", "behind 2", "behind 3", "side behind", "tilted behind", "far shelf"];

/// A floor, a wall across the view with a doorway, a back wall (sky above it), mirrors in
/// front of the wall (on the floor and a side wall), and mirrors behind it: four coplanar
/// ones (a plane group), a turned one, a tilted one and a shelf, all hidden, and one seen
/// through the doorway.
fn walled_room() -> AnalyticScene {
    let mut s = AnalyticScene::default();
    let grey = Albedo::Solid(Vec3::splat(0.35));
    s.quad(DVec3::new(0.0, 0.0, -5.0), DVec3::X, DVec3::NEG_Z, [8.0, 8.0], grey.clone());
    // The wall at z = -5 (facing the camera), with a doorway from x = -0.4 to 0.4 below 2 m.
    s.quad(DVec3::new(-2.2, 1.5, -5.0), DVec3::X, DVec3::Y, [1.8, 1.5], Albedo::Waves(0.5));
    s.quad(DVec3::new(2.2, 1.5, -5.0), DVec3::X, DVec3::Y, [1.8, 1.5], Albedo::Waves(0.4));
    s.quad(DVec3::new(0.0, 2.5, -5.0), DVec3::X, DVec3::Y, [0.4, 0.5], Albedo::Waves(0.6));
    s.quad(DVec3::new(0.0, 3.0, -10.0), DVec3::X, DVec3::Y, [10.0, 3.0], Albedo::Waves(0.3));
    s.cuboid(DVec3::new(-1.5, 0.0, -3.5), DVec3::new(-0.8, 1.0, -2.8), Vec3::new(0.9, 0.2, 0.1));
    s.mirror("front floor", DVec3::new(0.8, 0.001, -3.0), DVec3::X, DVec3::NEG_Z, [0.9, 0.9]);
    s.mirror("front side", DVec3::new(-3.5, 1.2, -3.0), DVec3::NEG_Z, DVec3::Y, [1.2, 1.0]);
    for i in 0..4 {
        let c = DVec3::new(-3.6 + 1.2 * (i % 2) as f64, 0.5 + (i / 2) as f64, -7.0);
        s.mirror(&format!("behind {i}"), c, DVec3::X, DVec3::Y, [0.5, 0.4]);
    }
    let turned = DVec3::new(1.0, 0.0, 1.0).normalize();
    s.mirror("side behind", DVec3::new(2.5, 1.0, -6.5), turned, DVec3::Y, [0.6, 0.6]);
    let tilted = DVec3::new(0.0, 1.0, 1.0).normalize();
    s.mirror("tilted behind", DVec3::new(-2.0, 1.5, -8.0), DVec3::X, tilted, [0.7, 0.5]);
    s.mirror("far shelf", DVec3::new(-2.5, 0.5, -7.5), DVec3::X, DVec3::NEG_Z, [1.0, 1.0]);
    s.mirror("through doorway", DVec3::new(0.0, 1.0, -8.0), DVec3::X, DVec3::Y, [1.0, 0.8]);
    s
}

fn camera() -> Camera {
    Camera::look_at(
        DVec3::new(0.3, 1.6, 1.0),
        DVec3::new(0.0, 1.0, -5.0),
        Vec3::Y,
        Projection { fov_y: 1.0, ..Default::default() },
    )
}

fn configured(hidden: Choice, culling: Choice, super_tiles: Choice, subgroups: Choice) -> ReflectionRenderer {
    let mut r = renderer();
    r.plan_params.hidden_culling = hidden;
    r.plan_params.tile_culling = culling;
    r.plan_params.super_tiles = super_tiles;
    r.plan_params.subgroup_cull = subgroups;
    r.plan_params.indirect = Choice::Off;
    r
}

/// Per entry of the plan's tested list, whether the hidden-shape pass found it seen.
fn seen(r: &ReflectionRenderer, out: &Output) -> Vec<bool> {
    let words: Vec<u32> =
        bytemuck::pod_collect_to_vec(&read_buffer(r.seen_tests_buffer().expect("prepared")));
    words[..out.plan.tested.len()].iter().map(|&w| w != 0).collect()
}

#[test]
fn reflectors_behind_a_wall_are_skipped_and_the_frame_is_the_same() {
    let scene = walled_room();
    let set = scene.reflector_set();
    let validated_set = validated(&set);
    let camera = camera();
    let gpu = GpuFrame::upload(&scene.render(&camera, SIZE));
    let mut plain = configured(Choice::Off, Choice::Off, Choice::Off, Choice::Off);
    plain.set_reflectors(&validated_set);
    let reference = run(&mut plain, &gpu, &camera);
    assert!(!reference.plan.hidden_culling);
    let written = reference.intermediate.iter().filter(|&&v| v != ppr_runtime::CLEAR_VALUE).count();
    assert!(written > 500, "the front mirrors reflect: {written} pixels written");

    let name = |i: u32| set.reflectors[i as usize].name.as_str();
    for (culling, super_tiles, subgroups) in [
        (Choice::Off, Choice::Off, Choice::Off),
        (Choice::Off, Choice::Off, Choice::On),
        (Choice::On, Choice::Off, Choice::Off),
        (Choice::On, Choice::On, Choice::Off),
    ] {
        let mut r = configured(Choice::On, culling, super_tiles, subgroups);
        r.set_reflectors(&validated_set);
        let out = run(&mut r, &gpu, &camera);
        let variant = format!("culling {culling:?}, super-tiles {super_tiles:?}, subgroups {subgroups:?}");
        assert!(out.plan.hidden_culling, "{variant}: {}", out.plan);
        assert!(out.plan.passes().contains(&"hidden shapes"));
        let seen = seen(&r, &out);
        let mut hidden_names = Vec::new();
        let mut groups = 0;
        for (entry, &s) in out.plan.tested.iter().zip(&seen) {
            match *entry {
                TestedEntry::Shape(i) => {
                    assert_eq!(!s, HIDDEN.contains(&name(i)), "{variant}: {} seen: {s}", name(i));
                    if !s {
                        hidden_names.push(name(i));
                    }
                }
                TestedEntry::PlaneGroup(_) => {
                    // The four mirrors behind the wall at z = -7.
                    groups += 1;
                    assert!(!s, "{variant}: the group behind the wall is hidden");
                    hidden_names.extend(&HIDDEN[..4]);
                }
                TestedEntry::ParallelTree(_) => panic!("no tree at this size"),
            }
        }
        assert_eq!(groups, 1, "{variant}: the four mirrors behind form a plane group: {}", out.plan);
        assert_eq!(hidden_names.len(), HIDDEN.len(), "{variant}: skipped {hidden_names:?}");
        assert_eq!(out.intermediate, reference.intermediate, "{variant}: the intermediate buffer");
        assert_eq!(out.pixels, reference.pixels, "{variant}: the reflection");
    }
}

#[test]
fn the_plan_culls_hidden_shapes_only_where_it_is_exact() {
    let scene = walled_room();
    let camera = camera();
    let gpu = GpuFrame::upload(&scene.render(&camera, SIZE));
    let mut r = configured(Choice::Auto, Choice::Off, Choice::Off, Choice::Off);
    r.set_reflectors(&validated(&scene.reflector_set()));
    let tested = run(&mut r, &gpu, &camera).plan.tested.len();
    r.plan_params.hidden_culling_min_shapes = tested;
    assert!(run(&mut r, &gpu, &camera).plan.hidden_culling, "Auto from the threshold on");
    r.plan_params.hidden_culling_min_shapes = tested + 1;
    assert!(!run(&mut r, &gpu, &camera).plan.hidden_culling, "Auto below the threshold");
    r.plan_params.hidden_culling = Choice::On;
    for (what, change) in [
        (
            "without depth occlusion",
            (|p: &mut ppr_runtime::PlanParams| p.depth_occlusion = Choice::Off) as fn(&mut _),
        ),
        ("without source boxes", |p| p.source_boxes = Choice::Off),
        ("with the parallel rule", |p| p.parallel_rule = Choice::On),
    ] {
        let saved = r.plan_params;
        change(&mut r.plan_params);
        let plan = run(&mut r, &gpu, &camera).plan;
        assert!(!plan.hidden_culling, "{what}: {plan}");
        assert!(!plan.passes().contains(&"hidden shapes"), "{what}");
        r.plan_params = saved;
    }
}
