//! The resolve pass of the exact glossy reference (`shaders/glossy_resolve.wgsl`): divides
//! the accumulated `Σ wL` by `Σ w` into the reference colour, on the pixels of rough
//! reflectors only (the others keep the mirror reference drawn before).

use ppr_scene_gpu::layout_entries::{storage_entry, texture_entry};
use ppr_scene_gpu::screen_pass::screen_pass_module;

use crate::gbuffer_targets::GBuffer;
use crate::glossy_accumulate::GlossyBindings;
use crate::reference::{REFERENCE_COLOR_FORMAT, ReferenceTargets};

/// The resolve pass (pipeline and layout built once).
pub struct GlossyResolvePass {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

impl GlossyResolvePass {
    /// Builds the pipeline.
    pub fn new(device: &wgpu::Device) -> Self {
        let shader = screen_pass_module(
            device,
            "glossy resolve shader",
            include_str!("../shaders/glossy_resolve.wgsl"),
        );
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("glossy resolve layout"),
            entries: &[storage_entry(0, fragment), texture_entry(1, fragment, wgpu::TextureSampleType::Uint)],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("glossy resolve pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("glossy resolve pipeline"),
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
                entry_point: Some("fs_resolve"),
                compilation_options: Default::default(),
                targets: &[Some(REFERENCE_COLOR_FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        Self { layout, pipeline }
    }

    /// The bind group over the sums of `glossy` and the main view's reflector ids.
    pub fn bind_group(
        &self,
        device: &wgpu::Device,
        main: &GBuffer,
        glossy: &GlossyBindings,
    ) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("glossy resolve bind group"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: glossy.accum().as_entire_binding() },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&main.reflector_id.view),
                },
            ],
        })
    }

    /// Records the resolve into the reference colour (loaded, not cleared).
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        targets: &ReferenceTargets,
        bind_group: &wgpu::BindGroup,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("glossy resolve pass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &targets.color.view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
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
}
