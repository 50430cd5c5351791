//! The composite pass mixes the reflection in over reflector pixels only.

use image::Rgba;
use ppr_testbed::composite::{CompositeInputs, CompositeParams, CompositePass};
use ppr_testbed::gbuffer_targets::{COLOR_FORMAT, REFLECTOR_ID_FORMAT, Target};
use ppr_testbed::readback::read_rgba_f32;

use crate::common::gpu;

#[test]
fn composite_mixes_valid_reflections_over_reflector_pixels() {
    let g = gpu();
    let _guard = g.lock();
    let (device, queue) = (&g.ctx.device, &g.ctx.queue);
    let (w, h) = (8u32, 4u32);
    let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
    let scene = Target::new(device, "scene", [w, h], COLOR_FORMAT, usage);
    let reflection = Target::new(device, "reflection", [w, h], COLOR_FORMAT, usage);
    let ids = Target::new(device, "ids", [w, h], REFLECTOR_ID_FORMAT, usage);
    let f16 = |v: [f32; 4]| v.map(|c| half::f16::from_f32(c).to_bits());
    // Scene: grey; reflection: blue, valid (alpha 1) in the left half, invalid in the right.
    let scene_px: Vec<[u16; 4]> = (0..w * h).map(|_| f16([0.5, 0.5, 0.5, 1.0])).collect();
    let refl_px: Vec<[u16; 4]> =
        (0..w * h).map(|i| f16([0.0, 0.0, 1.0, if i % w < w / 2 { 1.0 } else { 0.0 }])).collect();
    // Reflector on rows 0 and 1 only.
    let id_px: Vec<u32> = (0..w * h).map(|i| u32::from(i / w < 2)).collect();
    let write = |t: &Target, bytes: &[u8], texel: u32| {
        queue.write_texture(
            t.texture.as_image_copy(),
            bytes,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(texel * w),
                rows_per_image: Some(h),
            },
            wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        );
    };
    write(&scene, bytemuck::cast_slice(&scene_px), 8);
    write(&reflection, bytemuck::cast_slice(&refl_px), 8);
    write(&ids, bytemuck::cast_slice(&id_px), 4);
    let output = CompositePass::output_target(device, [w, h], "composite test output");
    let pass = CompositePass::new(device);
    let inputs = CompositeInputs {
        scene_color: &scene.view,
        reflection: &reflection.view,
        reflector_id: &ids.view,
        output: &output.view,
    };
    pass.run(device, queue, &inputs, &CompositeParams { reflectivity: 0.75 });
    let out = read_rgba_f32(device, queue, &output.texture).expect("readback");
    for (x, y, p) in out.enumerate_pixels() {
        let expected = if y < 2 && x < w / 2 {
            Rgba([0.125, 0.125, 0.875, 1.0]) // 0.25 grey + 0.75 blue
        } else {
            Rgba([0.5, 0.5, 0.5, 1.0])
        };
        for c in 0..4 {
            assert!((p.0[c] - expected.0[c]).abs() < 2e-3, "({x}, {y}): {p:?} != {expected:?}");
        }
    }
}
