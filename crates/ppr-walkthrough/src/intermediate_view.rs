//! Debug view of PPR's intermediate buffer (`ReflectionRenderer::intermediate_buffer`):
//! each pixel's encoded offset decoded and shown as a colour, black where nothing was
//! written. The walkthrough turns indirect dispatch off while this view is on, so the whole
//! buffer is cleared every frame (with indirect dispatch only active tiles are).

use ppr_runtime::EncodingLayout;
use ppr_scene_gpu::layout_entries::{storage_entry, uniform_entry};
use ppr_scene_gpu::screen_pass::with_fullscreen_triangle;

use crate::fullscreen_pipeline::{begin_output_pass, fullscreen_pipeline};

const WGSL: &str = include_str!("../shaders/intermediate_view.wgsl");

#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct IntermediateViewUniform {
    size: [u32; 2],
    major_int_bits: u32,
    major_frac_bits: u32,
    minor_int_bits: u32,
    minor_frac_bits: u32,
    encode_srgb: u32,
    range: f32,
}
const _: () = assert!(size_of::<IntermediateViewUniform>() == 32);

/// The intermediate-buffer view for one output format.
pub struct IntermediateView {
    device: wgpu::Device,
    queue: wgpu::Queue,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    encode_srgb: bool,
}

impl IntermediateView {
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, format: wgpu::TextureFormat) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("walkthrough intermediate view"),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::FRAGMENT, false),
                storage_entry(1, wgpu::ShaderStages::FRAGMENT),
            ],
        });
        let pipeline = fullscreen_pipeline(
            device,
            "walkthrough intermediate view",
            &with_fullscreen_triangle(WGSL),
            &layout,
            format,
            None,
        );
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("walkthrough intermediate view"),
            size: size_of::<IntermediateViewUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self {
            device: device.clone(),
            queue: queue.clone(),
            pipeline,
            layout,
            uniform,
            encode_srgb: !format.is_srgb(),
        }
    }

    /// Records the view of `intermediate` (a `size` viewport encoded with `encoding`).
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        intermediate: &wgpu::Buffer,
        size: [u32; 2],
        encoding: &EncodingLayout,
        output: &wgpu::TextureView,
    ) {
        let uniform = IntermediateViewUniform {
            size,
            major_int_bits: encoding.major_int_bits,
            major_frac_bits: encoding.major_frac_bits,
            minor_int_bits: encoding.minor_int_bits,
            minor_frac_bits: encoding.minor_frac_bits,
            encode_srgb: u32::from(self.encode_srgb),
            range: (size[0].max(size[1]) as f32 * 0.5).max(1.0),
        };
        self.queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("walkthrough intermediate view"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: self.uniform.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: intermediate.as_entire_binding() },
            ],
        });
        let mut pass = begin_output_pass(
            encoder,
            "walkthrough intermediate view",
            output,
            wgpu::LoadOp::Clear(wgpu::Color::BLACK),
        );
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.draw(0..3, 0..1);
    }
}
