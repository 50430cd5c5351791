//! The game's own forward pass: the level lit by one sun into linear HDR colour
//! (`Rgba16Float`), the reflection weight (`R8Unorm`) and depth (`Depth32Float`), in the
//! camera's depth convention. Opaque surfaces first, then blended ones (no depth write).

use glam::Vec3;
use ppr_runtime::{Camera, DepthMode};

use crate::forward_layouts::ForwardLayouts;
use crate::frame_targets::{COLOR_FORMAT, DEPTH_FORMAT, FrameTargets, WEIGHT_FORMAT};
use crate::gltf_level::{AlphaBlend, Vertex};
use crate::level_meshes::{Culling, LevelMeshes};

const WGSL: &str = include_str!("../shaders/forward_pass.wgsl");

/// Linear colour where nothing is drawn (the testbed's, so frames compare).
pub const BACKGROUND: wgpu::Color = wgpu::Color { r: 0.05, g: 0.07, b: 0.11, a: 1.0 };

/// The light: one sun plus ambient, no shadows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneLight {
    /// Direction towards the light (normalised when used).
    pub direction: Vec3,
    /// Linear intensity (multiplies Lambert's cosine).
    pub intensity: f32,
    /// Linear ambient colour.
    pub ambient: [f32; 3],
}

impl Default for SceneLight {
    /// The testbed's default light, so a headless frame can be compared with its frame.
    fn default() -> Self {
        Self { direction: Vec3::new(0.35, 1.0, 0.55), intensity: 0.85, ambient: [0.25, 0.25, 0.27] }
    }
}

/// View uniform (group 0).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct ViewUniform {
    clip_from_rel: [[f32; 4]; 4],
    light: [f32; 4],
    ambient: [f32; 4],
}
const _: () = assert!(size_of::<ViewUniform>() == 96);

/// The forward pass for one depth convention.
pub struct ForwardPass {
    pub layouts: ForwardLayouts,
    depth: DepthMode,
    /// `pipelines[blend][culling]`: opaque then blended, each culling mode.
    pipelines: [[wgpu::RenderPipeline; 3]; 2],
    view_uniform: wgpu::Buffer,
    view_group: wgpu::BindGroup,
}

impl ForwardPass {
    /// Builds the pipelines (once) for cameras with `depth`.
    pub fn new(device: &wgpu::Device, depth: DepthMode) -> Self {
        let layouts = ForwardLayouts::new(device);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("walkthrough forward pass"),
            source: wgpu::ShaderSource::Wgsl(WGSL.into()),
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("walkthrough forward pass"),
            bind_group_layouts: &[Some(&layouts.view), Some(&layouts.material), Some(&layouts.draw)],
            immediate_size: 0,
        });
        let compare = match depth {
            DepthMode::Standard => wgpu::CompareFunction::Less,
            DepthMode::Reversed => wgpu::CompareFunction::Greater,
        };
        let pipeline = |blend: AlphaBlend, culling: Culling| {
            let (front_face, cull_mode) = match culling {
                Culling::BackCcw => (wgpu::FrontFace::Ccw, Some(wgpu::Face::Back)),
                Culling::BackCw => (wgpu::FrontFace::Cw, Some(wgpu::Face::Back)),
                Culling::None => (wgpu::FrontFace::Ccw, None),
            };
            let blend_state = match blend {
                AlphaBlend::Opaque => None,
                // Colour: "over". Alpha: multiplied by (1 - the surface's alpha), so the
                // colour target's alpha tells how much of the opaque surface is still seen.
                AlphaBlend::Blend => Some(wgpu::BlendState {
                    color: wgpu::BlendState::ALPHA_BLENDING.color,
                    alpha: wgpu::BlendComponent {
                        src_factor: wgpu::BlendFactor::Zero,
                        dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                        operation: wgpu::BlendOperation::Add,
                    },
                }),
            };
            let target = |format| {
                Some(wgpu::ColorTargetState {
                    format,
                    blend: blend_state,
                    write_mask: wgpu::ColorWrites::ALL,
                })
            };
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&format!("walkthrough forward pass ({blend:?}, {culling:?})")),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_main"),
                    compilation_options: Default::default(),
                    buffers: &[Some(wgpu::VertexBufferLayout {
                        array_stride: size_of::<Vertex>() as u64,
                        step_mode: wgpu::VertexStepMode::Vertex,
                        attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2],
                    })],
                },
                primitive: wgpu::PrimitiveState { front_face, cull_mode, ..Default::default() },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(blend == AlphaBlend::Opaque),
                    depth_compare: Some(compare),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs_main"),
                    compilation_options: Default::default(),
                    targets: &[target(COLOR_FORMAT), target(WEIGHT_FORMAT)],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let pipelines = [AlphaBlend::Opaque, AlphaBlend::Blend].map(|b| Culling::ALL.map(|c| pipeline(b, c)));
        let view_uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("walkthrough forward: view"),
            size: size_of::<ViewUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let view_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("walkthrough forward: view"),
            layout: &layouts.view,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: view_uniform.as_entire_binding() }],
        });
        Self { layouts, depth, pipelines, view_uniform, view_group }
    }

    /// The depth convention the pipelines were built for.
    pub fn depth_mode(&self) -> DepthMode {
        self.depth
    }

    /// Uploads the view: the camera's camera-relative matrix and the light.
    pub fn prepare(&self, queue: &wgpu::Queue, camera: &Camera, size: [u32; 2], light: &SceneLight) {
        let aspect = size[0] as f32 / size[1].max(1) as f32;
        let l = light.direction.normalize_or(Vec3::Y);
        let uniform = ViewUniform {
            clip_from_rel: camera.clip_from_relative(aspect).to_cols_array_2d(),
            light: [l.x, l.y, l.z, light.intensity],
            ambient: [light.ambient[0], light.ambient[1], light.ambient[2], 0.0],
        };
        queue.write_buffer(&self.view_uniform, 0, bytemuck::bytes_of(&uniform));
    }

    /// Records the pass: clears colour, weight and depth, draws opaque then blended surfaces.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        targets: &FrameTargets,
        meshes: &LevelMeshes,
        far_depth: f32,
    ) {
        let colour = |view, clear| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Clear(clear), store: wgpu::StoreOp::Store },
            })
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("walkthrough forward pass"),
            color_attachments: &[
                colour(&targets.color.view, BACKGROUND),
                colour(&targets.reflection_weight.view, wgpu::Color::TRANSPARENT),
            ],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &targets.depth.view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(far_depth),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &self.view_group, &[]);
        for (b, blend) in [AlphaBlend::Opaque, AlphaBlend::Blend].into_iter().enumerate() {
            for (c, culling) in Culling::ALL.into_iter().enumerate() {
                pass.set_pipeline(&self.pipelines[b][c]);
                meshes.record(&mut pass, culling, blend);
            }
        }
    }
}
