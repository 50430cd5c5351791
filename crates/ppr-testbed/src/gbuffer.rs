//! The G-buffer pass: rasterises a level into colour, depth, world normal and reflector id.
//!
//! The same pass draws the mirrored views of the exact reference ([`crate::MirrorReference`]);
//! there the winding flips and the reflector mask is disabled.

use ppr_runtime::DepthMode;

use crate::gbuffer_targets::{COLOR_FORMAT, DEPTH_FORMAT, GBuffer, NORMAL_FORMAT, REFLECTOR_ID_FORMAT};
use crate::mesh::{FaceCulling, LevelMeshes};
use crate::scene_layouts::SceneLayouts;
use crate::view::ViewBindings;

const CULLINGS: [FaceCulling; 4] =
    [FaceCulling::BackCcw, FaceCulling::BackCw, FaceCulling::None, FaceCulling::NoneCw];

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
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("gbuffer shader"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../shaders/gbuffer.wgsl").into()),
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("gbuffer pipeline layout"),
            bind_group_layouts: &[Some(&layouts.view), Some(&layouts.material), Some(&layouts.draw)],
            immediate_size: 0,
        });
        let make = |depth: DepthMode, culling: FaceCulling| {
            let (front_face, cull_mode) = match culling {
                FaceCulling::BackCcw => (wgpu::FrontFace::Ccw, Some(wgpu::Face::Back)),
                FaceCulling::BackCw => (wgpu::FrontFace::Cw, Some(wgpu::Face::Back)),
                FaceCulling::None => (wgpu::FrontFace::Ccw, None),
                FaceCulling::NoneCw => (wgpu::FrontFace::Cw, None),
            };
            let compare = ppr_runtime::Projection { depth, ..Default::default() }.depth_compare();
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&format!("gbuffer pipeline ({depth:?} depth, {culling:?})")),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some("vs_main"),
                    compilation_options: Default::default(),
                    buffers: &[Some(LevelMeshes::vertex_layout())],
                },
                primitive: wgpu::PrimitiveState {
                    topology: wgpu::PrimitiveTopology::TriangleList,
                    front_face,
                    cull_mode,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(compare),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some("fs_main"),
                    compilation_options: Default::default(),
                    targets: &[
                        Some(COLOR_FORMAT.into()),
                        Some(NORMAL_FORMAT.into()),
                        Some(REFLECTOR_ID_FORMAT.into()),
                    ],
                }),
                multiview_mask: None,
                cache: None,
            })
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
        let color = |view, clear| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Clear(clear), store: wgpu::StoreOp::Store },
            })
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(match draw.kind {
                ViewKind::Direct => "gbuffer pass",
                ViewKind::Mirrored => "gbuffer pass (mirrored view)",
            }),
            color_attachments: &[
                color(&t.color.view, wgpu::Color { r, g, b, a }),
                color(&t.normal.view, wgpu::Color::TRANSPARENT),
                color(&t.reflector_id.view, wgpu::Color::TRANSPARENT),
            ],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &t.depth.view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(far),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        views.bind(&mut pass, draw.slot);
        for culling in CULLINGS {
            let pass_culling = match draw.kind {
                ViewKind::Direct => culling,
                ViewKind::Mirrored => culling.mirrored(),
            };
            pass.set_pipeline(&self.pipelines[depth_index(draw.depth)][culling_index(pass_culling)]);
            meshes.record_draws(&mut pass, culling);
        }
    }
}
