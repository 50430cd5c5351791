//! The composite pass: PPR's reflection over the fallback reflection by its confidence,
//! then over the scene colour by the reflection weight, tone mapped, into the output (the
//! swapchain image or the screenshot target). Also the debug views of the reflection
//! buffer and the weight.

use ppr_scene_gpu::layout_entries::{unfilterable_texture_entry, uniform_entry};
use ppr_scene_gpu::screen_pass::with_fullscreen_triangle;

use crate::forward_pass::BACKGROUND;
use crate::frame_targets::FrameTargets;
use crate::fullscreen_pipeline::{begin_output_pass, fullscreen_pipeline};

const WGSL: &str = include_str!("../shaders/composite_pass.wgsl");

/// What the composite shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CompositeMode {
    /// The game's image: scene with reflections.
    #[default]
    Final,
    /// PPR's raw output (reflected colour over dark purple by its confidence: holes purple).
    ReflectionBuffer,
    /// The per-pixel reflection weight of the forward pass.
    ReflectionWeight,
    /// The game's image in linear HDR, neither tone mapped nor encoded (the previous
    /// frame PPR may read as its colour input, [`crate::previous_frame`]).
    FinalLinear,
}

/// Composite uniform.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct CompositeUniform {
    mode: u32,
    reflections: u32,
    encode_srgb: u32,
    exposure: f32,
    fallback: [f32; 4],
}
const _: () = assert!(size_of::<CompositeUniform>() == 32);

/// The reflection where PPR has none, or fades out at the screen borders: a constant sky
/// colour, the one the forward pass clears to (a game samples its reflection probe there).
pub const FALLBACK_REFLECTION: [f32; 3] = [BACKGROUND.r as f32, BACKGROUND.g as f32, BACKGROUND.b as f32];

/// The composite pass for one output format.
pub struct CompositePass {
    device: wgpu::Device,
    queue: wgpu::Queue,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    encode_srgb: bool,
}

impl CompositePass {
    /// Builds the pipeline for outputs of `format` (sRGB or not: encoded accordingly).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, format: wgpu::TextureFormat) -> Self {
        let texture = |binding| unfilterable_texture_entry(binding, wgpu::ShaderStages::FRAGMENT);
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("walkthrough composite"),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::FRAGMENT, false),
                texture(1),
                texture(2),
                texture(3),
            ],
        });
        let pipeline = fullscreen_pipeline(
            device,
            "walkthrough composite",
            &with_fullscreen_triangle(WGSL),
            &layout,
            format,
            None,
        );
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("walkthrough composite"),
            size: size_of::<CompositeUniform>() as u64,
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

    /// Records the composite into `output` (same size as `targets`). `reflections` says
    /// whether `targets.reflection` holds this frame's PPR output.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        targets: &FrameTargets,
        output: &wgpu::TextureView,
        mode: CompositeMode,
        reflections: bool,
    ) {
        let uniform = CompositeUniform {
            mode: match mode {
                CompositeMode::Final => 0,
                CompositeMode::ReflectionBuffer => 1,
                CompositeMode::ReflectionWeight => 2,
                CompositeMode::FinalLinear => 3,
            },
            reflections: u32::from(reflections),
            encode_srgb: u32::from(self.encode_srgb),
            exposure: 1.0,
            fallback: [FALLBACK_REFLECTION[0], FALLBACK_REFLECTION[1], FALLBACK_REFLECTION[2], 0.0],
        };
        self.queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("walkthrough composite"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: self.uniform.as_entire_binding() },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&targets.color.view),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&targets.reflection.view),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::TextureView(&targets.reflection_weight.view),
                },
            ],
        });
        let mut pass = begin_output_pass(
            encoder,
            "walkthrough composite",
            output,
            wgpu::LoadOp::Clear(wgpu::Color::BLACK),
        );
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.draw(0..3, 0..1);
    }
}
