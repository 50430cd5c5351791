//! Merged plane groups (`ppr_runtime::plane_groups`): coplanar reflectors tested as one
//! plane with a grid lookup write what testing each of them writes, under every culling
//! variant, and the plan merges only what it may.

use glam::{DVec3, Vec3};
use ppr_runtime::{Camera, Choice, Projection, ReflectionRenderer, TestedEntry};

use ppr_tests::harness::{GpuFrame, Output, renderer, run, validated};
use ppr_tests::scene::{Albedo, AnalyticScene};

const SIZE: [u32; 2] = [128, 96];

/// A floor of `n` puddles in a grid (every third turned in the plane, some overlapping
/// their neighbour), a raised mirror platform (another plane), a wall and boxes.
fn puddle_floor(n: usize) -> AnalyticScene {
    let mut s = AnalyticScene::default();
    s.quad(
        DVec3::new(0.0, -0.001, -4.0),
        DVec3::X,
        DVec3::NEG_Z,
        [8.0, 8.0],
        Albedo::Solid(Vec3::splat(0.3)),
    );
    s.quad(DVec3::new(0.0, 3.0, -8.0), DVec3::X, DVec3::Y, [8.0, 3.0], Albedo::Waves(0.3));
    s.cuboid(DVec3::new(-1.0, 0.0, -5.0), DVec3::new(0.0, 1.5, -4.0), Vec3::new(0.9, 0.2, 0.1));
    s.cuboid(DVec3::new(1.0, 0.0, -3.0), DVec3::new(1.6, 0.8, -2.4), Vec3::new(0.1, 0.3, 0.9));
    s.mirror("platform", DVec3::new(2.5, 0.4, -6.0), DVec3::X, DVec3::NEG_Z, [0.8, 0.8]);
    let side = (n as f64).sqrt().ceil() as usize;
    let pitch = 6.0 / side as f64;
    for i in 0..n {
        let c = DVec3::new(-3.0 + (i % side) as f64 * pitch, 0.0, -7.0 + (i / side) as f64 * pitch);
        let angle = if i % 3 == 0 { 0.3 + 0.1 * (i % 7) as f64 } else { 0.0 };
        let u = DVec3::new(angle.cos(), 0.0, angle.sin());
        let v = DVec3::Y.cross(u);
        let half = if i % 5 == 0 { [0.7 * pitch, 0.3 * pitch] } else { [0.4 * pitch, 0.35 * pitch] };
        s.mirror(&format!("puddle {i}"), c, u, v, half);
    }
    s
}

fn cameras() -> Vec<Camera> {
    let look = |eye: DVec3, at: DVec3, fov: f32| {
        Camera::look_at(eye, at, Vec3::Y, Projection { fov_y: fov, ..Default::default() })
    };
    vec![
        look(DVec3::new(0.0, 2.5, 1.5), DVec3::new(0.0, 0.0, -4.5), 1.2),
        look(DVec3::new(-2.0, 1.2, 0.5), DVec3::new(1.0, 0.3, -5.0), 1.0),
        look(DVec3::new(2.5, 4.0, -1.0), DVec3::new(-1.0, 0.0, -5.0), 0.9),
    ]
}

/// A renderer with the given plane-group choice and culling, full-screen passes.
fn configured(groups: Choice, culling: Choice, super_tiles: Choice) -> ReflectionRenderer {
    let mut r = renderer();
    r.plan_params.plane_groups = groups;
    r.plan_params.tile_culling = culling;
    r.plan_params.super_tiles = super_tiles;
    r.plan_params.indirect = Choice::Off;
    r
}

fn written(out: &Output) -> usize {
    out.intermediate.iter().filter(|&&v| v != ppr_runtime::CLEAR_VALUE).count()
}

#[test]
fn a_merged_plane_writes_what_its_shapes_write() {
    let scene = puddle_floor(60);
    let set = validated(&scene.reflector_set());
    let (mut checked, mut total_differing) = (0usize, 0usize);
    for camera in cameras() {
        let gpu = GpuFrame::upload(&scene.render(&camera, SIZE));
        let mut plain = configured(Choice::Off, Choice::Off, Choice::Off);
        plain.set_reflectors(&set);
        let a = run(&mut plain, &gpu, &camera);
        let mut merged = configured(Choice::On, Choice::Off, Choice::Off);
        merged.set_reflectors(&set);
        let b = run(&mut merged, &gpu, &camera);
        let groups = b.plan.tested.iter().filter(|e| matches!(e, TestedEntry::PlaneGroup(_))).count();
        eprintln!("{}", b.plan);
        assert_eq!(groups, 1, "the puddles form one group, the platform stays apart: {}", b.plan);
        assert!(b.plan.tested.contains(&TestedEntry::Shape(0)), "the platform is tested alone");
        assert_eq!(b.plan.grouped_shapes + b.plan.tested.len() - 1, b.plan.visible.len());
        assert_eq!(a.plan.tested.len(), a.plan.visible.len(), "Off merges nothing");
        // The same writes, but where a reflection point lies within f32 rounding of a
        // puddle's edge (the pyramid's side planes and the grid's rectangle test round
        // differently there).
        let differing = a.intermediate.iter().zip(&b.intermediate).filter(|(x, y)| x != y).count();
        let n = written(&a);
        eprintln!("{n} pixels written, {differing} differ");
        assert!(n > 800, "the puddles must reflect something: {n}");
        assert!(differing * 1000 <= n, "{differing} of {n} written pixels differ");
        checked += n;
        total_differing += differing;

        // Block lists and super-tile lists treat the group's test like any other.
        for (culling, super_tiles) in [(Choice::On, Choice::Off), (Choice::On, Choice::On)] {
            let mut tiled = configured(Choice::On, culling, super_tiles);
            tiled.set_reflectors(&set);
            let c = run(&mut tiled, &gpu, &camera);
            assert!(c.plan.tile_culling, "{}", c.plan);
            assert_eq!(c.intermediate, b.intermediate, "culling {culling:?}, super-tiles {super_tiles:?}");
        }
    }
    eprintln!("{total_differing} of {checked} written pixels differ over the cameras");
}

#[test]
fn the_plan_merges_only_what_it_may() {
    let scene = puddle_floor(12);
    let camera = cameras().remove(0);
    let gpu = GpuFrame::upload(&scene.render(&camera, SIZE));
    let mut set = scene.reflector_set();
    let mut r = renderer();
    r.set_reflectors(&validated(&set));
    let out = run(&mut r, &gpu, &camera);
    let visible_puddles = out.plan.visible.len() - 1;
    assert!(visible_puddles >= r.plan_params.plane_group_min_shapes, "{}", out.plan);
    assert_eq!(out.plan.tested.len(), 2, "Auto merges the puddles: {}", out.plan);
    assert!(out.plan.to_string().contains("plane groups:"), "{}", out.plan);

    // Below the threshold, with debug write masks (which are per shape), or with one
    // member rougher than the plan renders: every visible shape tested alone.
    r.plan_params.plane_group_min_shapes = visible_puddles + 1;
    assert_eq!(run(&mut r, &gpu, &camera).plan.tested.len(), out.plan.visible.len());
    r.plan_params.plane_group_min_shapes = 2;
    r.debug.writes = true;
    assert_eq!(run(&mut r, &gpu, &camera).plan.tested.len(), out.plan.visible.len());
    r.debug.writes = false;
    set.reflectors[3].roughness = 0.9;
    r.set_reflectors(&validated(&set));
    let rough = run(&mut r, &gpu, &camera);
    assert_eq!(rough.plan.too_rough, 1);
    assert_eq!(rough.plan.grouped_shapes, 0, "{}", rough.plan);
}
