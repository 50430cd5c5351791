//! The composite pass: final frame = scene colour mixed with a reflection over reflector pixels.

use ppr_scene_gpu::layout_entries::{texture_entry, uniform_entry};
use ppr_scene_gpu::screen_pass::screen_pass_module;
use wgpu::util::DeviceExt;

use crate::gbuffer_targets::{COLOR_FORMAT, Target};

/// Format of the composited frame.
pub const COMPOSITE_FORMAT: wgpu::TextureFormat = COLOR_FORMAT;

/// How the reflection is mixed in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompositeParams {
    /// Weight of the reflection on reflector pixels, in `[0, 1]` (no Fresnel term).
    pub reflectivity: f32,
}

impl Default for CompositeParams {
    fn default() -> Self {
        Self { reflectivity: 0.8 }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct CompositeUniform {
    params: [f32; 4],
}

/// The inputs of one composite.
pub struct CompositeInputs<'a> {
    /// Linear scene colour (`Rgba16Float`).
    pub scene_color: &'a wgpu::TextureView,
    /// Reflection colour with its confidence in alpha (`Rgba16Float`, e.g. the PPR output or the reference).
    pub reflection: &'a wgpu::TextureView,
    /// Reflector id (`R32Uint`): only non-zero pixels get the reflection.
    pub reflector_id: &'a wgpu::TextureView,
    /// Where the result goes ([`COMPOSITE_FORMAT`], render attachment).
    pub output: &'a wgpu::TextureView,
}

/// The composite pass (pipeline and layout built once).
pub struct CompositePass {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

impl CompositePass {
    /// Builds the pipeline.
    pub fn new(device: &wgpu::Device) -> Self {
        let shader =
            screen_pass_module(device, "composite shader", include_str!("../shaders/composite.wgsl"));
        let tex = |binding, sample_type| texture_entry(binding, wgpu::ShaderStages::FRAGMENT, sample_type);
        let float = wgpu::TextureSampleType::Float { filterable: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("composite layout"),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::FRAGMENT, false),
                tex(1, float),
                tex(2, float),
                tex(3, wgpu::TextureSampleType::Uint),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("composite pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("composite pipeline"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(COMPOSITE_FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        Self { layout, pipeline }
    }

    /// A bind group for `inputs` (make it before recording; it holds the uniform).
    pub fn bind_group(
        &self,
        device: &wgpu::Device,
        inputs: &CompositeInputs<'_>,
        params: &CompositeParams,
    ) -> wgpu::BindGroup {
        let uniform = CompositeUniform { params: [params.reflectivity.clamp(0.0, 1.0), 0.0, 0.0, 0.0] };
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("composite uniform"),
            contents: bytemuck::bytes_of(&uniform),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let view = |binding, view| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(view),
        };
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("composite bind group"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() },
                view(1, inputs.scene_color),
                view(2, inputs.reflection),
                view(3, inputs.reflector_id),
            ],
        })
    }

    /// Records the composite into `output` (which must be the one the bind group was made for).
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        bind_group: &wgpu::BindGroup,
        output: &wgpu::TextureView,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("composite pass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: output,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.draw(0..3, 0..1);
    }

    /// A target the composite can write and the testbed can read back.
    pub fn output_target(device: &wgpu::Device, size: [u32; 2], label: &str) -> Target {
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC;
        Target::new(device, label, size, COMPOSITE_FORMAT, usage)
    }

    /// Makes a bind group, records and submits one composite.
    pub fn run(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        inputs: &CompositeInputs<'_>,
        params: &CompositeParams,
    ) {
        let bind_group = self.bind_group(device, inputs, params);
        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("composite") });
        self.encode(&mut encoder, &bind_group, inputs.output);
        queue.submit([encoder.finish()]);
    }
}
