//! `clear_target`, the one reflection-target clear of the testbed, the inspector and the
//! bench: a target holding an earlier frame's reflection reads back as "no reflection".

use ppr_testbed::clear_target;
use ppr_testbed::readback::read_rgba_f32;
use ppr_testbed::technique::REFLECTION_FORMAT;

use crate::common::gpu;

#[test]
fn a_written_target_is_cleared_to_no_reflection() {
    let g = gpu();
    let _lock = g.lock();
    let (device, queue) = (&g.ctx.device, &g.ctx.queue);
    let size = wgpu::Extent3d { width: 4, height: 4, depth_or_array_layers: 1 };
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("clear test target"),
        size,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: REFLECTION_FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    // An earlier frame's reflection: every texel (0.5, 0.25, 1, 1) in f16.
    let texel: [u16; 4] = [0x3800, 0x3400, 0x3C00, 0x3C00];
    let bytes: Vec<u8> = (0..16).flat_map(|_| texel).flat_map(u16::to_le_bytes).collect();
    queue.write_texture(
        texture.as_image_copy(),
        &bytes,
        wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4 * 8), rows_per_image: None },
        size,
    );
    let before = read_rgba_f32(device, queue, &texture).expect("read back");
    assert_eq!(before.get_pixel(3, 3).0, [0.5, 0.25, 1.0, 1.0]);

    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("clear test") });
    clear_target(&mut encoder, &view, "clear test");
    queue.submit([encoder.finish()]);
    let after = read_rgba_f32(device, queue, &texture).expect("read back");
    assert!(after.pixels().all(|p| p.0 == [0.0; 4]), "every texel is transparent black");
}
