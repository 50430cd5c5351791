//! What the scene calls for: glass panels (transparent atlas), water planes (a layer per
//! plane, edge stretch), normal maps — each against the exact reflection, and each absent
//! from the plan (no pass, no variant) when the frame has no such surface.

use glam::{DVec3, Vec3, Vec4};
use ppr_runtime::{Camera, Choice, FrameInputs, LayerPlacement, Projection, ReflectionSettings};
use ppr_tests::harness::{GpuFrame, compare, renderer, run};
use ppr_tests::masks::{interior, reference_edges};
use ppr_tests::scene::{Albedo, AnalyticScene, Frame};

const SIZE: [u32; 2] = [160, 120];

fn camera() -> Camera {
    Camera::look_at(DVec3::new(0.3, 1.9, 2.8), DVec3::new(-0.2, 0.4, -5.0), Vec3::Y, Projection::default())
}

/// Walls and boxes to reflect.
fn room(s: &mut AnalyticScene) {
    s.quad(
        DVec3::new(0.0, -0.001, -4.0),
        DVec3::X,
        DVec3::NEG_Z,
        [8.0, 8.0],
        Albedo::Solid(Vec3::splat(0.25)),
    );
    s.quad(DVec3::new(0.0, 2.5, -8.0), DVec3::X, DVec3::Y, [6.0, 2.5], Albedo::Waves(0.25));
    for side in [-1.0, 1.0] {
        s.quad(
            DVec3::new(4.5 * side, 2.5, -4.0),
            DVec3::Z,
            DVec3::Y,
            [6.0, 2.5],
            Albedo::Gradient(Vec3::new(0.9, 0.6, 0.2), Vec3::new(0.2, 0.5, 0.9)),
        );
    }
    s.cuboid(DVec3::new(-2.2, 0.0, -6.6), DVec3::new(-1.6, 2.0, -6.0), Vec3::new(0.1, 0.8, 0.2));
}

/// The room with a floor mirror (3.5 m × 3.5 m) in the middle.
fn floor_mirror_room() -> AnalyticScene {
    let mut s = AnalyticScene::default();
    room(&mut s);
    s.mirror("floor mirror", DVec3::new(0.0, 0.0, -4.0), DVec3::X, DVec3::NEG_Z, [3.5, 3.5]);
    s
}

/// An output's bits, pixel by pixel (for bit-for-bit comparisons).
fn output_bits(pixels: &[Vec4]) -> Vec<[u32; 4]> {
    pixels.iter().map(|v| v.to_array().map(f32::to_bits)).collect()
}

/// Error over `mask` pixels away from edges of `reference`.
fn compare_layer(
    frame: &Frame,
    pixels: &[Vec4],
    reference: &[Vec3],
    mask: impl Fn(usize) -> bool,
) -> ppr_tests::harness::Comparison {
    // `compare` reads `frame.reference`: compare against the given reference instead.
    let mut f = Frame { reference: reference.to_vec(), mirror: frame.mirror.clone(), ..frame.clone_images() };
    for (i, m) in f.mirror.iter_mut().enumerate() {
        if mask(i) {
            *m = Some(0);
        }
    }
    let edges = reference_edges(&f, 0.15);
    let smooth = interior(&f, 1, |i| mask(i) && !edges[i]);
    compare(&f, pixels, |i| smooth[i])
}

#[test]
fn a_glass_panel_over_a_floor_mirror_reflects_both() {
    let mut s = floor_mirror_room();
    // A glass table top 0.8 m above the mirror, covering part of it.
    s.glass("glass top", DVec3::new(0.6, 0.7, -2.2), DVec3::X, DVec3::NEG_Z, [2.0, 1.6]);
    let cam = camera();
    let frame = s.render(&cam, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let through_glass =
        |i: usize| frame.glass[i].is_some() && frame.mirror[i].is_some() && frame.on_screen[i];
    // Full-screen passes, then indirect ones: a mirror seen through the glass has the
    // glass's depth, and its tiles must still be classified active.
    let mut outputs = Vec::new();
    for indirect in [Choice::Off, Choice::On] {
        let mut r = renderer();
        r.plan_params.indirect = indirect;
        r.set_reflectors(&ppr_tests::harness::validated(&s.reflector_set()));
        let out = run(&mut r, &gpu, &cam);
        eprintln!("{}", out.plan);
        assert_eq!(out.plan.indirect, indirect == Choice::On);
        assert_eq!(out.plan.layers.len(), 1, "the glass panel gets a layer");
        assert!(out.plan.passes().contains(&"layers"));

        let glass_px = frame.glass.iter().filter(|g| g.is_some()).count();
        let mirror_under_glass =
            compare(&frame, &out.pixels, |i| through_glass(i) && interior(&frame, 0, |_| true)[i]);
        let glass =
            compare_layer(&frame, &out.layer_pixels, &frame.glass_reference, |i| frame.glass_on_screen[i]);
        let layer_elsewhere = out
            .layer_pixels
            .iter()
            .enumerate()
            .filter(|(i, p)| frame.glass[*i].is_none() && p.w > 0.0)
            .count();
        eprintln!(
            "indirect {indirect:?}, glass pixels {glass_px}: layer vs glass reference {glass:?}\n  mirror seen through the glass, main output {mirror_under_glass:?}\n  layer pixels outside the glass {layer_elsewhere}"
        );
        assert!(glass.pixels > 500, "{glass:?}");
        // Away from silhouettes, like the main reflection (35 dB there; see tests/it/reflection.rs).
        assert!(glass.psnr >= 30.0, "{glass:?}");
        assert!(mirror_under_glass.pixels > 300 && mirror_under_glass.psnr >= 20.0, "{mirror_under_glass:?}");
        assert_eq!(layer_elsewhere, 0, "the layer output covers only glass pixels");
        outputs.push(out.pixels);
    }
    let differing =
        (0..frame.mirror.len()).filter(|&i| through_glass(i) && outputs[0][i] != outputs[1][i]).count();
    assert_eq!(differing, 0, "indirect dispatch changes the mirror seen through the glass");
}

#[test]
fn indirect_dispatch_keeps_a_mirror_seen_through_glass_written_to_depth() {
    // A renderer whose depth pass writes the glass (the testbed's does): the mirror under
    // a large glass table is then not in the depth buffer, and the tiles that show it only
    // through the glass must still be classified active (the classification counts layers).
    let mut s = floor_mirror_room();
    s.glass("glass top", DVec3::new(0.0, 0.7, -3.0), DVec3::X, DVec3::NEG_Z, [3.4, 2.6]);
    // Looking down at the table, so that whole tiles show the mirror only through it.
    let cam = Camera::look_at(
        DVec3::new(0.0, 2.6, -0.5),
        DVec3::new(0.0, 0.0, -3.5),
        Vec3::Y,
        Projection::default(),
    );
    let mut frame = s.render(&cam, SIZE);
    for (d, g) in frame.depth.iter_mut().zip(&frame.glass_depth) {
        if let Some(g) = g {
            *d = *g;
        }
    }
    let gpu = GpuFrame::upload(&frame);
    let mut outputs = Vec::new();
    for indirect in [Choice::Off, Choice::On] {
        let mut r = renderer();
        r.plan_params.indirect = indirect;
        r.set_reflectors(&ppr_tests::harness::validated(&s.reflector_set()));
        let out = run(&mut r, &gpu, &cam);
        assert_eq!(out.plan.indirect, indirect == Choice::On, "{}", out.plan);
        outputs.push(out.pixels);
    }
    let through_glass = |i: usize| frame.glass[i].is_some() && frame.mirror[i].is_some();
    let shown = (0..frame.mirror.len()).filter(|&i| through_glass(i) && outputs[0][i].w > 0.0).count();
    let differing =
        (0..frame.mirror.len()).filter(|&i| through_glass(i) && outputs[0][i] != outputs[1][i]).count();
    eprintln!("{shown} reflections under the glass; {differing} differ with indirect dispatch");
    // Tiles (16 px) that show the mirror only through the glass: what the test is about.
    let [w, h] = SIZE;
    let glass_only_tiles = (0..w.div_ceil(16) * h.div_ceil(16))
        .filter(|t| {
            let (tx, ty) = (t % w.div_ceil(16), t / w.div_ceil(16));
            (0..256).all(|k| {
                let (x, y) = (tx * 16 + k % 16, ty * 16 + k / 16);
                x >= w || y >= h || through_glass((y * w + x) as usize)
            })
        })
        .count();
    eprintln!("{glass_only_tiles} tiles show the mirror only through the glass");
    assert!(glass_only_tiles >= 10, "{glass_only_tiles}");
    assert!(shown > 2000, "{shown}");
    assert_eq!(differing, 0, "indirect dispatch loses the mirror seen through the glass");
}

#[test]
fn water_planes_at_two_heights_get_a_layer_each() {
    let mut s = AnalyticScene::default();
    room(&mut s);
    s.water("lake", DVec3::new(0.0, 0.0, -4.5), DVec3::X, DVec3::NEG_Z, [3.5, 3.0]);
    s.water("basin", DVec3::new(2.0, 0.4, -1.5), DVec3::X, DVec3::NEG_Z, [1.0, 0.8]);
    let cam = camera();
    let frame = s.render(&cam, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let set = s.reflector_set();
    let on_screen_water = |i: usize| frame.mirror[i].is_some() && frame.on_screen[i];

    let mut r = renderer();
    r.plan_params.indirect = Choice::Off;
    r.set_reflectors(&ppr_tests::harness::validated(&set));
    let layered = run(&mut r, &gpu, &cam);
    assert_eq!(layered.plan.layers.len(), 2, "{}", layered.plan);
    assert!(layered.plan.visible.is_empty(), "both water planes are layers");
    let lake_and_basin = compare_layer(&frame, &layered.layer_pixels, &frame.reference, on_screen_water);

    // With one water layer, the smaller plane (the basin) goes into the main buffer.
    r.plan_params.max_water_layers = 1;
    let one = run(&mut r, &gpu, &cam);
    assert_eq!((one.plan.layers.len(), one.plan.visible.len()), (1, 1), "{}", one.plan);
    let merged: Vec<Vec4> =
        one.layer_pixels.iter().zip(&one.pixels).map(|(l, m)| if l.w > 0.0 { *l } else { *m }).collect();
    let split = compare_layer(&frame, &merged, &frame.reference, on_screen_water);
    eprintln!("two water layers {lake_and_basin:?}\n  one layer + main buffer {split:?}");
    assert!(lake_and_basin.pixels > 1500 && lake_and_basin.psnr >= 30.0, "{lake_and_basin:?}");
    assert!((split.psnr - lake_and_basin.psnr).abs() < 3.0, "{split:?} vs {lake_and_basin:?}");
}

#[test]
fn passes_recorded_in_fewer_compute_passes_give_the_same_images() {
    // The layer reflection in the reflection's compute pass (no barrier between them), the
    // tile classification and the reflection in the projection's (wgpu's barriers between
    // them): the same images as each in its own pass, the same dispatches, and the merged
    // passes untimed.
    let mut s = floor_mirror_room();
    s.glass("glass top", DVec3::new(0.6, 0.7, -2.2), DVec3::X, DVec3::NEG_Z, [2.0, 1.6]);
    s.water("basin", DVec3::new(-2.0, 0.3, -2.0), DVec3::X, DVec3::NEG_Z, [1.0, 0.8]);
    let cam = camera();
    let frame = s.render(&cam, SIZE);
    let gpu = GpuFrame::upload(&frame);
    // (layer placement, classification in the projection's pass, reflection in its own,
    // layered frames' reflection in its own)
    let layouts = [
        (LayerPlacement::OwnPass, false, true, false),
        (LayerPlacement::AfterReflection, false, false, false),
        (LayerPlacement::BeforeReflection, false, false, true),
        (LayerPlacement::BeforeReflection, false, false, false),
        (LayerPlacement::OwnPass, true, true, false),
        (LayerPlacement::BeforeReflection, true, false, true),
        (LayerPlacement::BeforeReflection, true, false, false),
        (LayerPlacement::OwnPass, true, false, false),
    ];
    for indirect in [Choice::Off, Choice::On] {
        let mut images = Vec::new();
        for (placement, classify_merged, reflection_own_pass, layered_own_pass) in layouts {
            let mut r = renderer();
            r.plan_params.indirect = indirect;
            r.debug.layer_placement = placement;
            r.debug.classify_own_pass = !classify_merged;
            r.debug.reflection_own_pass = reflection_own_pass;
            r.debug.layered_reflection_own_pass = layered_own_pass;
            r.set_reflectors(&ppr_tests::harness::validated(&s.reflector_set()));
            // The second frame: the first finds its slot dirty and clears it in a clear
            // pass, which puts the classification in a pass of its own.
            run(&mut r, &gpu, &cam);
            let out = run(&mut r, &gpu, &cam);
            assert_eq!((out.plan.layers.len(), out.plan.visible.len()), (2, 1), "{}", out.plan);
            assert_eq!(out.plan.indirect, indirect == Choice::On);
            // Each pass's timestamps: its own pass's, or none (the pass it joined covers it).
            // The reflection joins the projection's pass where no layer dispatch goes with
            // it, or where the layers go first (unless the bench keeps layered frames apart).
            let reflection_merged = !reflection_own_pass
                && (placement == LayerPlacement::OwnPass
                    || (placement == LayerPlacement::BeforeReflection && !layered_own_pass));
            let [classify, _, projection, reflection, layers, .., together] = r.passes_recorded();
            assert_eq!(
                (projection, reflection, together),
                (!reflection_merged, !reflection_merged, reflection_merged)
            );
            assert_eq!(
                classify,
                indirect == Choice::On && !classify_merged,
                "{placement:?} {classify_merged}"
            );
            assert_eq!(layers, placement == LayerPlacement::OwnPass, "{placement:?}");
            let reflected = out.layer_pixels.iter().filter(|p| p.w > 0.0).count();
            assert!(reflected > 300, "{placement:?}: {reflected} layer pixels with a reflection");
            images.push((
                placement,
                (classify_merged, reflection_merged),
                r.last_dispatch_count(),
                output_bits(&out.pixels),
                output_bits(&out.layer_pixels),
            ));
        }
        let (_, _, dispatches, main, layer) = &images[0];
        for (placement, merged, d, m, l) in &images[1..] {
            let what =
                format!("{indirect:?}, layers {placement:?}, (classify, reflection) merged {merged:?}");
            assert_eq!(d, dispatches, "{what}: dispatches");
            assert!(m == main, "{what}: the main output differs");
            assert!(l == layer, "{what}: the layer output differs");
        }
    }
}

#[test]
fn without_layers_the_reflection_shares_the_projection_s_compute_pass() {
    let s = floor_mirror_room();
    let cam = camera();
    let gpu = GpuFrame::upload(&s.render(&cam, SIZE));
    for indirect in [Choice::Off, Choice::On] {
        let mut outputs = Vec::new();
        for own_pass in [true, false] {
            let mut r = renderer();
            r.plan_params.indirect = indirect;
            r.debug.reflection_own_pass = own_pass;
            r.set_reflectors(&ppr_tests::harness::validated(&s.reflector_set()));
            let out = run(&mut r, &gpu, &cam);
            assert!(out.plan.layers.is_empty(), "{}", out.plan);
            let [_, _, projection, reflection, .., together] = r.passes_recorded();
            assert_eq!((projection, reflection, together), (own_pass, own_pass, !own_pass), "{indirect:?}");
            let reflected = out.pixels.iter().filter(|p| p.w > 0.0).count();
            assert!(reflected > 1000, "{indirect:?}: {reflected} pixels with a reflection");
            outputs.push((r.last_dispatch_count(), output_bits(&out.pixels)));
        }
        assert!(outputs[0] == outputs[1], "{indirect:?}: one compute pass changes the frame");
    }
}

#[test]
fn layers_are_planned_only_while_the_frame_gives_them_an_output() {
    // `layers: Auto` with `FrameInputs::new` (no layer output): from the second frame on,
    // the water planes go to the main buffer instead of layers nobody reads.
    let mut s = AnalyticScene::default();
    room(&mut s);
    s.water("lake", DVec3::new(0.0, 0.0, -4.5), DVec3::X, DVec3::NEG_Z, [3.5, 3.0]);
    let cam = camera();
    let frame = s.render(&cam, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let mut r = renderer();
    r.set_reflectors(&ppr_tests::harness::validated(&s.reflector_set()));
    let g = ppr_tests::gpu::gpu();
    let color = gpu.color.create_view(&Default::default());
    let aspect = if gpu.depth.format().has_depth_aspect() {
        wgpu::TextureAspect::DepthOnly
    } else {
        wgpu::TextureAspect::All
    };
    let depth = gpu.depth.create_view(&wgpu::TextureViewDescriptor { aspect, ..Default::default() });
    let output = gpu.output.create_view(&Default::default());
    let layer_output = gpu.layer_output.create_view(&Default::default());
    // A frame seen by `camera`, with a layer output never, always, or only when the plan
    // has layers (as the testbed passes it).
    #[derive(Clone, Copy, PartialEq)]
    enum Given {
        Never,
        Always,
        WhenPlanned,
    }
    let away =
        Camera::look_at(DVec3::new(0.3, 1.9, 2.8), DVec3::new(0.3, 1.9, 8.0), Vec3::Y, Projection::default());
    let frame_seen = |r: &mut ppr_runtime::ReflectionRenderer, camera: &Camera, given: Given| {
        let plan = r.prepare(camera, SIZE);
        let layers = given == Given::Always || (given == Given::WhenPlanned && !plan.layers.is_empty());
        let mut encoder = g.device.create_command_encoder(&Default::default());
        let inputs = FrameInputs {
            layer_output: layers.then_some(&layer_output),
            ..FrameInputs::new(&color, &depth, &output)
        };
        r.encode(&mut encoder, &inputs);
        g.queue.submit([encoder.finish()]);
        (plan.layers.len(), plan.visible.len())
    };
    let frame_with = |r: &mut ppr_runtime::ReflectionRenderer, layers: bool| {
        frame_seen(r, &cam, if layers { Given::Always } else { Given::Never })
    };
    // First frame: the renderer cannot know yet, and plans the layer.
    assert_eq!(frame_with(&mut r, false), (1, 0));
    // Then: no layer output seen, the lake is an ordinary reflector of the main buffer.
    assert_eq!(frame_with(&mut r, false), (0, 1));
    assert_eq!(frame_with(&mut r, true), (0, 1), "planned before this encode gave the output");
    assert_eq!(frame_with(&mut r, true), (1, 0), "the layer output is back");
    // A renderer that passes the output only when the plan has layers keeps them, also
    // through frames where no layer is in view.
    assert_eq!(frame_seen(&mut r, &away, Given::WhenPlanned), (0, 0), "looking away");
    assert_eq!(frame_seen(&mut r, &cam, Given::WhenPlanned), (1, 0));
    assert_eq!(frame_seen(&mut r, &away, Given::WhenPlanned), (0, 0));
    assert_eq!(frame_seen(&mut r, &cam, Given::WhenPlanned), (1, 0));
    // `On` plans them whatever the frame gives.
    r.plan_params.layers = Choice::On;
    assert_eq!(frame_with(&mut r, false), (1, 0));
    assert_eq!(frame_with(&mut r, false), (1, 0));
}

#[test]
fn water_edge_stretch_fills_reflections_missing_at_the_border() {
    let mut s = AnalyticScene::default();
    room(&mut s);
    s.water("lake", DVec3::new(0.0, 0.0, -4.5), DVec3::X, DVec3::NEG_Z, [3.5, 3.0]);
    // Looking down: the reflected walls' tops are above the screen.
    let cam = Camera::look_at(
        DVec3::new(0.0, 2.2, 1.5),
        DVec3::new(0.0, 0.0, -4.0),
        Vec3::Y,
        Projection::default(),
    );
    let frame = s.render(&cam, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let water = |i: usize| frame.mirror[i].is_some();
    let layer = |stretch: bool, full_walk: bool| {
        let mut r = renderer();
        r.settings = ReflectionSettings { water_edge_stretch: stretch, ..ReflectionSettings::ALL };
        r.debug.full_stretch_walk = full_walk;
        r.set_reflectors(&ppr_tests::harness::validated(&s.reflector_set()));
        let out = run(&mut r, &gpu, &cam);
        assert!(out.layer_pixels.iter().all(|p| p.is_finite()));
        out.layer_pixels
    };
    let count = |pixels: &[Vec4]| (0..pixels.len()).filter(|&i| water(i) && pixels[i].w > 0.0).count();
    let water_px = (0..frame.mirror.len()).filter(|&i| water(i)).count();
    let off_screen = (0..frame.mirror.len()).filter(|&i| water(i) && !frame.on_screen[i]).count();
    let stretched = layer(true, false);
    let (without, with) = (count(&layer(false, false)), count(&stretched));
    eprintln!(
        "{water_px} water pixels, {off_screen} reflect off-screen points; with a reflection: {without} without stretch, {with} with"
    );
    assert!(off_screen > 200, "the view must lose reflections at the border: {off_screen}");
    assert!(with >= without + off_screen / 2, "stretch fills at least half of them: {without} -> {with}");
    // The walk ends where its steps leave the layer's rectangle: the steps it skips read
    // nothing, so every pixel is bit for bit the full walk's.
    let full = layer(true, true);
    let differ = (0..full.len())
        .filter(|&i| full[i].to_array().map(f32::to_bits) != stretched[i].to_array().map(f32::to_bits))
        .count();
    assert_eq!(differ, 0, "pixels where the walk that stops at the rectangle differs from the full walk");
}

#[test]
fn normal_maps_bring_the_reflection_closer_to_the_bumpy_reference() {
    let mut s = AnalyticScene::default();
    room(&mut s);
    s.bumpy_mirror(
        "bumpy floor",
        DVec3::new(0.0, 0.0, -4.0),
        DVec3::X,
        DVec3::NEG_Z,
        [3.5, 3.5],
        (0.05, 0.6),
    );
    let cam = camera();
    let frame = s.render(&cam, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let mut r = renderer();
    r.set_reflectors(&ppr_tests::harness::validated(&s.reflector_set()));
    let mapped = run(&mut r, &gpu, &cam);
    assert!(mapped.plan.normal_maps && mapped.plan.passes().iter().any(|p| p.contains("normal maps")));
    r.plan_params.normal_maps = Choice::Off;
    let flat = run(&mut r, &gpu, &cam);
    assert!(!flat.plan.normal_maps);
    let mask = |i: usize| frame.on_screen[i];
    let (m, f) = (compare(&frame, &mapped.pixels, mask), compare(&frame, &flat.pixels, mask));
    eprintln!("bumpy mirror vs its exact reflection: flat {f:?}\n  normal-mapped {m:?}");
    assert!(m.pixels > 2000);
    assert!(m.mean_abs < 0.9 * f.mean_abs, "{f:?} -> {m:?}");
}

#[test]
fn without_glass_water_or_normal_maps_nothing_extra_runs() {
    let s = floor_mirror_room();
    let cam = camera();
    let frame = s.render(&cam, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let mut r = renderer();
    r.plan_params.indirect = Choice::Off;
    r.set_reflectors(&ppr_tests::harness::validated(&s.reflector_set()));
    let out = run(&mut r, &gpu, &cam);
    assert!(out.plan.layers.is_empty() && !out.plan.normal_maps, "{}", out.plan);
    assert_eq!(out.plan.passes(), vec!["clear (unless done ahead)", "projection", "reflection"]);
    assert_eq!(r.last_dispatch_count(), 3);
    assert!(out.layer_pixels.iter().all(|p| p.w == 0.0), "no layer output written");
}

#[test]
fn normal_maps_keep_the_flat_reflection_where_the_source_is_the_pixel_itself() {
    // A textured sheet 1 cm above a normal-mapped mirror: its pixels reflect into
    // themselves (whole offset 0, a sub-pixel fraction), so the normal-map path sees a
    // reflected point in the pixel it shades (`q == p`): the direction `normalize(q - p)` is
    // NaN. Its shading normal is the plane's, so the normal-mapped result must be the flat
    // reflection, bit for bit. (Depth occlusion off: with it, the sheet hides the mirror
    // under it and no such write happens; the reflection pass must still cope with one.)
    let mut s = AnalyticScene::default();
    room(&mut s);
    s.bumpy_mirror(
        "bumpy floor",
        DVec3::new(0.0, 0.0, -4.0),
        DVec3::X,
        DVec3::NEG_Z,
        [3.5, 3.5],
        (0.05, 0.6),
    );
    s.quad(DVec3::new(0.4, 0.01, -2.2), DVec3::X, DVec3::NEG_Z, [0.9, 0.7], Albedo::Waves(0.05));
    let cam = camera();
    let frame = s.render(&cam, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let mut r = renderer();
    r.plan_params.indirect = Choice::Off;
    r.plan_params.depth_occlusion = Choice::Off;
    r.set_reflectors(&ppr_tests::harness::validated(&s.reflector_set()));
    let mapped = run(&mut r, &gpu, &cam);
    assert!(mapped.plan.normal_maps, "{}", mapped.plan);
    r.plan_params.normal_maps = Choice::Off;
    let flat = run(&mut r, &gpu, &cam);
    let layout = ppr_runtime::EncodingLayout::for_resolution(SIZE[0], SIZE[1]);
    let self_sourced: Vec<usize> = (0..frame.color.len())
        .filter(|&i| {
            ppr_runtime::encoding::decode(flat.intermediate[i], &layout)
                .is_some_and(|d| d.whole_offset() == glam::Vec2::ZERO && flat.pixels[i].w > 0.0)
        })
        .collect();
    let differing: Vec<usize> =
        self_sourced.iter().copied().filter(|&i| mapped.pixels[i] != flat.pixels[i]).collect();
    eprintln!(
        "{} self-sourced pixels; {} differ with normal maps (first: {:?})",
        self_sourced.len(),
        differing.len(),
        differing.first().map(|&i| (i, mapped.pixels[i], flat.pixels[i]))
    );
    assert!(self_sourced.len() >= 100, "the sheet reflects into itself: {}", self_sourced.len());
    assert!(mapped.pixels.iter().all(|p| p.is_finite()));
    assert!(
        differing.is_empty(),
        "{} of {} self-sourced pixels changed",
        differing.len(),
        self_sourced.len()
    );
}
