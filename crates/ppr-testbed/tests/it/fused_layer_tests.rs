//! The projection's fused block lists also sort out the glass and water layers: a block
//! whose box of positions cannot reflect into a layer skips its test, one that lies inside
//! the layer's pyramid tests its plane only. On the demo's three cameras (two water planes,
//! a glass pane), the reflection and the layer output are bit for bit those of the separate
//! lists, whose projection tests every layer wherever its source box meets the block.

use ppr_runtime::{Choice, ReflectionRenderer};
use ppr_testbed::camera_spec::{ProjectionChoice, pick_camera};
use ppr_testbed::gbuffer_targets::Target;
use ppr_testbed::readback::read_rgba_f32;
use ppr_testbed::{Level, LevelRenderer};

use crate::common::{gpu, timed};
use crate::demo_level_tests::{asset, demo_reflectors};
use crate::layer_tiles_tests::frame_with_layers;

#[test]
fn fused_lists_cull_the_layers_without_changing_a_pixel() {
    timed("fused_lists_cull_the_layers_without_changing_a_pixel", || {
        let level = Level::load_gltf(asset("demo_room.glb")).expect("demo level");
        let set = demo_reflectors();
        let g = gpu();
        let _guard = g.lock();
        let (device, queue) = (&g.ctx.device, &g.ctx.queue);
        let size = [320, 180];
        let mut scene = LevelRenderer::new(device, queue, &level, &set);
        for name in ["cam_overview", "cam_mirror", "cam_steps"] {
            let camera = pick_camera(&level, Some(name), ProjectionChoice::default()).expect("camera");
            scene.render(device, queue, &camera, size);
            let gbuffer = scene.gbuffer();
            let run = |fused: bool| {
                let configure = |ppr: &mut ReflectionRenderer| {
                    ppr.plan_params.tile_culling = Choice::On;
                    // Forced both ways: `Auto` leaves fused lists off on the software adapter.
                    ppr.plan_params.fused_lists = if fused { Choice::On } else { Choice::Off };
                };
                let (plan, output, layer) =
                    frame_with_layers(device, queue, &set, (&camera, gbuffer, size), configure, None);
                let read = |t: &Target| read_rgba_f32(device, queue, &t.texture).expect("read back");
                (plan, read(&output), read(&layer))
            };
            let (plan, output, layer) = run(true);
            let (separate_plan, separate_output, separate_layer) = run(false);
            assert!(plan.tile_culling && plan.fused_lists, "{name}: {plan}");
            assert!(separate_plan.tile_culling && !separate_plan.fused_lists, "{name}: {separate_plan}");
            assert!(!plan.layers.is_empty(), "{name}: the demo's cameras see its layers");
            let bits =
                |i: &image::Rgba32FImage| i.pixels().flat_map(|p| p.0.map(f32::to_bits)).collect::<Vec<_>>();
            assert!(bits(&output) == bits(&separate_output), "{name}: the reflection differs");
            assert!(bits(&layer) == bits(&separate_layer), "{name}: the layer output differs");
            let reflected = layer.pixels().filter(|p| p.0[3] > 0.0).count();
            eprintln!("{name}: {} layers, {reflected} layer pixels with a reflection", plan.layers.len());
            if name == "cam_overview" {
                assert!(reflected > 200, "{name}: {reflected} layer pixels with a reflection");
            }
        }
    });
}
