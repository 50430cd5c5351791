//! Tile culling, indirect dispatch and the frame plan on random scenes and cameras:
//! culling never loses a write, tiles cover every reflector pixel, an empty frame
//! dispatches nothing.

use glam::{DVec3, Vec3, Vec4};
use ppr_runtime::{Camera, Choice, Projection, ReflectionRenderer};

use ppr_tests::gpu::read_buffer;
use ppr_tests::harness::{GpuFrame, renderer, run};
use ppr_tests::scene::{Albedo, AnalyticScene};

const SIZE: [u32; 2] = [96, 64];

/// xorshift64*: deterministic test randomness.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// Puddles: many small coplanar mirrors on the floor (one plane, one parallel group), the
/// case where a tile test that gives up on tiles straddling the plane culls nothing.
fn puddle_floor(rng: &mut Rng) -> AnalyticScene {
    let mut s = AnalyticScene::default();
    s.quad(
        DVec3::new(0.0, -0.001, 0.0),
        DVec3::X,
        DVec3::NEG_Z,
        [12.0, 12.0],
        Albedo::Solid(Vec3::splat(0.3)),
    );
    s.quad(DVec3::new(0.0, 3.0, -10.0), DVec3::X, DVec3::Y, [12.0, 3.0], Albedo::Waves(0.3));
    for _ in 0..3 {
        let c = DVec3::new(rng.range(-4.0, 4.0), 0.0, rng.range(-8.0, 0.0));
        let colour = Vec3::new(rng.next() as f32, rng.next() as f32, rng.next() as f32);
        s.cuboid(c - DVec3::new(0.4, 0.0, 0.4), c + DVec3::new(0.4, rng.range(0.5, 2.0), 0.4), colour);
    }
    for i in 0..24 {
        let c =
            DVec3::new(-5.0 + (i % 6) as f64 * 2.0 + rng.range(-0.3, 0.3), 0.0, -9.0 + (i / 6) as f64 * 2.5);
        s.mirror(
            &format!("puddle {i}"),
            c,
            DVec3::X,
            DVec3::NEG_Z,
            [rng.range(0.3, 0.8), rng.range(0.3, 0.8)],
        );
    }
    s
}

/// A random soup of mirrors (a stairway of parallel steps when `parallel`, else all
/// orientations different) among boxes, inside a room of coloured walls.
fn random_scene(rng: &mut Rng, parallel: bool) -> AnalyticScene {
    let mut s = AnalyticScene::default();
    s.quad(DVec3::new(0.0, -0.01, 0.0), DVec3::X, DVec3::NEG_Z, [12.0, 12.0], Albedo::Waves(0.2));
    s.quad(DVec3::new(0.0, 3.0, -10.0), DVec3::X, DVec3::Y, [12.0, 3.0], Albedo::Waves(0.3));
    for _ in 0..4 {
        let c = DVec3::new(rng.range(-5.0, 5.0), 0.0, rng.range(-8.0, 2.0));
        let size = DVec3::new(rng.range(0.3, 1.5), rng.range(0.3, 2.5), rng.range(0.3, 1.5));
        let colour = Vec3::new(rng.next() as f32, rng.next() as f32, rng.next() as f32);
        s.cuboid(
            c - DVec3::new(size.x, 0.0, size.z) * 0.5,
            c + DVec3::new(size.x * 0.5, size.y, size.z * 0.5),
            colour,
        );
    }
    let count = 5 + (rng.next() * 4.0) as usize;
    for i in 0..count {
        let name = format!("mirror {i}");
        if parallel {
            // Stairway steps: all facing up, at rising heights.
            let c = DVec3::new(rng.range(-3.0, 3.0), 0.1 + 0.2 * i as f64, rng.range(-6.0, 0.0));
            s.mirror(&name, c, DVec3::X, DVec3::NEG_Z, [rng.range(1.0, 2.5), rng.range(0.6, 1.5)]);
        } else {
            // Distinct orientations: tilted about a random axis by a distinct angle.
            let yaw = rng.range(0.0, std::f64::consts::TAU);
            let tilt = 0.15 + 0.3 * i as f64;
            let n = DVec3::new(tilt.sin() * yaw.cos(), tilt.cos(), tilt.sin() * yaw.sin()).normalize();
            let u = n.cross(DVec3::Y).try_normalize().unwrap_or(DVec3::X);
            let v = n.cross(u);
            let c = DVec3::new(rng.range(-3.0, 3.0), rng.range(0.1, 1.5), rng.range(-6.0, 0.0));
            s.mirror(&name, c, u, v, [rng.range(1.0, 2.5), rng.range(0.6, 1.5)]);
        }
    }
    s
}

fn random_camera(rng: &mut Rng) -> Camera {
    let eye = DVec3::new(rng.range(-3.0, 3.0), rng.range(1.0, 4.0), rng.range(3.0, 6.0));
    let target = DVec3::new(rng.range(-2.0, 2.0), rng.range(0.0, 1.0), rng.range(-6.0, -2.0));
    Camera::look_at(
        eye,
        target,
        Vec3::Y,
        Projection { fov_y: rng.range(0.6, 1.4) as f32, ..Default::default() },
    )
}

/// The set of a scene, with parallel groups by normal.
fn grouped_set(scene: &AnalyticScene) -> ppr_format::ReflectorSet {
    let mut set = scene.reflector_set();
    let mut normals: Vec<DVec3> = Vec::new();
    for r in &mut set.reflectors {
        let g = normals.iter().position(|n| n.dot(r.normal) > 1.0 - 1e-9).unwrap_or_else(|| {
            normals.push(r.normal);
            normals.len() - 1
        });
        r.parallel_group = g as u32;
    }
    set
}

fn configured(tile_culling: bool, parallel_rule: Choice) -> ReflectionRenderer {
    let mut r = renderer();
    r.plan_params.tile_culling = if tile_culling { Choice::On } else { Choice::Off };
    r.plan_params.parallel_rule = parallel_rule;
    r.plan_params.indirect = Choice::Off;
    r.debug_writes = true;
    r
}

fn debug_masks(r: &ReflectionRenderer) -> Vec<u32> {
    bytemuck::pod_collect_to_vec(&read_buffer(r.debug_writes_buffer().expect("debug writes on")))
}

#[test]
fn tile_culling_keeps_every_write_of_the_plain_loop_under_the_parallel_rule() {
    let mut rng = Rng(0x5eed_0001);
    let mut checked = 0usize;
    for case in 0..10 {
        let parallel = case % 2 == 0;
        let scene = if case >= 8 { puddle_floor(&mut rng) } else { random_scene(&mut rng, parallel) };
        let camera = random_camera(&mut rng);
        let frame = scene.render(&camera, SIZE);
        let gpu = GpuFrame::upload(&frame);
        let set = grouped_set(&scene);

        let mut plain = configured(false, Choice::On);
        plain.set_reflectors(&set);
        run(&mut plain, &gpu, &camera);
        let mut tiled = configured(true, Choice::On);
        tiled.set_reflectors(&set);
        let out = run(&mut tiled, &gpu, &camera);
        assert!(out.plan.tile_culling && out.plan.parallel_rule, "{}", out.plan);

        let (a, b) = (debug_masks(&plain), debug_masks(&tiled));
        let missing = a.iter().zip(&b).filter(|(p, t)| *p & !*t != 0).count();
        let extra = a.iter().zip(&b).filter(|(p, t)| *t & !*p != 0).count();
        let writes: usize = a.iter().map(|m| m.count_ones() as usize).sum();
        eprintln!(
            "case {case} ({} visible, parallel {parallel}): {writes} writes, {missing} lost by culling, {extra} extra",
            out.plan.visible.len()
        );
        assert_eq!(missing, 0, "tile culling lost writes in case {case}");
        assert_eq!(extra, 0, "culling only removes candidates; case {case}");
        checked += writes;
    }
    assert!(checked > 3_000, "the random scenes must produce writes: {checked}");
}

#[test]
fn without_parallel_shapes_culling_changes_no_pixel() {
    let mut rng = Rng(0x5eed_0002);
    for case in 0..4 {
        let scene = random_scene(&mut rng, false);
        let camera = random_camera(&mut rng);
        let frame = scene.render(&camera, SIZE);
        let gpu = GpuFrame::upload(&frame);
        let set = grouped_set(&scene);
        let groups: std::collections::HashSet<u32> =
            set.reflectors.iter().map(|r| r.parallel_group).collect();
        assert_eq!(groups.len(), set.reflectors.len(), "no two mirrors parallel");

        let mut plain = configured(false, Choice::Auto);
        plain.set_reflectors(&set);
        let a = run(&mut plain, &gpu, &camera);
        let mut tiled = configured(true, Choice::Auto);
        tiled.set_reflectors(&set);
        let b = run(&mut tiled, &gpu, &camera);
        assert!(!a.plan.parallel_rule && b.plan.parallel_rule);
        let bits = |o: &[Vec4]| o.iter().flat_map(|v| v.to_array().map(f32::to_bits)).collect::<Vec<_>>();
        let written = a.pixels.iter().filter(|p| p.w > 0.5).count();
        eprintln!("case {case}: {} visible, {written} reflection pixels", a.plan.visible.len());
        assert_eq!(a.intermediate, b.intermediate, "intermediate buffers differ in case {case}");
        assert!(bits(&a.pixels) == bits(&b.pixels), "images differ in case {case}");
    }
}

#[test]
fn active_tiles_cover_every_reflector_pixel() {
    let mut rng = Rng(0x5eed_0003);
    for case in 0..4 {
        let scene = random_scene(&mut rng, case % 2 == 0);
        let camera = random_camera(&mut rng);
        let frame = scene.render(&camera, SIZE);
        let gpu = GpuFrame::upload(&frame);
        let mut r = renderer();
        r.plan_params.indirect = Choice::On;
        r.set_reflectors(&grouped_set(&scene));
        let out = run(&mut r, &gpu, &camera);
        assert!(out.plan.indirect);
        let list: Vec<u32> =
            bytemuck::pod_collect_to_vec(&read_buffer(r.active_tiles_buffer().expect("buffers")));
        let active: std::collections::HashSet<u32> = list[4..4 + list[0] as usize].iter().copied().collect();
        let tiles_x = SIZE[0].div_ceil(16);
        let mut reflector_pixels = 0;
        for (i, m) in frame.mirror.iter().enumerate() {
            if m.is_some() && out.plan.visible.contains(&(m.unwrap() as u32)) {
                reflector_pixels += 1;
                let (x, y) = (i as u32 % SIZE[0], i as u32 / SIZE[0]);
                assert!(
                    active.contains(&(x / 16 + y / 16 * tiles_x)),
                    "pixel {x},{y} of a visible reflector outside the active tiles (case {case})"
                );
            }
        }
        eprintln!(
            "case {case}: {} of {} tiles active for {reflector_pixels} reflector pixels",
            active.len(),
            out.plan.tile_count()
        );
        assert!(reflector_pixels > 0);
    }
}

#[test]
fn indirect_dispatch_gives_the_same_reflection_on_reflector_pixels() {
    let mut rng = Rng(0x5eed_0004);
    let scene = random_scene(&mut rng, true);
    let camera = random_camera(&mut rng);
    let frame = scene.render(&camera, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let set = grouped_set(&scene);
    let mut full = renderer();
    full.plan_params.indirect = Choice::Off;
    full.set_reflectors(&set);
    let a = run(&mut full, &gpu, &camera);
    let mut tiles = renderer();
    tiles.plan_params.indirect = Choice::On;
    tiles.set_reflectors(&set);
    let b = run(&mut tiles, &gpu, &camera);
    let mut compared = 0;
    for (i, m) in frame.mirror.iter().enumerate() {
        if m.is_some() {
            compared += 1;
            assert_eq!(a.pixels[i], b.pixels[i], "pixel {i}");
        }
    }
    assert!(compared > 100, "{compared}");
}

#[test]
fn a_frame_without_visible_reflectors_dispatches_nothing() {
    let mut scene = AnalyticScene::default();
    scene.mirror("behind the camera", DVec3::new(0.0, 1.0, 5.0), DVec3::NEG_X, DVec3::Y, [1.0, 1.0]);
    scene.mirror("facing away", DVec3::new(0.0, 1.0, -5.0), DVec3::NEG_X, DVec3::Y, [1.0, 1.0]);
    scene.mirror("off to the side", DVec3::new(40.0, 1.0, -5.0), DVec3::X, DVec3::Y, [1.0, 1.0]);
    scene.quad(DVec3::new(0.0, 1.0, -8.0), DVec3::X, DVec3::Y, [5.0, 5.0], Albedo::Waves(0.3));
    let camera = Camera::look_at(
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, -1.0),
        Vec3::Y,
        Projection::default(),
    );
    let frame = scene.render(&camera, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let mut r = renderer();
    r.set_reflectors(&scene.reflector_set());
    let out = run(&mut r, &gpu, &camera);
    eprintln!("{}", out.plan);
    assert!(out.plan.is_empty());
    assert_eq!((out.plan.culled_frustum, out.plan.culled_back_side), (2, 1));
    assert_eq!(r.last_dispatch_count(), 0);
    assert!(out.plan.to_string().contains("nothing dispatched"));
    // And a visible one dispatches the plan's passes.
    let camera =
        Camera::look_at(DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, 1.0, 1.0), Vec3::Y, Projection::default());
    let out = run(&mut r, &gpu, &camera);
    assert_eq!(out.plan.visible.len(), 1, "{}", out.plan);
    assert!(r.last_dispatch_count() >= 3);
}

#[test]
fn tile_lists_stay_short_on_coplanar_puddles() {
    // Culling must pay where many shapes share a plane: a floor tile lists only the
    // puddles its pixels can reflect into, not all of them.
    let mut rng = Rng(0x5eed_0005);
    let scene = puddle_floor(&mut rng);
    let camera = Camera::look_at(
        DVec3::new(0.0, 3.0, 4.0),
        DVec3::new(0.0, 0.0, -5.0),
        Vec3::Y,
        Projection::default(),
    );
    let frame = scene.render(&camera, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let mut r = configured(true, Choice::On);
    r.debug_tile_lists = true;
    r.set_reflectors(&grouped_set(&scene));
    let out = run(&mut r, &gpu, &camera);
    let lengths = debug_masks(&r);
    let listed: Vec<u32> = lengths.iter().copied().filter(|&n| n != u32::MAX).collect();
    let overflowed = lengths.len() - listed.len();
    let mean = listed.iter().map(|&n| f64::from(n)).sum::<f64>() / listed.len().max(1) as f64;
    let longest = listed.iter().copied().max().unwrap_or(0);
    eprintln!(
        "{} visible puddles: mean list {mean:.2}, longest {longest}, {overflowed} pixels without a list",
        out.plan.visible.len()
    );
    assert!(out.plan.visible.len() >= 20);
    assert!(mean <= 0.25 * out.plan.visible.len() as f64, "mean list {mean}");
}
