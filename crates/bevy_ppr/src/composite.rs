//! `CompositePipeline`: blends the runtime's output over the camera's main texture, through
//! Bevy's pipeline cache and fullscreen vertex shader.

use bevy::asset::{Assets, Handle};
use bevy::core_pipeline::FullscreenShader;
use bevy::ecs::prelude::*;
use bevy::render::render_resource::binding_types::{texture_2d, uniform_buffer_sized};
use bevy::render::render_resource::{
    BindGroup, BindGroupEntries, BindGroupLayoutDescriptor, BindGroupLayoutEntries, BlendComponent,
    BlendFactor, BlendOperation, BlendState, BufferInitDescriptor, BufferUsages, CachedRenderPipelineId,
    ColorTargetState, ColorWrites, FragmentState, PipelineCache, RenderPipeline, RenderPipelineDescriptor,
    ShaderStages, TextureFormat, TextureSampleType, TextureView,
};
use bevy::render::renderer::RenderDevice;
use bevy::shader::Shader;

/// The main texture of an `Hdr` camera, the only target the pipeline is built for (the
/// runtime reads linear float colour).
pub(crate) const TARGET_FORMAT: TextureFormat = TextureFormat::Rgba16Float;

/// The composite's WGSL.
const WGSL: &str = include_str!("../shaders/composite.wgsl");

/// Colour: `src × weight + dst × (1 − weight)`, the weight in the source's alpha; the
/// target keeps its alpha.
const BLEND: BlendState = BlendState {
    color: BlendComponent {
        src_factor: BlendFactor::SrcAlpha,
        dst_factor: BlendFactor::OneMinusSrcAlpha,
        operation: BlendOperation::Add,
    },
    alpha: BlendComponent {
        src_factor: BlendFactor::Zero,
        dst_factor: BlendFactor::One,
        operation: BlendOperation::Add,
    },
};

/// The composite shader, added to the main world's shaders by the plugin.
#[derive(Resource, Clone)]
pub(crate) struct CompositeShader(pub Handle<Shader>);

impl CompositeShader {
    pub fn add(shaders: &mut Assets<Shader>) -> Self {
        Self(shaders.add(Shader::from_wgsl(WGSL, "bevy_ppr/shaders/composite.wgsl")))
    }
}

/// The pipeline (queued once, for HDR views) and its bind-group layout.
#[derive(Resource)]
pub(crate) struct CompositePipeline {
    layout: BindGroupLayoutDescriptor,
    pipeline: CachedRenderPipelineId,
}

/// `RenderStartup`: queues the pipeline.
pub(crate) fn init_composite_pipeline(
    mut commands: Commands,
    cache: Res<PipelineCache>,
    fullscreen: Res<FullscreenShader>,
    shader: Res<CompositeShader>,
) {
    let layout = BindGroupLayoutDescriptor::new(
        "bevy_ppr composite",
        &BindGroupLayoutEntries::sequential(
            ShaderStages::FRAGMENT,
            (uniform_buffer_sized(false, None), texture_2d(TextureSampleType::Float { filterable: false })),
        ),
    );
    let pipeline = cache.queue_render_pipeline(RenderPipelineDescriptor {
        label: Some("bevy_ppr composite".into()),
        layout: vec![layout.clone()],
        vertex: fullscreen.to_vertex_state(),
        fragment: Some(FragmentState {
            shader: shader.0.clone(),
            targets: vec![Some(ColorTargetState {
                format: TARGET_FORMAT,
                blend: Some(BLEND),
                write_mask: ColorWrites::ALL,
            })],
            ..Default::default()
        }),
        ..Default::default()
    });
    commands.insert_resource(CompositePipeline { layout, pipeline });
}

impl CompositePipeline {
    /// The pipeline once compiled (it compiles in the background).
    pub fn get<'a>(&self, cache: &'a PipelineCache) -> Option<&'a RenderPipeline> {
        cache.get_render_pipeline(self.pipeline)
    }

    /// A bind group of the reflection and the reflectivity, for one view's frame.
    pub fn bind_group(
        &self,
        device: &RenderDevice,
        cache: &PipelineCache,
        reflection: &TextureView,
        reflectivity: f32,
    ) -> BindGroup {
        let params = [reflectivity.clamp(0.0, 1.0), 0.0, 0.0, 0.0];
        let uniform = device.create_buffer_with_data(&BufferInitDescriptor {
            label: Some("bevy_ppr composite"),
            contents: bytemuck::cast_slice(&params),
            usage: BufferUsages::UNIFORM,
        });
        device.create_bind_group(
            "bevy_ppr composite",
            &cache.get_bind_group_layout(&self.layout),
            &BindGroupEntries::sequential((uniform.as_entire_binding(), reflection)),
        )
    }
}
