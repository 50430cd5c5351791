//! Tile culling, indirect dispatch and the frame plan on random scenes and cameras:
//! culling (flat tile lists and super-tile lists) never loses a write, overflowing lists
//! fall back without losing one, tiles cover every reflector pixel, an empty frame
//! dispatches nothing.

use glam::{DVec3, Vec3, Vec4};
use ppr_runtime::passes::super_tile_lists::{SUPER_LIST_CAPACITY, super_tile_grid};
use ppr_runtime::{Camera, Choice, Projection, ReflectionRenderer};

use ppr_tests::gpu::read_buffer;
use ppr_tests::harness::{GpuFrame, renderer, run};
use ppr_tests::random_scenes::{Rng, grouped_set, puddle_floor, random_camera, random_scene};
use ppr_tests::scene::{Albedo, AnalyticScene};

const SIZE: [u32; 2] = [96, 64];
/// The size of the list-length test.
const LIST_SIZE: [u32; 2] = [192, 128];

/// How the projection pass culls shapes.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Culling {
    /// Every pixel loops over every visible shape.
    Plain,
    /// Per-tile lists built from every visible shape.
    Tiles,
    /// Per-tile lists built from their super-tile's list.
    SuperTiles,
    /// Per-tile lists built by the projection itself (`PlanParams::fused_lists`).
    FusedTiles,
    /// The same from their super-tile's list.
    FusedSuperTiles,
}

impl Culling {
    fn super_tiles(self) -> bool {
        matches!(self, Self::SuperTiles | Self::FusedSuperTiles)
    }

    fn fused(self) -> bool {
        matches!(self, Self::FusedTiles | Self::FusedSuperTiles)
    }
}

const CULLED: [Culling; 2] = [Culling::Tiles, Culling::SuperTiles];

fn configured(culling: Culling, parallel_rule: Choice) -> ReflectionRenderer {
    let mut r = renderer();
    r.plan_params.tile_culling = if culling == Culling::Plain { Choice::Off } else { Choice::On };
    r.plan_params.super_tiles = if culling.super_tiles() { Choice::On } else { Choice::Off };
    // Forced both ways: `Auto` leaves it off on the software adapter.
    r.plan_params.fused_lists = if culling.fused() { Choice::On } else { Choice::Off };
    r.plan_params.parallel_rule = parallel_rule;
    r.plan_params.indirect = Choice::Off;
    r.debug.writes = true;
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

        let mut plain = configured(Culling::Plain, Choice::On);
        plain.set_reflectors(&ppr_tests::harness::validated(&set));
        run(&mut plain, &gpu, &camera);
        let a = debug_masks(&plain);
        let writes: usize = a.iter().map(|m| m.count_ones() as usize).sum();
        for culling in CULLED {
            let mut tiled = configured(culling, Choice::On);
            tiled.set_reflectors(&ppr_tests::harness::validated(&set));
            let out = run(&mut tiled, &gpu, &camera);
            assert!(out.plan.tile_culling && out.plan.parallel_rule, "{}", out.plan);
            assert_eq!(out.plan.super_tiles, culling.super_tiles(), "{}", out.plan);

            let b = debug_masks(&tiled);
            let missing = a.iter().zip(&b).filter(|(p, t)| *p & !*t != 0).count();
            let extra = a.iter().zip(&b).filter(|(p, t)| *t & !*p != 0).count();
            eprintln!(
                "case {case} ({} visible, parallel {parallel}, {culling:?}): {writes} writes, {missing} lost by culling, {extra} extra",
                out.plan.visible.len()
            );
            assert_eq!(missing, 0, "{culling:?} lost writes in case {case}");
            assert_eq!(extra, 0, "culling only removes candidates; case {case}, {culling:?}");
        }
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

        let mut plain = configured(Culling::Plain, Choice::Auto);
        plain.set_reflectors(&ppr_tests::harness::validated(&set));
        let a = run(&mut plain, &gpu, &camera);
        let bits = |o: &[Vec4]| o.iter().flat_map(|v| v.to_array().map(f32::to_bits)).collect::<Vec<_>>();
        let written = a.pixels.iter().filter(|p| p.w > 0.0).count();
        eprintln!("case {case}: {} visible, {written} reflection pixels", a.plan.visible.len());
        for culling in CULLED {
            let mut tiled = configured(culling, Choice::On);
            tiled.set_reflectors(&ppr_tests::harness::validated(&set));
            let b = run(&mut tiled, &gpu, &camera);
            assert!(!a.plan.parallel_rule && b.plan.parallel_rule);
            assert_eq!(
                a.intermediate, b.intermediate,
                "intermediate buffers differ in case {case}, {culling:?}"
            );
            assert!(bits(&a.pixels) == bits(&b.pixels), "images differ in case {case}, {culling:?}");
        }
    }
}

#[test]
fn uniform_and_storage_shape_tests_write_the_same_buffer() {
    // The plan reads the shape tests from a uniform copy when they fit; the storage path
    // (over 128 shapes and layers) must give the same frame, bit for bit, with and without
    // the parallel rule and tile culling.
    let mut rng = Rng(0x5eed_0007);
    let mut written = 0usize;
    for case in 0..4 {
        let parallel = case % 2 == 0;
        let scene = random_scene(&mut rng, parallel);
        let camera = random_camera(&mut rng);
        let frame = scene.render(&camera, SIZE);
        let gpu = GpuFrame::upload(&frame);
        let set = grouped_set(&scene);
        let culling = if case < 2 { Culling::Plain } else { Culling::Tiles };
        let rule = if parallel { Choice::On } else { Choice::Off };
        let mut uniform = configured(culling, rule);
        uniform.set_reflectors(&ppr_tests::harness::validated(&set));
        let a = run(&mut uniform, &gpu, &camera);
        let mut storage = configured(culling, rule);
        storage.plan_params.uniform_tests = Choice::Off;
        storage.set_reflectors(&ppr_tests::harness::validated(&set));
        let b = run(&mut storage, &gpu, &camera);
        assert!(a.plan.uniform_tests && !b.plan.uniform_tests, "{} / {}", a.plan, b.plan);
        assert_eq!(a.intermediate, b.intermediate, "intermediate buffers differ in case {case}");
        assert_eq!(debug_masks(&uniform), debug_masks(&storage), "writes differ in case {case}");
        written += a.intermediate.iter().filter(|&&v| v != ppr_runtime::CLEAR_VALUE).count();
    }
    assert!(written > 1_000, "the random scenes must produce writes: {written}");
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
        r.set_reflectors(&ppr_tests::harness::validated(&grouped_set(&scene)));
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
    full.set_reflectors(&ppr_tests::harness::validated(&set));
    let a = run(&mut full, &gpu, &camera);
    let mut tiles = renderer();
    tiles.plan_params.indirect = Choice::On;
    tiles.set_reflectors(&ppr_tests::harness::validated(&set));
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
    r.set_reflectors(&ppr_tests::harness::validated(&scene.reflector_set()));
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
    // Culling must pay where many shapes share a plane: a floor block lists only the
    // puddles its pixels can reflect into, not all of them. Twice the other tests' size,
    // so that a 32-pixel block covers as little of the view as 16-pixel tiles did.
    let mut rng = Rng(0x5eed_0005);
    let scene = puddle_floor(&mut rng);
    let camera = Camera::look_at(
        DVec3::new(0.0, 3.0, 4.0),
        DVec3::new(0.0, 0.0, -5.0),
        Vec3::Y,
        Projection::default(),
    );
    let frame = scene.render(&camera, LIST_SIZE);
    let gpu = GpuFrame::upload(&frame);
    let mut r = configured(Culling::Tiles, Choice::On);
    r.debug.tile_lists = true;
    r.set_reflectors(&ppr_tests::harness::validated(&grouped_set(&scene)));
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

    // Built from super-tile lists, every tile lists the same shapes: a super-tile's list
    // holds every shape any of its tiles would list (the box test is monotone), and the
    // super-tile lists themselves are shorter than the visible list.
    let mut s = configured(Culling::SuperTiles, Choice::On);
    s.debug.tile_lists = true;
    s.set_reflectors(&ppr_tests::harness::validated(&grouped_set(&scene)));
    let out = run(&mut s, &gpu, &camera);
    assert!(out.plan.super_tiles, "{}", out.plan);
    assert_eq!(debug_masks(&s), lengths, "tile lists differ when built from super-tile lists");
    let counts = super_tile_counts(&s, LIST_SIZE);
    eprintln!("super-tile lists: {counts:?} of {} visible", out.plan.visible.len());
    assert!(counts.iter().all(|&n| n as usize <= out.plan.visible.len()), "{counts:?}");
    assert!(counts.iter().any(|&n| (n as usize) < out.plan.visible.len()), "{counts:?}");
}

/// A floor of `n` small coplanar puddles (one parallel group) in a grid, under a wall and
/// boxes: enough shapes in one place that tile and super-tile lists overflow.
fn dense_puddles(n: usize) -> AnalyticScene {
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
    let side = (n as f64).sqrt().ceil() as usize;
    let pitch = 6.0 / side as f64;
    for i in 0..n {
        let c = DVec3::new(-3.0 + (i % side) as f64 * pitch, 0.0, -7.0 + (i / side) as f64 * pitch);
        s.mirror(&format!("puddle {i}"), c, DVec3::X, DVec3::NEG_Z, [0.4 * pitch, 0.4 * pitch]);
    }
    s
}

/// [`dense_puddles`] seen from above the near edge: the camera, the uploaded frame, the set.
fn dense_puddles_frame(n: usize) -> (Camera, GpuFrame, ppr_format::ReflectorSet) {
    let scene = dense_puddles(n);
    let camera = Camera::look_at(
        DVec3::new(0.0, 2.5, 1.5),
        DVec3::new(0.0, 0.0, -4.5),
        Vec3::Y,
        Projection { fov_y: 1.2, ..Default::default() },
    );
    let gpu = GpuFrame::upload(&scene.render(&camera, SIZE));
    (camera, gpu, grouped_set(&scene))
}

/// The super-tile list lengths of the last frame (over capacity: overflowed).
fn super_tile_counts(r: &ReflectionRenderer, size: [u32; 2]) -> Vec<u32> {
    let (x, y) = super_tile_grid(size);
    let words: Vec<u32> =
        bytemuck::pod_collect_to_vec(&read_buffer(r.super_tile_lists_buffer().expect("buffers")));
    words[..(x * y) as usize].to_vec()
}

#[test]
fn overflowing_tile_and_super_tile_lists_lose_no_write() {
    // 1 200 puddles in view: tiles that see the wall list more than 256 of them and
    // super-tiles more than 1 024, so both fallbacks run (a tile to its super-tile's list,
    // a super-tile to every visible shape). Under the parallel rule the intermediate buffer
    // is then exactly the plain loop's.
    let (camera, gpu, set) = dense_puddles_frame(1200);
    let mut plain = configured(Culling::Plain, Choice::On);
    plain.set_reflectors(&ppr_tests::harness::validated(&set));
    let a = run(&mut plain, &gpu, &camera);
    let written = a.intermediate.iter().filter(|&&v| v != ppr_runtime::CLEAR_VALUE).count();
    assert!(a.plan.visible.len() > 1024, "{}", a.plan);
    assert!(written > 500, "the puddles must reflect something: {written}");
    for culling in CULLED {
        let mut r = configured(culling, Choice::On);
        r.debug.tile_lists = true;
        r.set_reflectors(&ppr_tests::harness::validated(&set));
        let b = run(&mut r, &gpu, &camera);
        let lengths = debug_masks(&r);
        let overflowed = lengths.iter().filter(|&&n| n == u32::MAX).count();
        let counts = super_tile_counts(&r, SIZE);
        let super_overflowed = counts.iter().filter(|&&n| n > SUPER_LIST_CAPACITY).count();
        eprintln!(
            "{culling:?}: {} visible, {written} written, {overflowed} pixels in tiles whose list overflowed, \
             {super_overflowed} of {} super-tiles overflowed",
            b.plan.visible.len(),
            counts.len()
        );
        assert!(overflowed > 0, "some tile list must overflow ({culling:?})");
        if culling.super_tiles() {
            assert!(super_overflowed > 0, "some super-tile list must overflow: {counts:?}");
            assert!(super_overflowed < counts.len(), "and some must not: {counts:?}");
        }
        assert_eq!(a.intermediate, b.intermediate, "{culling:?} changed the intermediate buffer");
    }
}

#[test]
fn super_tiles_run_from_the_plan_threshold() {
    let (camera, gpu, set) = dense_puddles_frame(200);
    let mut r = renderer();
    // The thresholds count projection tests: coplanar puddles merged into a plane group
    // would be one.
    r.plan_params.plane_groups = Choice::Off;
    r.set_reflectors(&ppr_tests::harness::validated(&set));
    let out = run(&mut r, &gpu, &camera);
    let n = out.plan.visible.len();
    assert!(n >= r.plan_params.tile_culling_min_shapes && n < 512, "{}", out.plan);
    assert_eq!(out.plan.super_tiles, n >= r.plan_params.super_tiles_min_shapes, "{}", out.plan);
    r.plan_params.super_tiles_min_shapes = n;
    let out = run(&mut r, &gpu, &camera);
    assert!(out.plan.tile_culling && out.plan.super_tiles, "{}", out.plan);
    assert!(out.plan.to_string().contains("super-tiles"), "{}", out.plan);
    r.plan_params.super_tiles_min_shapes = n + 1;
    let out = run(&mut r, &gpu, &camera);
    assert!(out.plan.tile_culling && !out.plan.super_tiles, "{}", out.plan);
}

#[test]
fn the_default_plan_never_drops_a_reflection_the_plain_loop_shows() {
    // Issue 14, item 1: a table top over a mirror floor (parallel planes, one group) and
    // enough puddles that the plan turns tile culling on. The parallel rule used to come
    // with it and keep only the nearest plane per pixel: the floor then lost the
    // reflections of the box on the table. Whatever the plan picks, every write of the
    // plain loop without the rule must stay.
    let mut s = AnalyticScene::default();
    s.quad(DVec3::new(0.0, 3.0, -9.0), DVec3::X, DVec3::Y, [8.0, 3.0], Albedo::Waves(0.3));
    s.mirror("floor", DVec3::new(0.0, 0.0, -4.0), DVec3::X, DVec3::NEG_Z, [4.0, 4.0]);
    s.mirror("table top", DVec3::new(0.8, 0.8, -4.5), DVec3::X, DVec3::NEG_Z, [0.9, 0.6]);
    s.cuboid(DVec3::new(0.5, 0.8, -4.7), DVec3::new(1.0, 1.6, -4.3), Vec3::new(0.9, 0.2, 0.1));
    for i in 0..24 {
        let c = DVec3::new(-3.5 + (i % 8) as f64, 0.0, -0.6 - (i / 8) as f64 * 0.3);
        s.mirror(&format!("puddle {i}"), c, DVec3::X, DVec3::NEG_Z, [0.1, 0.1]);
    }
    let camera = Camera::look_at(
        DVec3::new(0.0, 1.6, 1.5),
        DVec3::new(0.4, 0.5, -4.0),
        Vec3::Y,
        Projection::default(),
    );
    let gpu = GpuFrame::upload(&s.render(&camera, SIZE));
    let set = grouped_set(&s);

    let mut plain = configured(Culling::Plain, Choice::Off);
    plain.set_reflectors(&ppr_tests::harness::validated(&set));
    run(&mut plain, &gpu, &camera);
    let a = debug_masks(&plain);
    let mut default = renderer();
    default.plan_params.indirect = Choice::Off;
    default.debug.writes = true;
    default.set_reflectors(&ppr_tests::harness::validated(&set));
    let out = run(&mut default, &gpu, &camera);
    let b = debug_masks(&default);
    let writes: usize = a.iter().map(|m| m.count_ones() as usize).sum();
    let missing = a.iter().zip(&b).filter(|(p, d)| *p & !*d != 0).count();
    eprintln!("{}\n{writes} writes in the plain loop, {missing} pixels lose some", out.plan);
    assert!(out.plan.tile_culling, "enough shapes for block lists: {}", out.plan);
    assert!(writes > 500, "{writes}");
    assert_eq!(missing, 0, "the default plan dropped reflections");
}

#[test]
fn lists_built_in_the_projection_are_the_block_list_pass_lists() {
    // The projection's own lists (workgroup memory) must be the block-list pass's, entry
    // for entry: the same length per block (overflow included: 1 200 puddles overflow
    // tiles and super-tiles), the same writes, the same intermediate buffer.
    let mut rng = Rng(0x5eed_0011);
    let mut frames = vec![dense_puddles_frame(1200)];
    for parallel in [true, false] {
        let scene = random_scene(&mut rng, parallel);
        let camera = random_camera(&mut rng);
        let gpu = GpuFrame::upload(&scene.render(&camera, SIZE));
        frames.push((camera, gpu, grouped_set(&scene)));
    }
    let mut overflowed = 0usize;
    for (case, (camera, gpu, set)) in frames.iter().enumerate() {
        for (separate, fused) in
            [(Culling::Tiles, Culling::FusedTiles), (Culling::SuperTiles, Culling::FusedSuperTiles)]
        {
            // `prefetch`: the fused lists load their first chunk before the box (the same
            // lists; the 1 200 puddles' blocks take several chunks).
            let lists = |culling: Culling, prefetch: bool| {
                let mut r = configured(culling, Choice::On);
                r.debug.tile_lists = true;
                r.debug.list_prefetch = prefetch;
                r.set_reflectors(&ppr_tests::harness::validated(set));
                let out = run(&mut r, gpu, camera);
                assert_eq!(out.plan.fused_lists, culling.fused(), "{}", out.plan);
                let mut w = configured(culling, Choice::On);
                w.debug.list_prefetch = prefetch;
                w.set_reflectors(&ppr_tests::harness::validated(set));
                let written = run(&mut w, gpu, camera);
                (debug_masks(&r), debug_masks(&w), written.intermediate)
            };
            let a = lists(separate, false);
            let listed = a.0.iter().filter(|&&n| n != u32::MAX).count();
            overflowed += a.0.len() - listed;
            eprintln!("case {case}, {fused:?}: {listed} pixels with a list, {} without", a.0.len() - listed);
            for prefetch in [false, true] {
                let b = lists(fused, prefetch);
                assert_eq!(a.0, b.0, "list lengths differ in case {case}, {fused:?}, prefetch {prefetch}");
                assert_eq!(a.1, b.1, "writes differ in case {case}, {fused:?}, prefetch {prefetch}");
                assert_eq!(
                    a.2, b.2,
                    "intermediate buffers differ in case {case}, {fused:?}, prefetch {prefetch}"
                );
            }
        }
    }
    assert!(overflowed > 0, "some list must overflow");
}

#[test]
fn blocks_wholly_inside_a_pyramid_skip_its_sides_without_changing_a_write() {
    // Block-list entries are flagged where the block's box of positions lies inside all
    // four sides of the shape's pyramid, and those pixels test only the plane. Switching
    // the flags off in the projection's own lists (`DebugOptions::no_inside_entries`) must
    // change no write and no value, with and without the parallel rule. (That the flags
    // occur at all is a matter of speed, measured on the GPU: docs/perf/runtime.md.)
    let mut rng = Rng(0x5eed_0017);
    let mut written = 0usize;
    for case in 0..4 {
        let parallel = case % 2 == 0;
        let scene = random_scene(&mut rng, parallel);
        let camera = random_camera(&mut rng);
        let gpu = GpuFrame::upload(&scene.render(&camera, SIZE));
        let set = grouped_set(&scene);
        let rule = if parallel { Choice::On } else { Choice::Off };
        let frame = |no_inside_entries: bool| {
            let mut r = configured(Culling::FusedTiles, rule);
            r.debug.no_inside_entries = no_inside_entries;
            r.set_reflectors(&ppr_tests::harness::validated(&set));
            let out = run(&mut r, &gpu, &camera);
            assert!(out.plan.tile_culling && out.plan.fused_lists, "{}", out.plan);
            (debug_masks(&r), out.intermediate)
        };
        let (flagged, plain) = (frame(false), frame(true));
        written += plain.1.iter().filter(|&&v| v != ppr_runtime::CLEAR_VALUE).count();
        assert_eq!(flagged.0, plain.0, "writes differ in case {case}");
        assert_eq!(flagged.1, plain.1, "intermediate buffers differ in case {case}");
    }
    assert!(written > 1000, "the scenes reflect something: {written} values");
}

#[test]
fn the_tile_loop_gives_the_indirect_dispatch_s_reflection() {
    // The default tile loop, and two workgroups walking the whole active-tile list (many
    // tiles each): the same output as one workgroup per tile by indirect dispatch, bit for
    // bit, glossy and mirror.
    let mut rng = Rng(0x5eed_0005);
    let scene = random_scene(&mut rng, true);
    let camera = random_camera(&mut rng);
    let frame = scene.render(&camera, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let set = grouped_set(&scene);
    for glossy in [true, false] {
        let mut outputs = Vec::new();
        for (indirect_dispatch, tile_loop) in [(true, None), (false, None), (false, Some(2))] {
            let mut r = renderer();
            r.plan_params.indirect = Choice::On;
            r.settings.glossy = glossy;
            r.debug.reflection_indirect_dispatch = indirect_dispatch;
            r.debug.reflection_tile_loop = tile_loop;
            r.set_reflectors(&ppr_tests::harness::validated(&set));
            let out = run(&mut r, &gpu, &camera);
            assert!(out.plan.indirect);
            let list: Vec<u32> =
                bytemuck::pod_collect_to_vec(&read_buffer(r.active_tiles_buffer().expect("buffers")));
            assert!(list[0] > 4, "several tiles per workgroup: {} active", list[0]);
            assert!(out.pixels.iter().filter(|p| p.w > 0.0).count() > 100);
            outputs.push(out.pixels);
        }
        for k in 1..3 {
            let differing = (0..outputs[0].len()).filter(|&i| outputs[0][i] != outputs[k][i]).count();
            assert_eq!(differing, 0, "glossy {glossy}: tile loop {k} changed {differing} pixels");
        }
    }
}

#[test]
fn the_occupancy_pad_leaves_the_projection_s_buffer_as_it_is() {
    // The bench's occupancy pad (workgroup memory no frame uses) only changes how many
    // workgroups fit on a multiprocessor: the same intermediate buffer, with fused lists.
    let mut rng = Rng(0x5eed_0025);
    let scene = random_scene(&mut rng, true);
    let camera = random_camera(&mut rng);
    let gpu = GpuFrame::upload(&scene.render(&camera, SIZE));
    let set = grouped_set(&scene);
    let buffer = |pad_kib: u32| {
        let mut r = configured(Culling::FusedTiles, Choice::On);
        r.debug.occupancy_pad_kib = pad_kib;
        r.set_reflectors(&ppr_tests::harness::validated(&set));
        let out = run(&mut r, &gpu, &camera);
        assert!(out.plan.fused_lists, "{}", out.plan);
        out.intermediate
    };
    let plain = buffer(0);
    assert!(plain.iter().any(|&v| v != ppr_runtime::CLEAR_VALUE), "the scene reflects something");
    assert_eq!(plain, buffer(8), "the occupancy pad changed the buffer");
}
