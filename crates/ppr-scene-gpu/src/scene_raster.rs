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

#[cfg(test)]
mod tests {
    use super::SCENE_RASTER_WGSL;
    use crate::level_meshes::{DrawUniform, MaterialUniform};
    use crate::screen_pass::with_fullscreen_triangle;

    /// The least a pass declares: group 0's `view` as the shared WGSL reads it.
    const MINIMAL_PASS: &str = "
        struct View { clip_from_rel: mat4x4<f32>, light: vec4<f32>, ambient: vec4<f32> }
        @group(0) @binding(0) var<uniform> view: View;
        @fragment
        fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
            return vec4<f32>(lit_colour(base_colour(in.uv).rgb, surface_normal(in, front)), 1.0);
        }";

    /// The module of `source`, parsed and validated (naga's message names the line).
    fn validated(source: &str) -> naga::Module {
        let checked =
            naga::front::wgsl::parse_str(source).map_err(|e| e.emit_to_string(source)).and_then(|module| {
                let flags = naga::valid::ValidationFlags::all();
                let mut validator = naga::valid::Validator::new(flags, naga::valid::Capabilities::all());
                validator.validate(&module).map(|_| module).map_err(|e| e.emit_to_string(source))
            });
        checked.unwrap_or_else(|message| panic!("{message}"))
    }

    /// Bytes of the WGSL type `name` (its uniform layout).
    fn wgsl_size(module: &naga::Module, name: &str) -> usize {
        let named = module.types.iter().find(|(_, t)| t.name.as_deref() == Some(name));
        let (_, ty) = named.unwrap_or_else(|| panic!("no type {name}"));
        ty.inner.size(module.to_ctx()) as usize
    }

    /// The shared WGSL validates in front of a pass, and its group 1 and 2 structs have the
    /// sizes of the uniforms `LevelMeshes` writes.
    #[test]
    fn shared_wgsl_validates_and_matches_the_rust_uniforms() {
        let module = validated(&format!("{SCENE_RASTER_WGSL}\n{MINIMAL_PASS}"));
        assert_eq!(wgsl_size(&module, "Draw"), size_of::<DrawUniform>());
        assert_eq!(wgsl_size(&module, "Material"), size_of::<MaterialUniform>());
        validated(&with_fullscreen_triangle(
            "@fragment fn fs_main() -> @location(0) vec4<f32> { return vec4<f32>(1.0); }",
        ));
    }
}
