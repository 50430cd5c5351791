//! The reference's later bounces on the GPU: scratch G-buffers per bounce, and the pass that
//! blends a deeper view over its parent where the parent shows the deeper view's plane.

use ppr_scene_gpu::layout_entries::{
    storage_entry, texture_entry, unfilterable_texture_entry, uniform_entry,
};
use ppr_scene_gpu::screen_pass::screen_pass_module;

use crate::gbuffer_targets::{COLOR_FORMAT, GBuffer};
use crate::scene_layouts::uniform_stride;

/// Scratch targets of bounces 2 to N and the bind groups that read them.
pub struct BounceTargets {
    /// Width and height in pixels.
    pub size: [u32; 2],
    /// The deepest bounce these targets serve.
    pub bounces: u32,
    /// `scratch[d - 2]`: the G-buffer of the view being drawn at bounce `d`.
    pub scratch: Vec<GBuffer>,
    /// `bind_groups[d - 2]`: reads the parent's reflector ids and `scratch[d - 2]`'s colour.
    bind_groups: Vec<wgpu::BindGroup>,
    /// One `[plane, 0, 0, 0]` per plane group, at `stride` (read through the bind groups).
    _plane_uniforms: wgpu::Buffer,
    stride: u64,
}

/// The blend of a deeper view over its parent (pipeline and layout built once).
pub struct BounceCompositePass {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

impl BounceCompositePass {
    /// Builds the pipeline.
    pub fn new(device: &wgpu::Device) -> Self {
        let shader = screen_pass_module(
            device,
            "bounce composite shader",
            include_str!("../shaders/bounce_composite.wgsl"),
        );
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("bounce composite layout"),
            entries: &[
                uniform_entry(0, fragment, true),
                storage_entry(1, fragment),
                texture_entry(2, fragment, wgpu::TextureSampleType::Uint),
                unfilterable_texture_entry(3, fragment),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("bounce composite pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let mix = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::Constant,
            dst_factor: wgpu::BlendFactor::OneMinusConstant,
            operation: wgpu::BlendOperation::Add,
        };
        let keep = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::Zero,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        };
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("bounce composite pipeline"),
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
                targets: &[Some(wgpu::ColorTargetState {
                    format: COLOR_FORMAT,
                    blend: Some(wgpu::BlendState { color: mix, alpha: keep }),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        Self { layout, pipeline }
    }

    /// Scratch targets for bounces 2 to `bounces` at `size`; `first_bounce` is the
    /// reference's mirrored-view G-buffer, `plane_of_reflector` its reflector → plane table.
    #[allow(clippy::too_many_arguments)] // the targets' inputs, each used once
    pub fn targets(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        size: [u32; 2],
        bounces: u32,
        first_bounce: &GBuffer,
        plane_of_reflector: &wgpu::Buffer,
        planes: usize,
    ) -> BounceTargets {
        let scratch: Vec<GBuffer> = (2..=bounces.max(2))
            .map(|d| GBuffer::new(device, size, &format!("reference: bounce {d} view")))
            .collect();
        let stride = uniform_stride(device, 16);
        let slots = planes.max(1) as u64;
        let plane_uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("bounce composite: plane uniforms"),
            size: stride * slots,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        for k in 0..slots {
            let plane = u32::try_from(k).expect("fewer than 2^32 planes");
            queue.write_buffer(&plane_uniforms, k * stride, bytemuck::cast_slice(&[plane, 0, 0, 0]));
        }
        let bind_groups = (0..scratch.len())
            .map(|i| {
                let parent = if i == 0 { first_bounce } else { &scratch[i - 1] };
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("bounce composite bind group"),
                    layout: &self.layout,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                                buffer: &plane_uniforms,
                                offset: 0,
                                size: wgpu::BufferSize::new(16),
                            }),
                        },
                        wgpu::BindGroupEntry { binding: 1, resource: plane_of_reflector.as_entire_binding() },
                        wgpu::BindGroupEntry {
                            binding: 2,
                            resource: wgpu::BindingResource::TextureView(&parent.reflector_id.view),
                        },
                        wgpu::BindGroupEntry {
                            binding: 3,
                            resource: wgpu::BindingResource::TextureView(&scratch[i].color.view),
                        },
                    ],
                })
            })
            .collect();
        BounceTargets { size, bounces, scratch, bind_groups, _plane_uniforms: plane_uniforms, stride }
    }

    /// Blends the bounce-`depth` view (in `targets.scratch[depth - 2]`) over `parent`'s
    /// colour where `parent` shows plane group `plane`: `mix(parent, child, reflectivity)`.
    ///
    /// # Panics
    /// If `depth` is not in `2..=targets.bounces`.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        targets: &BounceTargets,
        parent: &GBuffer,
        depth: u32,
        plane: usize,
        reflectivity: f32,
    ) {
        let index = (depth - 2) as usize;
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("bounce composite pass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &parent.color.view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        let offset = u32::try_from(plane as u64 * targets.stride).expect("plane uniforms under 4 GiB");
        let r = f64::from(reflectivity.clamp(0.0, 1.0));
        pass.set_pipeline(&self.pipeline);
        pass.set_blend_constant(wgpu::Color { r, g: r, b: r, a: r });
        pass.set_bind_group(0, &targets.bind_groups[index], &[offset]);
        pass.draw(0..3, 0..1);
    }
}

impl BounceTargets {
    /// Whether these targets serve frames of `size` up to bounce `bounces`.
    pub fn fits(&self, size: [u32; 2], bounces: u32) -> bool {
        self.size == size && self.bounces == bounces
    }
}
