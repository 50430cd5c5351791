//! The game's own forward pass: the level lit by one sun into linear HDR colour
//! (`Rgba16Float`), the reflection weight (`R8Unorm`) and depth (`Depth32Float`), in the
//! camera's depth convention. Opaque surfaces first, then blended ones (no depth write).
//! The meshes, bind-group layouts, vertex shader and lighting are `ppr-scene-gpu`'s, shared
//! with the testbed's G-buffer (so headless frames compare with its frames).

use ppr_runtime::{Camera, DepthMode};
use ppr_scene_gpu::layout_entries::uniform_entry;
use ppr_scene_gpu::scene_raster::{
    RasterPipelineDesc, begin_raster_pass, raster_pipeline, scene_pipeline_layout, scene_raster_module,
};
use ppr_scene_gpu::{FaceCulling, LevelMeshes, Material, MeshDraw, MeshInstance, SceneLayouts, SurfaceRules};

use crate::frame_targets::{COLOR_FORMAT, FrameTargets, WEIGHT_FORMAT};
use crate::gltf_level::AlphaBlend;
use crate::reflectivity::reflectivity;

const WGSL: &str = include_str!("../shaders/forward_pass.wgsl");

/// The forward pass's per-material numbers (x: metallic, y: 1 if alpha blended) and
/// per-draw ones (x: the bits of the draw's `f32` reflectivity, [`reflectivity`]).
pub const FORWARD_SURFACES: SurfaceRules =
    SurfaceRules { material_params: forward_material_params, draw_params: forward_draw_params };

fn forward_material_params(m: &Material) -> [f32; 4] {
    [m.metallic, f32::from(u8::from(AlphaBlend::of(m) == AlphaBlend::Blend)), 0.0, 0.0]
}

fn forward_draw_params(m: &Material, instance: &MeshInstance) -> [u32; 4] {
    [reflectivity(m, instance.reflector_hint).to_bits(), 0, 0, 0]
}

/// The culling pipelines, in the order they are built: double-sided surfaces are drawn
/// with counter-clockwise front faces whatever their transform ([`pipeline_culling`]).
const CULLINGS: [FaceCulling; 3] = [FaceCulling::BackCcw, FaceCulling::BackCw, FaceCulling::None];

/// The pipeline a draw of `culling` is drawn with.
fn pipeline_culling(culling: FaceCulling) -> FaceCulling {
    match culling {
        FaceCulling::NoneCw => FaceCulling::None,
        other => other,
    }
}

/// Whether `draw` is drawn with the pipeline of `blend` and `culling`.
fn drawn_with(draw: &MeshDraw, blend: AlphaBlend, culling: FaceCulling) -> bool {
    pipeline_culling(draw.culling) == culling && draw.blended == (blend == AlphaBlend::Blend)
}

/// Linear colour where nothing is drawn (the testbed's, so frames compare).
pub const BACKGROUND: wgpu::Color = wgpu::Color { r: 0.05, g: 0.07, b: 0.11, a: 1.0 };

/// The light: one sun plus ambient, no shadows; `ppr-scene-gpu`'s `Lighting`, whose default
/// is the testbed's, so a headless frame can be compared with its frame.
pub use ppr_scene_gpu::Lighting as SceneLight;

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
    pub layouts: SceneLayouts,
    depth: DepthMode,
    /// `pipelines[blend][culling]`: opaque then blended, each of [`CULLINGS`].
    pipelines: [[wgpu::RenderPipeline; 3]; 2],
    view_uniform: wgpu::Buffer,
    view_group: wgpu::BindGroup,
}

impl ForwardPass {
    /// Builds the pipelines (once) for cameras with `depth`.
    pub fn new(device: &wgpu::Device, depth: DepthMode) -> Self {
        let view_entry = uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT, false);
        let layouts = SceneLayouts::new(device, "walkthrough forward", &[view_entry]);
        let module = scene_raster_module(device, "walkthrough forward pass", WGSL);
        let pipeline_layout = scene_pipeline_layout(device, "walkthrough forward pass", &layouts);
        let compare = match depth {
            DepthMode::Standard => wgpu::CompareFunction::Less,
            DepthMode::Reversed => wgpu::CompareFunction::Greater,
        };
        let pipeline = |blend: AlphaBlend, culling: FaceCulling| {
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
            raster_pipeline(
                device,
                &RasterPipelineDesc {
                    label: &format!("walkthrough forward pass ({blend:?}, {culling:?})"),
                    layout: &pipeline_layout,
                    module: &module,
                    culling,
                    depth_compare: compare,
                    depth_write: blend == AlphaBlend::Opaque,
                    targets: &[target(COLOR_FORMAT), target(WEIGHT_FORMAT)],
                },
            )
        };
        let pipelines = [AlphaBlend::Opaque, AlphaBlend::Blend].map(|b| CULLINGS.map(|c| pipeline(b, c)));
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
        let (light, ambient) = light.uniform_vectors();
        let uniform = ViewUniform {
            clip_from_rel: camera.clip_from_relative(aspect).to_cols_array_2d(),
            light,
            ambient,
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
        let colours =
            [(&targets.color.view, BACKGROUND), (&targets.reflection_weight.view, wgpu::Color::TRANSPARENT)];
        let mut pass =
            begin_raster_pass(encoder, "walkthrough forward pass", &colours, &targets.depth.view, far_depth);
        pass.set_bind_group(0, &self.view_group, &[]);
        for (b, blend) in [AlphaBlend::Opaque, AlphaBlend::Blend].into_iter().enumerate() {
            for (c, culling) in CULLINGS.into_iter().enumerate() {
                pass.set_pipeline(&self.pipelines[b][c]);
                meshes.record_draws(&mut pass, |d| drawn_with(d, blend, culling));
            }
        }
    }
}
