//! Draws the on-screen text image ([`crate::overlay_text::TextImage`]) over the frame.
//! The texture is re-uploaded only when the text changes.

use ppr_scene_gpu::layout_entries::{unfilterable_texture_entry, uniform_entry};

use crate::fullscreen_pipeline::{begin_output_pass, fullscreen_pipeline};
use crate::overlay_text::TextImage;

const WGSL: &str = include_str!("../shaders/overlay_pass.wgsl");

/// Pixels between the window's corner and the text box.
pub const MARGIN: u32 = 8;

#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct OverlayUniform {
    origin: [f32; 2],
    size: [f32; 2],
    target_size: [f32; 2],
    encode_srgb: u32,
    _pad: u32,
}
const _: () = assert!(size_of::<OverlayUniform>() == 32);

/// The overlay pass for one output format, with the current text texture.
pub struct OverlayPass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    encode_srgb: bool,
    text: Option<(TextImage, wgpu::BindGroup)>,
}

impl OverlayPass {
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("walkthrough overlay"),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT, false),
                unfilterable_texture_entry(1, wgpu::ShaderStages::FRAGMENT),
            ],
        });
        let pipeline = fullscreen_pipeline(
            device,
            "walkthrough overlay",
            WGSL,
            &layout,
            format,
            Some(wgpu::BlendState::ALPHA_BLENDING),
        );
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("walkthrough overlay"),
            size: size_of::<OverlayUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self { pipeline, layout, uniform, encode_srgb: !format.is_srgb(), text: None }
    }

    /// Uploads `image` unless it is the one already shown.
    pub fn set_text(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, image: TextImage) {
        if self.text.as_ref().is_some_and(|(shown, _)| *shown == image)
            || image.width == 0
            || image.height == 0
        {
            return;
        }
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("walkthrough overlay text"),
            size: wgpu::Extent3d { width: image.width, height: image.height, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8UnormSrgb,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        queue.write_texture(
            texture.as_image_copy(),
            &image.rgba8,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * image.width),
                rows_per_image: Some(image.height),
            },
            wgpu::Extent3d { width: image.width, height: image.height, depth_or_array_layers: 1 },
        );
        let view = texture.create_view(&Default::default());
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("walkthrough overlay"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: self.uniform.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(&view) },
            ],
        });
        self.text = Some((image, group));
    }

    /// Records the text over `output` (a `target_size` image), if there is any text.
    pub fn encode(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        output: &wgpu::TextureView,
        target_size: [u32; 2],
    ) {
        let Some((image, group)) = &self.text else { return };
        let uniform = OverlayUniform {
            origin: [MARGIN as f32; 2],
            size: [image.width as f32, image.height as f32],
            target_size: [target_size[0] as f32, target_size[1] as f32],
            encode_srgb: u32::from(self.encode_srgb),
            _pad: 0,
        };
        queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        let mut pass = begin_output_pass(encoder, "walkthrough overlay", output, wgpu::LoadOp::Load);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.draw(0..6, 0..1);
    }
}
