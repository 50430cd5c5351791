//! The layer reflection writes only the 16 × 16 tiles of the layers' common rectangle that
//! meet a layer's own (the demo's overview: a glass pane in the middle, two water planes
//! at the sides), the same values there as when it wrote every tile, and nothing elsewhere.

use std::sync::Arc;

use ppr_format::{ReflectorSet, ValidatedSet};
use ppr_runtime::{
    Camera, DebugOptions, FrameInputs, FramePlan, ReflectionRenderer, RendererDesc, ScreenRect,
};
use ppr_testbed::camera_spec::{ProjectionChoice, pick_camera};
use ppr_testbed::gbuffer_targets::{GBuffer, Target};
use ppr_testbed::readback::read_rgba_f32;
use ppr_testbed::{Level, LevelRenderer};

use crate::common::{gpu, timed};
use crate::demo_level_tests::{asset, demo_reflectors};

/// What an earlier frame left in the layer output: (0.5, 0.25, 1, 1), as half floats.
const STALE: [f32; 4] = [0.5, 0.25, 1.0, 1.0];
const TILE: u32 = 16;

/// Whether pixel `(x, y)` lies in a 16 × 16 tile (from the layer rectangle's corner) that
/// meets some layer's rectangle.
fn in_a_layer_tile(plan: &FramePlan, x: u32, y: u32) -> bool {
    let o = plan.layer_rect.min;
    let lo = [o[0] + (x - o[0]) / TILE * TILE, o[1] + (y - o[1]) / TILE * TILE];
    plan.layers.iter().any(|l| (0..2).all(|a| lo[a] < l.rect.max[a] && lo[a] + TILE > l.rect.min[a]))
}

fn inside(r: &ScreenRect, x: u32, y: u32) -> bool {
    x >= r.min[0] && x < r.max[0] && y >= r.min[1] && y < r.max[1]
}

/// One frame of a new reflection renderer for `set` (configured by `configure`) over
/// `gbuffer`, with a layer output: its plan, output and layer output (the layer output
/// holding `layer_texels` before the frame, where given: RGBA half floats).
pub fn frame_with_layers(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    set: &ReflectorSet,
    (camera, gbuffer, size): (&Camera, &GBuffer, [u32; 2]),
    configure: impl FnOnce(&mut ReflectionRenderer),
    layer_texels: Option<&[u8]>,
) -> (Arc<FramePlan>, Target, Target) {
    let mut ppr = ReflectionRenderer::new(device, queue, &RendererDesc::default());
    ppr.set_reflectors(&ValidatedSet::new(set.clone()).expect("valid set"));
    configure(&mut ppr);
    let plan = ppr.prepare(camera, size);
    let usage = wgpu::TextureUsages::STORAGE_BINDING
        | wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::COPY_SRC
        | wgpu::TextureUsages::COPY_DST;
    let target = |label| Target::new(device, label, size, ppr_runtime::OUTPUT_FORMAT, usage);
    let (output, layer) = (target("ppr output"), target("ppr layer output"));
    if let Some(texels) = layer_texels {
        queue.write_texture(
            layer.texture.as_image_copy(),
            texels,
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(size[0] * 8), rows_per_image: None },
            layer.texture.size(),
        );
    }
    let mut encoder = device.create_command_encoder(&Default::default());
    let frame = FrameInputs {
        layer_output: Some(&layer.view),
        ..FrameInputs::new(&gbuffer.color.view, &gbuffer.depth.view, &output.view)
    };
    ppr.encode(&mut encoder, &frame);
    queue.submit([encoder.finish()]);
    (plan, output, layer)
}

#[test]
fn the_layer_pass_writes_only_the_tiles_that_meet_a_layer() {
    timed("the_layer_pass_writes_only_the_tiles_that_meet_a_layer", || {
        let level = Level::load_gltf(asset("demo_room.glb")).expect("demo level");
        let set = demo_reflectors();
        let g = gpu();
        let _guard = g.lock();
        let (device, queue) = (&g.ctx.device, &g.ctx.queue);
        let size = [320, 180];
        let camera = pick_camera(&level, Some("cam_overview"), ProjectionChoice::default()).expect("camera");
        let mut scene = LevelRenderer::new(device, queue, &level, &set);
        scene.render(device, queue, &camera, size);
        let gbuffer = scene.gbuffer();

        let stale: Vec<u8> = STALE
            .map(|c| half::f16::from_f32(c).to_bits())
            .into_iter()
            .cycle()
            .take(4 * (size[0] * size[1]) as usize)
            .flat_map(u16::to_le_bytes)
            .collect();
        // Each run's layer output starts as an earlier frame's, every texel STALE.
        let run = |every_tile: bool| {
            let configure = |ppr: &mut ReflectionRenderer| {
                ppr.debug = DebugOptions { layer_every_tile: every_tile, ..DebugOptions::default() };
            };
            let (plan, _, layer) =
                frame_with_layers(device, queue, &set, (&camera, gbuffer, size), configure, Some(&stale));
            (plan, read_rgba_f32(device, queue, &layer.texture).expect("read back"))
        };
        let (plan, tiles) = run(false);
        let (every_plan, every) = run(true);
        assert_eq!(plan.layers.len(), every_plan.layers.len());
        assert!(plan.layers.len() >= 2, "the overview's layers: {:?}", plan.layers);

        let r = plan.layer_rect;
        let (mut in_layers, mut reflected, mut skipped, mut padding) = (0, 0, 0, 0);
        for (x, y, p) in tiles.enumerate_pixels() {
            let old = every.get_pixel(x, y).0;
            let what = format!("pixel ({x}, {y}): {:?} against every tile's {old:?}", p.0);
            if !inside(&r, x, y) {
                // Outside the common rectangle neither run writes.
                assert_eq!((p.0, old), (STALE, STALE), "{what}");
            } else if !in_a_layer_tile(&plan, x, y) {
                // A tile no layer meets: not written now, no reflection before.
                assert_eq!(p.0, STALE, "{what}");
                assert_eq!(old, [0.0; 4], "{what}");
                skipped += 1;
            } else {
                // Written in both runs, with the same value.
                assert_eq!(p.0, old, "{what}");
                if plan.layers.iter().any(|l| inside(&l.rect, x, y)) {
                    in_layers += 1;
                    reflected += usize::from(p.0[3] > 0.0);
                } else {
                    assert_eq!(p.0, [0.0; 4], "{what}: outside every layer's rectangle");
                    padding += 1;
                }
            }
        }
        eprintln!(
            "layer rect {r:?}: {in_layers} pixels in layers ({reflected} reflected), {padding} \
             more in their tiles, {skipped} in tiles no layer meets"
        );
        assert!(skipped > in_layers, "{skipped} pixels skipped, {in_layers} in layers");
        assert!(reflected > 200, "{reflected} layer pixels with a reflection");
    });
}
