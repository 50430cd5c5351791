//! What the scene raster passes (the testbed's G-buffer, the walkthrough's forward pass)
//! build their pipelines and render passes from: the shared WGSL (`scene_raster.wgsl`:
//! groups 1 and 2, the vertex shader, normal, base colour and lighting) in front of the
//! pass's own, one pipeline per culling mode, and a pass that clears its targets.

use crate::level_meshes::{FaceCulling, LevelMeshes};
use crate::render_target::DEPTH_FORMAT;
use crate::scene_layouts::SceneLayouts;

/// The WGSL every scene raster pass starts with.
pub const SCENE_RASTER_WGSL: &str = include_str!("../shaders/scene_raster.wgsl");

/// The shader module of a scene raster pass: [`SCENE_RASTER_WGSL`], then `pass_wgsl`
/// (which declares group 0's `view` and the fragment shader `fs_main`).
pub fn scene_raster_module(device: &wgpu::Device, label: &str, pass_wgsl: &str) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(format!("{SCENE_RASTER_WGSL}\n{pass_wgsl}").into()),
    })
}

/// The pipeline layout of groups 0 (view), 1 (material) and 2 (draw).
pub fn scene_pipeline_layout(
    device: &wgpu::Device,
    label: &str,
    layouts: &SceneLayouts,
) -> wgpu::PipelineLayout {
    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(&layouts.view), Some(&layouts.material), Some(&layouts.draw)],
        immediate_size: 0,
    })
}

/// One pipeline of a scene raster pass.
pub struct RasterPipelineDesc<'a> {
    /// The pipeline's label.
    pub label: &'a str,
    /// From [`scene_pipeline_layout`].
    pub layout: &'a wgpu::PipelineLayout,
    /// From [`scene_raster_module`] (`vs_main`, `fs_main`).
    pub module: &'a wgpu::ShaderModule,
    /// Front face and cull mode.
    pub culling: FaceCulling,
    /// The depth test (`Less` for standard Z, `Greater` for reversed).
    pub depth_compare: wgpu::CompareFunction,
    /// Whether the pipeline writes depth.
    pub depth_write: bool,
    /// The colour targets, in `fs_main`'s location order.
    pub targets: &'a [Option<wgpu::ColorTargetState>],
}

/// A pipeline drawing [`LevelMeshes`] into [`DEPTH_FORMAT`] depth and `desc.targets`.
pub fn raster_pipeline(device: &wgpu::Device, desc: &RasterPipelineDesc<'_>) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(desc.label),
        layout: Some(desc.layout),
        vertex: wgpu::VertexState {
            module: desc.module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[Some(LevelMeshes::vertex_layout())],
        },
        primitive: desc.culling.primitive_state(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(desc.depth_write),
            depth_compare: Some(desc.depth_compare),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: desc.module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: desc.targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// Begins a render pass that clears each colour target to its colour and `depth` to
/// `far_depth`.
pub fn begin_raster_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    colours: &[(&wgpu::TextureView, wgpu::Color)],
    depth: &wgpu::TextureView,
    far_depth: f32,
) -> wgpu::RenderPass<'e> {
    let color_attachments: Vec<Option<wgpu::RenderPassColorAttachment<'_>>> = colours
        .iter()
        .map(|&(view, clear)| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Clear(clear), store: wgpu::StoreOp::Store },
            })
        })
        .collect();
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &color_attachments,
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: depth,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(far_depth),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}
