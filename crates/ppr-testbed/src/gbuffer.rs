//! The G-buffer pass: rasterises a level into colour, depth, world normal and reflector id.
//!
//! The same pass draws the mirrored views of the exact reference ([`crate::MirrorReference`]);
//! there the winding flips and the reflector mask is disabled. Its pipelines, render pass
//! and shared WGSL are `ppr-scene-gpu`'s `scene_raster`.

use ppr_runtime::DepthMode;
use ppr_scene_gpu::scene_raster::{
    RasterPipelineDesc, begin_raster_pass, raster_pipeline, scene_pipeline_layout, scene_raster_module,
};
use ppr_scene_gpu::{FaceCulling, LevelMeshes, Material, MeshInstance, SceneLayouts, SurfaceRules};

use crate::gbuffer_targets::{COLOR_FORMAT, GBuffer, NORMAL_FORMAT, REFLECTOR_ID_FORMAT};
use crate::level::is_reflective;
use crate::view::ViewBindings;

const CULLINGS: [FaceCulling; 4] =
    [FaceCulling::BackCcw, FaceCulling::BackCw, FaceCulling::None, FaceCulling::NoneCw];

/// The G-buffer's per-material numbers (roughness, metallic, transmission, 1 if textured)
/// and per-draw ones (x: 1 if the surface counts as reflective for the reflector mask: its
/// instance's `extras.ppr.reflector`, else [`is_reflective`]).
pub const GBUFFER_SURFACES: SurfaceRules =
    SurfaceRules { material_params: gbuffer_material_params, draw_params: gbuffer_draw_params };

fn gbuffer_material_params(m: &Material) -> [f32; 4] {
    [m.roughness, m.metallic, m.transmission, if m.base_color_texture.is_some() { 1.0 } else { 0.0 }]
}

fn gbuffer_draw_params(m: &Material, instance: &MeshInstance) -> [u32; 4] {
    [u32::from(instance.reflector_hint.unwrap_or_else(|| is_reflective(m))), 0, 0, 0]
}

/// Whether a view sees the scene directly or through a mirror (which flips the winding).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ViewKind {
    /// The camera's own view.
    Direct,
    /// A view through a planar mirror: front faces appear clockwise.
    Mirrored,
}

/// What one recording of the pass draws into.
pub struct GBufferDraw<'a> {
    /// Render targets (cleared first).
    pub targets: &'a GBuffer,
    /// View slot to bind from `views`.
    pub slot: u32,
    /// Direct or mirrored.
    pub kind: ViewKind,
    /// Depth convention of the projection in the view slot.
    pub depth: DepthMode,
    /// Linear colour where nothing is drawn (the sky).
    pub background: [f64; 4],
}

/// The scene raster pass: one pipeline per depth convention and culling mode.
pub struct GBufferPass {
    /// `pipelines[depth][culling]`, indices from [`depth_index`] and [`culling_index`].
    pipelines: [[wgpu::RenderPipeline; 4]; 2],
}

fn depth_index(depth: DepthMode) -> usize {
    match depth {
        DepthMode::Standard => 0,
        DepthMode::Reversed => 1,
    }
}

fn culling_index(culling: FaceCulling) -> usize {
    match culling {
        FaceCulling::BackCcw => 0,
        FaceCulling::BackCw => 1,
        FaceCulling::None => 2,
        FaceCulling::NoneCw => 3,
    }
}

impl GBufferPass {
    /// Builds the eight pipelines.
    pub fn new(device: &wgpu::Device, layouts: &SceneLayouts) -> Self {
        let module = scene_raster_module(device, "gbuffer shader", include_str!("../shaders/gbuffer.wgsl"));
        let layout = scene_pipeline_layout(device, "gbuffer pipeline layout", layouts);
        let targets =
            [Some(COLOR_FORMAT.into()), Some(NORMAL_FORMAT.into()), Some(REFLECTOR_ID_FORMAT.into())];
        let make = |depth: DepthMode, culling: FaceCulling| {
            raster_pipeline(
                device,
                &RasterPipelineDesc {
                    label: &format!("gbuffer pipeline ({depth:?} depth, {culling:?})"),
                    layout: &layout,
                    module: &module,
                    culling,
                    depth_compare: ppr_runtime::Projection { depth, ..Default::default() }.depth_compare(),
                    depth_write: true,
                    targets: &targets,
                },
            )
        };
        let row = |depth| CULLINGS.map(|c| make(depth, c));
        Self { pipelines: [row(DepthMode::Standard), row(DepthMode::Reversed)] }
    }

    /// Records the pass: clears the targets, then draws every mesh of `meshes`.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        meshes: &LevelMeshes,
        views: &ViewBindings,
        draw: &GBufferDraw<'_>,
    ) {
        let t = draw.targets;
        let [r, g, b, a] = draw.background;
        let far = ppr_runtime::Projection { depth: draw.depth, ..Default::default() }.far_depth();
        let label = match draw.kind {
            ViewKind::Direct => "gbuffer pass",
            ViewKind::Mirrored => "gbuffer pass (mirrored view)",
        };
        let colours = [
            (&t.color.view, wgpu::Color { r, g, b, a }),
            (&t.normal.view, wgpu::Color::TRANSPARENT),
            (&t.reflector_id.view, wgpu::Color::TRANSPARENT),
        ];
        let mut pass = begin_raster_pass(encoder, label, &colours, &t.depth.view, far);
        views.bind(&mut pass, draw.slot);
        for culling in CULLINGS {
            let pass_culling = match draw.kind {
                ViewKind::Direct => culling,
                ViewKind::Mirrored => culling.mirrored(),
            };
            pass.set_pipeline(&self.pipelines[depth_index(draw.depth)][culling_index(pass_culling)]);
            meshes.record_draws(&mut pass, |d| d.culling == culling);
        }
    }
}
