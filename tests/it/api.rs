//! How the runtime's API is used in a real frame loop: more than one `encode` per
//! `prepare`, several views prepared before one submit, and sets that were never validated.

use glam::{DVec3, Vec3, Vec4};
use ppr_runtime::{Camera, Choice, FrameInputs, Projection, ReflectionRenderer};

use ppr_tests::gpu::{gpu, read_buffer};
use ppr_tests::harness::{GpuFrame, read_rgba16f, renderer, run};
use ppr_tests::views::{SIZE, pond_views, room, room_camera, two_views_of};

/// Records `r`'s last prepared frame with `frame`'s colour and depth into `output`.
fn encode_into(
    r: &ReflectionRenderer,
    encoder: &mut wgpu::CommandEncoder,
    frame: &GpuFrame,
    output: &wgpu::Texture,
) {
    let color = frame.color.create_view(&Default::default());
    let depth = frame.depth.create_view(&wgpu::TextureViewDescriptor {
        aspect: wgpu::TextureAspect::DepthOnly,
        ..Default::default()
    });
    let output = output.create_view(&Default::default());
    r.encode(encoder, &FrameInputs::new(&color, &depth, &output));
}

/// The active-tile count the classification left in the renderer's buffer.
fn active_tile_count(r: &ReflectionRenderer) -> u32 {
    active_tile_header(r)[0]
}

/// The last frame's active-tile count and indirect dispatch arguments (x, y, z).
fn active_tile_header(r: &ReflectionRenderer) -> [u32; 4] {
    let words: Vec<u32> =
        bytemuck::pod_collect_to_vec(&read_buffer(r.active_tiles_buffer().expect("prepared")));
    [words[0], words[1], words[2], words[3]]
}

fn bits(pixels: &[Vec4]) -> Vec<u32> {
    pixels.iter().flat_map(|p| p.to_array().map(f32::to_bits)).collect()
}

#[test]
fn a_second_encode_per_prepare_gives_the_same_output_as_the_first() {
    let s = room();
    let cam = room_camera(DVec3::new(0.3, 1.6, 2.0));
    let gpu_frame = GpuFrame::upload(&s.render(&cam, SIZE));
    let g = gpu();
    for indirect in [Choice::On, Choice::Off] {
        let mut r = renderer();
        r.plan_params.indirect = indirect;
        r.set_reflectors(&ppr_tests::harness::validated(&s.reflector_set()));
        let plan = r.prepare(&cam, SIZE).clone();
        assert_eq!(plan.indirect, indirect == Choice::On, "{plan}");
        let mut outputs = Vec::new();
        let mut counts = Vec::new();
        // Three encodes of one prepare: two in one encoder, then one in another submit.
        let outs: Vec<wgpu::Texture> = (0..3).map(|_| fresh_output()).collect();
        let mut encoder = g.device.create_command_encoder(&Default::default());
        encode_into(&r, &mut encoder, &gpu_frame, &outs[0]);
        g.queue.submit([encoder.finish()]);
        counts.push(active_tile_count(&r));
        let mut encoder = g.device.create_command_encoder(&Default::default());
        encode_into(&r, &mut encoder, &gpu_frame, &outs[1]);
        encode_into(&r, &mut encoder, &gpu_frame, &outs[2]);
        g.queue.submit([encoder.finish()]);
        counts.push(active_tile_count(&r));
        for o in &outs {
            outputs.push(read_rgba16f(o));
        }
        let found = outputs[0].iter().filter(|p| p.w > 0.0).count();
        eprintln!(
            "indirect {indirect:?}: {found} pixels with a reflection; active-tile counts {counts:?} of {} tiles",
            plan.tile_count()
        );
        assert!(found > 500, "{found}");
        if plan.indirect {
            assert!(counts[0] > 0 && counts[0] < plan.tile_count(), "{counts:?}");
            assert_eq!(counts[1], counts[0], "each encode counts the active tiles from zero");
        }
        assert!(bits(&outputs[1]) == bits(&outputs[0]), "the second encode changed the output");
        assert!(bits(&outputs[2]) == bits(&outputs[0]), "the third encode changed the output");
    }
}

/// An output texture for `SIZE`, zero-initialised.
fn fresh_output() -> wgpu::Texture {
    gpu().device.create_texture(&wgpu::TextureDescriptor {
        label: Some("test output"),
        size: wgpu::Extent3d { width: SIZE[0], height: SIZE[1], depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: ppr_runtime::OUTPUT_FORMAT,
        usage: wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}

/// The scene's set, two cameras on it and their frames (a split screen's two views).
fn two_views() -> (ppr_format::ReflectorSet, [Camera; 2], Vec<GpuFrame>) {
    two_views_of(&room())
}

#[test]
fn views_prepared_before_one_submit_each_get_their_own_camera() {
    // Split screen (or two probes) with one renderer, and with one renderer per view:
    // prepare, encode, prepare, encode, then one submit.
    let (set, cams, frames) = two_views();
    let g = gpu();
    for indirect in [Choice::Off, Choice::On] {
        // Each view alone.
        let alone: Vec<Vec<Vec4>> = cams
            .iter()
            .zip(&frames)
            .map(|(c, f)| {
                let mut r = renderer();
                r.plan_params.indirect = indirect;
                r.set_reflectors(&ppr_tests::harness::validated(&set));
                run(&mut r, f, c).pixels
            })
            .collect();
        assert!(bits(&alone[0]) != bits(&alone[1]), "the two views must differ");
        // One renderer for both views.
        let mut shared = renderer();
        shared.plan_params.indirect = indirect;
        shared.set_reflectors(&ppr_tests::harness::validated(&set));
        let outs = [fresh_output(), fresh_output()];
        let mut encoder = g.device.create_command_encoder(&Default::default());
        for k in 0..2 {
            shared.prepare(&cams[k], SIZE);
            encode_into(&shared, &mut encoder, &frames[k], &outs[k]);
        }
        g.queue.submit([encoder.finish()]);
        // One renderer per view, both prepared before either is encoded.
        let mut own = [renderer(), renderer()];
        let own_outs = [fresh_output(), fresh_output()];
        for (k, r) in own.iter_mut().enumerate() {
            r.plan_params.indirect = indirect;
            r.set_reflectors(&ppr_tests::harness::validated(&set));
            r.prepare(&cams[k], SIZE);
        }
        let mut encoder = g.device.create_command_encoder(&Default::default());
        for k in 0..2 {
            encode_into(&own[k], &mut encoder, &frames[k], &own_outs[k]);
        }
        g.queue.submit([encoder.finish()]);
        for k in 0..2 {
            let (a, b) = (read_rgba16f(&outs[k]), read_rgba16f(&own_outs[k]));
            let differing = (0..a.len()).filter(|&i| a[i] != alone[k][i]).count();
            eprintln!(
                "indirect {indirect:?}, view {k}: one renderer for both views: {differing} pixels differ from the view alone"
            );
            assert_eq!(
                differing, 0,
                "view {k} (one renderer, indirect {indirect:?}) got another camera's result"
            );
            assert!(bits(&b) == bits(&alone[k]), "view {k} (own renderer, indirect {indirect:?})");
        }
    }
}

#[test]
fn a_set_that_breaks_an_invariant_never_reaches_the_renderer() {
    // The renderer takes only a ValidatedSet: the broken set is refused when validated,
    // naming the field, and the renderer keeps what it had.
    let s = room();
    let mut bad = s.reflector_set();
    bad.reflectors[0].occluders = vec![7];
    let mut r = renderer();
    let err = ppr_format::ValidatedSet::new(bad).expect_err("an occluder index out of range");
    let field = err.field_path();
    eprintln!("{err}");
    assert_eq!(field.as_deref(), Some("reflectors[0].occluders[0]"), "{err}");
    // The renderer keeps what it had (nothing) and still renders frames.
    let cam = room_camera(DVec3::new(0.3, 1.6, 2.0));
    assert!(r.prepare(&cam, SIZE).is_empty());
    // A valid set afterwards renders.
    r.set_reflectors(&ppr_tests::harness::validated(&s.reflector_set()));
    assert_eq!(r.prepare(&cam, SIZE).visible.len(), 1);
}

#[test]
fn a_camera_from_the_games_matrices_renders_as_the_camera_it_describes() {
    // A game hands its view and projection matrices; without jitter the frame is the
    // fov-built camera's, bit for bit; a TAA jitter of half a pixel moves the reflection.
    let s = room();
    let cam = room_camera(DVec3::new(0.3, 1.6, 2.0));
    let frame = s.render(&cam, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let set = s.reflector_set();
    let view = glam::DMat4::from_rotation_translation(cam.rotation.as_dquat(), cam.position).inverse();
    let aspect = SIZE[0] as f32 / SIZE[1] as f32;
    let clip = cam.projection.clip_from_view(aspect);
    let from = Camera::from_matrices(view, clip, cam.projection.depth).expect("a rigid view");
    // f64 round trip of the rotation: the same camera to within rounding.
    let mut exact = from;
    exact.rotation = cam.rotation;
    exact.position = cam.position;

    let mut r = renderer();
    r.set_reflectors(&ppr_tests::harness::validated(&set));
    let a = run(&mut r, &gpu, &cam);
    let b = run(&mut r, &gpu, &exact);
    let written = a.pixels.iter().filter(|p| p.w > 0.0).count();
    assert!(written > 500, "the mirror must show a reflection: {written}");
    assert_eq!(bits(&a.pixels), bits(&b.pixels), "matrix camera differs from the fov camera");

    let jitter = glam::Mat4::from_translation(Vec3::new(1.0 / SIZE[0] as f32, 0.0, 0.0));
    let mut jittered = exact;
    jittered.projection.matrix = Some(jitter * clip);
    let c = run(&mut r, &gpu, &jittered);
    let changed = a.intermediate.iter().zip(&c.intermediate).filter(|(x, y)| x != y).count();
    assert!(changed * 10 > written, "a half-pixel jitter must move the projection: {changed} of {written}");
}

#[test]
fn an_empty_plan_reports_no_timings_without_waiting() {
    // Looking away from the only mirror: nothing visible, nothing recorded, no times (not
    // zeros, and not a wait for a frame that timed nothing).
    let s = room();
    let away = Camera::look_at(
        DVec3::new(0.0, 1.6, -3.0),
        DVec3::new(0.0, 1.6, 5.0),
        Vec3::Y,
        Projection::default(),
    );
    let frame = s.render(&away, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let mut r = renderer();
    r.set_reflectors(&ppr_tests::harness::validated(&s.reflector_set()));
    let out = run(&mut r, &gpu, &away);
    assert!(out.plan.is_empty(), "{}", out.plan);
    assert_eq!(r.passes_recorded(), [false; 9]);
    assert!(r.read_timings().is_none(), "an empty plan has no pass times");
    // A frame that ran passes still reports them where the adapter has timestamps.
    let cam = room_camera(DVec3::new(0.3, 1.6, 2.0));
    let gpu = GpuFrame::upload(&s.render(&cam, SIZE));
    run(&mut r, &gpu, &cam);
    if r.has_timestamps() {
        assert!(r.read_timings().is_some(), "a frame with passes reports times");
    }
    // Timed as a whole (the bench's frame span): the span's slot alone, where the device
    // writes timestamps between passes; nothing where it cannot.
    r.debug.frame_span = true;
    run(&mut r, &gpu, &cam);
    let spans = r.has_timestamps()
        && ppr_tests::gpu::gpu().device.features().contains(wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS);
    let recorded = r.passes_recorded();
    assert_eq!(recorded[..7], [false; 7], "no pass timed on its own");
    assert_eq!(recorded[7], spans, "the frame's span");
    assert!(!recorded[8], "no pass timed on its own");
    if let Some(t) = r.read_timings() {
        assert!(spans);
        let own: Vec<_> =
            t.passes().into_iter().filter(|(name, ms)| *name != "frame" && ms.is_some()).collect();
        assert!(own.is_empty(), "{own:?}");
    }
}

#[test]
fn each_eye_of_a_stereo_frame_is_its_mono_frame_bit_for_bit() {
    // One renderer, both eyes planned by one prepare_stereo and recorded by one
    // encode_stereo into the two layers of an array texture; a glossy floor mirror.
    let mut s = room();
    s.roughen("floor mirror", 0.25);
    let set = ppr_tests::harness::validated(&s.reflector_set());
    let head = DVec3::new(0.3, 1.6, 2.0);
    let eyes = [-0.032, 0.032].map(|dx| room_camera(head + DVec3::new(dx, 0.0, 0.0)));
    let frames: Vec<GpuFrame> = eyes.iter().map(|c| GpuFrame::upload(&s.render(c, SIZE))).collect();
    let g = gpu();
    for indirect in [Choice::Off, Choice::On] {
        let mono: Vec<Vec<Vec4>> = (0..2)
            .map(|k| {
                let mut r = renderer();
                r.plan_params.indirect = indirect;
                r.set_reflectors(&set);
                r.prepare(&eyes[k], SIZE);
                let out = fresh_output();
                let mut encoder = g.device.create_command_encoder(&Default::default());
                encode_into(&r, &mut encoder, &frames[k], &out);
                g.queue.submit([encoder.finish()]);
                read_rgba16f(&out)
            })
            .collect();
        assert!(bits(&mono[0]) != bits(&mono[1]), "the eyes must see different reflections");

        let mut r = renderer();
        r.plan_params.indirect = indirect;
        r.set_reflectors(&set);
        let plans = r.prepare_stereo([&eyes[0], &eyes[1]], SIZE);
        assert!(plans.iter().all(|p| p.glossy.len() == 1), "{}", plans[0]);
        let array = g.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("stereo output"),
            size: wgpu::Extent3d { width: SIZE[0], height: SIZE[1], depth_or_array_layers: 2 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: ppr_runtime::OUTPUT_FORMAT,
            usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let layer = |k: u32| {
            array.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(wgpu::TextureViewDimension::D2),
                base_array_layer: k,
                array_layer_count: Some(1),
                ..Default::default()
            })
        };
        let outputs = [layer(0), layer(1)];
        let colors = frames.iter().map(|f| f.color.create_view(&Default::default())).collect::<Vec<_>>();
        let depths = frames
            .iter()
            .map(|f| {
                f.depth.create_view(&wgpu::TextureViewDescriptor {
                    aspect: wgpu::TextureAspect::DepthOnly,
                    ..Default::default()
                })
            })
            .collect::<Vec<_>>();
        let inputs: Vec<FrameInputs> =
            (0..2).map(|k| FrameInputs::new(&colors[k], &depths[k], &outputs[k])).collect();
        let mut encoder = g.device.create_command_encoder(&Default::default());
        r.encode_stereo(&mut encoder, [&inputs[0], &inputs[1]]);
        // Each layer into a texture of its own, to read back.
        let copies = [fresh_output(), fresh_output()];
        for (k, copy) in copies.iter().enumerate() {
            encoder.copy_texture_to_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &array,
                    mip_level: 0,
                    origin: wgpu::Origin3d { x: 0, y: 0, z: k as u32 },
                    aspect: wgpu::TextureAspect::All,
                },
                copy.as_image_copy(),
                wgpu::Extent3d { width: SIZE[0], height: SIZE[1], depth_or_array_layers: 1 },
            );
        }
        g.queue.submit([encoder.finish()]);
        for k in 0..2 {
            let stereo = read_rgba16f(&copies[k]);
            let differing = (0..stereo.len())
                .filter(|&i| {
                    stereo[i].to_array().map(f32::to_bits) != mono[k][i].to_array().map(f32::to_bits)
                })
                .count();
            eprintln!("indirect {indirect:?}, eye {k}: {differing} pixels differ from the mono frame");
            assert_eq!(differing, 0, "eye {k}, indirect {indirect:?}");
        }
    }
}

#[test]
fn frames_reuse_their_upload_buffers() {
    // Each encode writes its view's upload into a staging buffer that comes back once the
    // encoder's commands have run: frames submitted one after the other reuse one, and an
    // encoder dropped without a submit loses its buffer but breaks nothing.
    let (set, cams, frames) = two_views();
    let mut r = renderer();
    r.set_reflectors(&ppr_tests::harness::validated(&set));
    let first: Vec<Vec<Vec4>> = (0..2).map(|k| run(&mut r, &frames[k], &cams[k]).pixels).collect();
    assert!(bits(&first[0]) != bits(&first[1]), "the two views must differ");
    for round in 0..3 {
        for k in 0..2 {
            let again = run(&mut r, &frames[k], &cams[k]).pixels;
            assert!(
                bits(&again) == bits(&first[k]),
                "view {k}, round {round}: a reused buffer changed the frame"
            );
        }
    }
    assert!(
        r.upload_buffers_created() <= 2,
        "8 frames, each waited for, created {} staging buffers",
        r.upload_buffers_created()
    );
    // An encoder recorded and dropped: its staging buffer never comes back.
    let g = gpu();
    r.prepare(&cams[0], SIZE);
    let out = fresh_output();
    let mut dropped = g.device.create_command_encoder(&Default::default());
    encode_into(&r, &mut dropped, &frames[0], &out);
    drop(dropped);
    let after = run(&mut r, &frames[1], &cams[1]).pixels;
    assert!(bits(&after) == bits(&first[1]), "the frame after a dropped encoder");
}

#[test]
fn a_small_level_s_upload_is_one_copy() {
    // Every part of a frame's upload (uniforms, layers, shapes, lists, tests, glossy
    // reflectors) lies in one buffer, close together for a small level: one copy command
    // carries them all, and the frames are those of one copy per part, bit for bit (two
    // views by turns, a water layer and a glossy pond, direct and indirect frames).
    let (set, cams, frames) = pond_views();
    for indirect in [Choice::Off, Choice::On] {
        let mut one = renderer();
        let mut each = renderer();
        each.debug.separate_upload_copies = true;
        for r in [&mut one, &mut each] {
            r.plan_params.indirect = indirect;
            r.set_reflectors(&set);
        }
        for (k, v) in [0, 1, 1, 0].into_iter().enumerate() {
            let a = run(&mut one, &frames[v], &cams[v]);
            let b = run(&mut each, &frames[v], &cams[v]);
            let what = format!("{indirect:?}, frame {k} (view {v})");
            assert!(!a.plan.layers.is_empty() && !a.plan.visible.is_empty(), "{what}: {}", a.plan);
            assert_eq!(one.last_upload_copy_count(), 1, "{what}");
            assert!(each.last_upload_copy_count() >= 6, "{what}: {} copies", each.last_upload_copy_count());
            assert!(a.pixels.iter().filter(|p| p.w > 0.0).count() > 500, "{what}: reflections found");
            assert!(bits(&a.pixels) == bits(&b.pixels), "{what}: output");
            assert!(bits(&a.layer_pixels) == bits(&b.layer_pixels), "{what}: layer output");
        }
    }
}

/// The clear pass's index in `ReflectionRenderer::passes_recorded`.
const CLEAR: usize = 1;

#[test]
fn direct_and_indirect_frames_by_turns_find_their_buffers_cleared() {
    // A slot's active-tile count is zeroed by the indirect frame before, which a direct
    // frame between them (the plan switches with the reflectors' screen coverage) does not
    // do: each frame must still match a renderer that clears everything before every frame.
    let (set, cams, frames) = pond_views();
    let mut turns = renderer();
    let mut every_frame = renderer();
    every_frame.debug.clear_pass_every_frame = true;
    for r in [&mut turns, &mut every_frame] {
        r.set_reflectors(&set);
    }
    let on = Choice::On;
    let off = Choice::Off;
    let sequence = [(on, 0), (off, 1), (on, 0), (on, 1), (off, 0), (off, 1), (on, 0), (on, 1), (on, 0)];
    for (k, (indirect, v)) in sequence.into_iter().enumerate() {
        let what = format!("frame {k} ({indirect:?}, view {v})");
        turns.plan_params.indirect = indirect;
        every_frame.plan_params.indirect = indirect;
        let a = run(&mut turns, &frames[v], &cams[v]);
        let b = run(&mut every_frame, &frames[v], &cams[v]);
        assert_eq!(a.plan.indirect, indirect == on, "{what}");
        a.assert_same_frame(&b, &what);
        if indirect == on {
            assert_eq!(
                active_tile_header(&turns),
                active_tile_header(&every_frame),
                "{what}: count and arguments"
            );
        }
    }
}

#[test]
fn each_frame_finds_its_buffers_cleared_by_the_frame_before() {
    // A frame clears the intermediate buffer and atlas that the next encode takes (two
    // slots, by turns): with direct dispatch its reflection pass, with indirect dispatch
    // its classification (which the projection then need not wait for), so that only the
    // first frame has a clear pass. Two views in the order A B A B B A A B put each view
    // into both slots, so that a slot left uncleared would hold the other view's values;
    // every frame must match a renderer that clears in the pass every frame, bit for bit
    // (output, layer output and intermediate buffer), a water layer included.
    let (set, cams, frames) = pond_views();
    for indirect in [Choice::Off, Choice::On] {
        let mut turns = renderer();
        let mut every_frame = renderer();
        every_frame.debug.clear_pass_every_frame = true;
        for r in [&mut turns, &mut every_frame] {
            r.plan_params.indirect = indirect;
            r.set_reflectors(&set);
        }
        // The first two frames may clear in the pass (the second where its layer needs a
        // larger atlas than the first's: new buffers); from the third on, none.
        for (k, v) in [0, 1, 0, 1, 1, 0, 0, 1].into_iter().enumerate() {
            let what = format!("{indirect:?}, frame {k} (view {v})");
            let a = run(&mut turns, &frames[v], &cams[v]);
            let cleared_in_pass = turns.passes_recorded()[CLEAR];
            let b = run(&mut every_frame, &frames[v], &cams[v]);
            assert!(!a.plan.visible.is_empty() && !a.plan.layers.is_empty(), "{}", a.plan);
            assert_eq!(a.plan.indirect, indirect == Choice::On, "{}", a.plan);
            assert!(a.pixels.iter().filter(|p| p.w > 0.0).count() > 500, "{what}: reflections found");
            assert!(a.layer_pixels.iter().any(|p| p.w > 0.0), "{what}: the water layer reflects");
            if k != 1 {
                assert_eq!(cleared_in_pass, k == 0, "{what}: only the first frames clear in the pass");
            }
            assert!(every_frame.passes_recorded()[CLEAR]);
            a.assert_same_frame(&b, &what);
            if indirect == Choice::On {
                // The list's count and dispatch arguments start from zero (the frame before
                // zeroed this slot's): the same as those of a list cleared before it.
                let header = active_tile_header(&turns);
                assert_eq!(
                    header,
                    active_tile_header(&every_frame),
                    "{what}: active-tile count and arguments"
                );
                assert!(header[0] > 0 && header[1] > 0 && header[3] == 1, "{what}: {header:?}");
            }
        }
        // After `forget_cleared` (an encoder dropped unsubmitted) the next frame clears again.
        turns.forget_cleared();
        run(&mut turns, &frames[0], &cams[0]);
        assert!(turns.passes_recorded()[CLEAR], "{indirect:?}: a forgotten clear is done in the pass");
    }
}
