//! `ReflectionRenderer`: what a game creates once and calls twice per frame.

use std::cell::{Cell, RefCell};
use std::sync::Arc;

use glam::DMat4;
use ppr_format::ValidatedSet;

use crate::camera::Camera;
use crate::encoding::EncodingLayout;
use crate::frame_buffers::FrameBuffers;
use crate::frame_upload::{FrameUpload, UploadMemory};
use crate::glossy::glossy_shapes;
use crate::gpu_types::{FLAG_LAYER_EVERY_TILE, FLAG_OCCLUDER_TESTS, FrameUniforms, GpuLayer, kind_code};
use crate::passes::layer_reflection::LayerPlacement;
use crate::passes::projection::BoxReduction;
use crate::passes::reflection::{ReflectionAblation, ReflectionVariant};
use crate::passes::{
    Ablation, BlockListPass, ClearPass, DownsamplePass, LayerReflectionPass, ProjectionPass,
    ProjectionVariant, ReflectionPass, SuperTileListPass, TileClassifyPass, UpsamplePass,
};
use crate::plan::{Choice, FramePlan, PlanParams};
use crate::reduced_targets::ReducedTargets;
use crate::settings::{ReflectionSettings, WriteMode};
use crate::shapes::ShapeTable;
use crate::timestamps::{PassTimer, PassTimings, TIMED_PASSES};
use crate::upload_layout::UploadTarget;
use crate::upload_ring::UploadRing;

mod recording;

/// Pixels within this fraction of their camera distance from a reflector's plane count as
/// lying on it and are not reflected by it (else a reflector reflects itself). 1e-4 covers
/// the position error of an f32 depth buffer at 1000× the near-plane distance.
pub const PLANE_EPSILON: f32 = 1e-4;

/// How a renderer is created.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RendererDesc {
    /// Write GPU timestamps around each pass when the device supports them.
    pub timestamps: bool,
}

impl Default for RendererDesc {
    fn default() -> Self {
        Self { timestamps: true }
    }
}

/// The textures one frame reads and writes.
///
/// - `color`: the lit scene, `Rgba16Float` (any filterable float format works),
///   `TEXTURE_BINDING`;
/// - `depth`: the scene's depth, `Depth32Float`, `TEXTURE_BINDING`, a depth-only view,
///   written with the camera's [`crate::Projection`] (standard or reversed Z);
/// - `output`: `Rgba16Float` with `STORAGE_BINDING`, same size: reflected colour, alpha a
///   confidence in [0, 1] (0 where no reflection was found, else fading towards the screen
///   borders over [`ReflectionSettings::border_fade`]; `alpha > 0` tells "found"). Blend it
///   over the engine's own fallback: `mix(fallback, rgb, alpha)`. It is written only where the plan's
///   passes run: nowhere when [`FramePlan::is_empty`], and with indirect dispatch only in
///   tiles that show a visible reflector (every pixel on a visible reflector is covered).
///
/// Optional:
/// - `layer_output`: like `output`, for the reflections of glass panels and water planes
///   (the nearest one the view ray hits in front of the depth buffer); written when the
///   plan has layers, over each layer's rectangle (`plan.layers[i].rect`); elsewhere in the
///   plan's `layer_rect` left as it was at full resolution (but for the rest of the 16 × 16
///   tiles that meet a layer's rectangle) or written with no reflection (the reduced
///   tiers), and outside `layer_rect` not written. With [`PlanParams::layers`] at `Auto`, a
///   renderer whose last frame with layers had no layer output plans no layers until an
///   `encode` gives one (only that first frame computes them for nothing); passing one
///   only when the plan has layers keeps them; `Off` never plans them.
/// - `normals`: the shading normals (world space, xyz in any float format, e.g.
///   `Rgba16Float`), `TEXTURE_BINDING`; reflectors with `normal_map` are perturbed by them.
pub struct FrameInputs<'a> {
    pub color: &'a wgpu::TextureView,
    pub depth: &'a wgpu::TextureView,
    pub output: &'a wgpu::TextureView,
    pub layer_output: Option<&'a wgpu::TextureView>,
    pub normals: Option<&'a wgpu::TextureView>,
}

impl<'a> FrameInputs<'a> {
    /// The three required textures; no layer output, no normals.
    pub fn new(
        color: &'a wgpu::TextureView,
        depth: &'a wgpu::TextureView,
        output: &'a wgpu::TextureView,
    ) -> Self {
        Self { color, depth, output, layer_output: None, normals: None }
    }
}

/// Debug and bench knobs of a [`ReflectionRenderer`]: what the inspector, the tests and the
/// bench change, and a game leaves at the defaults.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DebugOptions {
    /// How the projection pass writes (shows the write-order artefact).
    pub write_mode: WriteMode,
    /// Record per source pixel which visible shapes it wrote for (see
    /// [`ReflectionRenderer::debug_writes_buffer`]).
    pub writes: bool,
    /// With `writes`: record each pixel's tile candidate-list length (0xffffffff: the list
    /// overflowed or there is none; with subgroup culling, the candidates the pixel's
    /// subgroup visits) instead of the write bits.
    pub tile_lists: bool,
    /// Use this encoding instead of the one the plan picks for the viewport (e.g. the
    /// seed's layout, or fraction mirroring off to show the swimming artefact). It must
    /// fit the viewport ([`EncodingLayout::fits_viewport`]) or long offsets are dropped.
    pub encoding: Option<EncodingLayout>,
    /// Leave parts of the projection pass out, to time the rest (bench only; the image
    /// is wrong with anything but [`Ablation::None`]).
    pub projection_ablation: Ablation,
    /// The projection's threads take one pixel in each 16 × 16 quarter of their block
    /// (the layout before the compact one; bench only, the same image).
    pub spread_quads: bool,
    /// The block-list pass stops after each block's box of positions (bench only, to time
    /// the rest of it; the projection then reads no lists: never a correct image).
    pub block_lists_box_only: bool,
    /// Leave parts of the reflection pass out, to time the rest (bench only; the image is
    /// wrong with anything but [`ReflectionAblation::None`]).
    pub reflection_ablation: ReflectionAblation,
    /// The reflection pass takes mirrors two by two pixels per invocation in direct
    /// dispatch, sharing their neighbourhood reads, instead of one pixel each (the default
    /// of the seventh to thirteenth sessions; bench only, the same image).
    pub reflection_quads: bool,
    /// The most taps per pixel of the glossy blur instead of the default (12): what the
    /// blur's cost and accuracy are made of (0 and 1 leave the image sharp: 0 stops after
    /// the reflector lookup, 1 after the footprint, for the bench's cost profile).
    pub glossy_taps: Option<u32>,
    /// The block lists the projection builds flag no entry as lying wholly inside its
    /// shape's pyramid: every pixel runs the side tests (bench only, the same image;
    /// the block-list pass flags them either way).
    pub no_inside_entries: bool,
    /// The water edge stretch reads all its steps, also those past the layer's rectangle
    /// (the walk before the eighteenth session; bench only, the same image).
    pub full_stretch_walk: bool,
    /// The layer reflection is dispatched over every 16 × 16 tile of the layers' common
    /// rectangle and writes them all, also those that meet no layer's own (the pass before
    /// the thirty-first session, as the reduced tiers run it; bench only, the same image
    /// inside the layers' rectangles).
    pub layer_every_tile: bool,
    /// How the block lists the projection builds reduce the box of the block's positions
    /// (bench only, the same lists; `ProjectionVariant::box_reduction`).
    pub box_reduction: BoxReduction,
    /// The block lists the projection builds load their first chunk's candidates and shape
    /// tests before the box reduction (bench only, the same lists;
    /// `ProjectionVariant::list_prefetch`).
    pub list_prefetch: bool,
    /// Every direct-dispatch frame clears its intermediate buffer (and atlas) in the clear
    /// pass, as before the twenty-fourth session, instead of finding them cleared by the
    /// last encode's reflection pass (bench only, the same image).
    pub clear_pass_every_frame: bool,
    /// Indirect frames' reflection pass walks the active-tile list with at most this many
    /// workgroups instead of [`TILE_LOOP_GROUPS`] (`ReflectionVariant::tile_loop`; bench
    /// only, the same image).
    pub reflection_tile_loop: Option<u32>,
    /// Indirect frames' reflection pass runs one workgroup per active tile by indirect
    /// dispatch instead of the tile loop (the layout before the twenty-fourth session;
    /// bench only, the same image).
    pub reflection_indirect_dispatch: bool,
    /// KiB of workgroup memory added to the projection that no frame uses, so that fewer
    /// of its workgroups run at once (`ProjectionVariant::occupancy_pad_kib`; bench only,
    /// the same image).
    pub occupancy_pad_kib: u32,
    /// Where the layer reflection is recorded: in the reflection's compute pass (the
    /// default; `PassTimings::layers_ms` is then `None` and the reflection's time covers
    /// both) or in its own (bench only, the same image).
    pub layer_placement: LayerPlacement,
    /// Time the frame as a whole, from two encoder timestamps around everything `encode`
    /// records (the upload's copies, the passes and the barriers between them;
    /// `PassTimings::frame_ms`), instead of a pair around each pass, which leaves the
    /// copies and barriers out (bench only, on devices with
    /// `TIMESTAMP_QUERY_INSIDE_ENCODERS`; elsewhere nothing is timed).
    pub frame_span: bool,
    /// Indirect frames record the tile classification in a compute pass of its own, timed on
    /// its own (the layout before the twenty-sixth session; bench only, the same image),
    /// instead of in the projection's (wgpu's barrier between the two dispatches; the
    /// projection's time covers both), which took 0.006-0.007 ms off the 4K overviews of
    /// the demo and the kitchen (H100, whole frames; docs/perf/runtime.md).
    pub classify_own_pass: bool,
    /// The reflection recorded in a compute pass of its own (the layout before the
    /// twenty-sixth session; bench only, the same image), instead of in the projection's
    /// (wgpu's barrier between them; timed together as
    /// `PassTimings::projection_reflection_ms`), which took 0.006 ms off the kitchen's two
    /// views without layers at 1080p and 4K (H100, whole frames). See also
    /// `layered_reflection_own_pass`.
    pub reflection_own_pass: bool,
    /// Copy each part of the frame upload on its own (eight to ten copy commands, as before
    /// the twenty-seventh session; bench only, the same frame) instead of one copy per run
    /// of parts that lie close together in the upload buffer (one for a level of a few
    /// hundred shapes), which took 0.009-0.013 ms off every frame of the demo and the
    /// kitchen and 0.035 off the 10 000-tread stairway's (H100, whole frames;
    /// docs/perf/runtime.md).
    pub separate_upload_copies: bool,
    /// On devices with `MAPPABLE_PRIMARY_BUFFERS`: copy the frame upload from a staging
    /// buffer into the frame buffers' upload buffer, as on every device before the
    /// thirty-third session (bench only, the same frame), instead of writing it into a
    /// mapped buffer that the passes bind themselves (`FrameBuffers::bindable_uploads`).
    pub copied_upload: bool,
    /// On frames whose layer dispatch goes with the reflection: record the two in a compute
    /// pass of their own after the projection's (the twenty-sixth session's layout; bench
    /// only, the same image), instead of in the projection's pass with the layers first
    /// (the layer dispatch binds the intermediate buffer, so that its barrier readies the
    /// reflection's buffers too), which took 0.005-0.008 ms off every layered frame of the
    /// demo and the kitchen (H100, whole frames). Without that binding the merged layout
    /// waited on a second barrier and lost 0.001-0.002 ms.
    pub layered_reflection_own_pass: bool,
    /// The reduced tiers' upsample reads each workgroup's reduced samples (colour, and
    /// their camera distances) into workgroup memory once, and each pixel its four from
    /// there, instead of each pixel reading its own four from the textures and computing
    /// their distances (`UpsampleVariant::shared`; bench only, the same image bit for bit).
    pub shared_upsample: bool,
    /// The reduced tiers' upsample replaced by a probe of its time (bench only, not the
    /// image: `UpsampleProbe`), on the output's dispatch (the layer output's stays).
    pub upsample_probe: crate::passes::upsample::UpsampleProbe,
}

/// Workgroups of the reflection pass's tile loop in indirect frames (`reflection.wgsl`'s
/// `TILE_LOOP`): 256 invocations each. A direct dispatch of at most this many workgroups
/// walking the active-tile list replaced the indirect dispatch, which wgpu precedes with a
/// validation dispatch and barriers of its own: 0.006-0.009 ms less for the 4K overviews'
/// mirror reflection on the H100 with 1 024 workgroups (docs/perf/runtime.md, twenty-fourth
/// session). On the H200, 4 096 take the demo's 4K overview (6 703 active tiles, its glossy
/// tiles uneven) 0.0740 -> 0.0636 ms (indirect dispatch 0.0712), as mirrors 0.0334 ->
/// 0.0300, and cost the kitchen's (260 tiles) 0.0008 and 0.0003 ms; on the H100 the demo's
/// 0.0739 (1 024) / 0.0699 (2 048) / 0.0639 (4 096) / 0.0657 (8 192), the kitchen's within
/// 0.0008 of each other (twenty-fifth session).
pub const TILE_LOOP_GROUPS: u32 = 4096;

/// Renders pixel-projected reflections: `prepare` then `encode`, once per view (several views
/// may share one renderer and one submit).
///
/// ```no_run
/// # fn frames(device: &wgpu::Device, queue: &wgpu::Queue, set: &ppr_format::ValidatedSet,
/// #     camera: &ppr_runtime::Camera, color: &wgpu::TextureView, depth: &wgpu::TextureView,
/// #     output: &wgpu::TextureView, [width, height]: [u32; 2]) {
/// use ppr_runtime::{FrameInputs, ReflectionRenderer, RendererDesc};
/// // once:
/// let mut ppr = ReflectionRenderer::new(device, queue, &RendererDesc::default());
/// ppr.set_reflectors(set); // a ValidatedSet: ValidatedSet::load(path)?, or ::new(set)?
/// // every frame, after the scene's colour and depth are recorded:
/// let plan = ppr.prepare(camera, [width, height]);
/// let mut encoder = device.create_command_encoder(&Default::default());
/// ppr.encode(&mut encoder, &FrameInputs::new(color, depth, output));
/// queue.submit([encoder.finish()]);
/// let timings = ppr.read_timings(); // optional: waits for the GPU
/// # }
/// ```
pub struct ReflectionRenderer {
    device: wgpu::Device,
    /// Whether the device is a CPU adapter (llvmpipe): `Auto` fused lists stay off there.
    cpu_adapter: bool,
    /// Steps of the reflection pass; change at any time.
    pub settings: ReflectionSettings,
    /// How the frame plan picks passes and variants.
    pub plan_params: PlanParams,
    /// Debug and bench knobs (write order, write records, encoding, ablations); a game
    /// leaves them at their defaults.
    pub debug: DebugOptions,
    classify: TileClassifyPass,
    clear: ClearPass,
    super_tile_lists: SuperTileListPass,
    block_lists: BlockListPass,
    projection: ProjectionPass,
    reflection: ReflectionPass,
    layer_reflection: LayerReflectionPass,
    downsample: DownsamplePass,
    upsample: UpsamplePass,
    /// The reduced tiers' textures (allocated by the first reduced `prepare`).
    reduced: Option<ReducedTargets>,
    table: ShapeTable,
    table_dirty: bool,
    buffers: Option<FrameBuffers>,
    /// What the last `prepare` (one view) or `prepare_stereo` (two) planned and uploads.
    pub(crate) views: Vec<PreparedView>,
    timer: Option<PassTimer>,
    pub(crate) dispatches: Cell<u32>,
    /// Copy commands of the last encode's upload.
    upload_copies: Cell<usize>,
    /// Where `encode` writes each view's upload for its copies (devices without
    /// `MAPPABLE_PRIMARY_BUFFERS`, or `DebugOptions::copied_upload`): staging buffers that
    /// come back once their encoder's commands are submitted and done.
    upload_ring: RefCell<UploadRing>,
    /// Whether the frames want layers: the last `encode` that gave a layer output, or had
    /// layers without one (`None` before either).
    layer_output_given: Cell<Option<bool>>,
    /// The timed passes the last `encode` recorded ([`Self::passes_recorded`]).
    recorded: Cell<[bool; TIMED_PASSES as usize]>,
}

impl ReflectionRenderer {
    /// Builds the pipelines (once).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, desc: &RendererDesc) -> Self {
        Self {
            device: device.clone(),
            cpu_adapter: device.adapter_info().device_type == wgpu::DeviceType::Cpu,
            settings: ReflectionSettings::default(),
            plan_params: PlanParams::default(),
            debug: DebugOptions::default(),
            classify: TileClassifyPass::new(device),
            clear: ClearPass::new(device),
            super_tile_lists: SuperTileListPass::new(device),
            block_lists: BlockListPass::new(device),
            projection: ProjectionPass::new(device),
            reflection: ReflectionPass::new(device),
            layer_reflection: LayerReflectionPass::new(device),
            downsample: DownsamplePass::new(device),
            upsample: UpsamplePass::new(device),
            reduced: None,
            table: ShapeTable::default(),
            table_dirty: true,
            buffers: None,
            views: Vec::new(),
            timer: if desc.timestamps { PassTimer::new(device, queue) } else { None },
            dispatches: Cell::new(0),
            upload_copies: Cell::new(0),
            upload_ring: RefCell::new(UploadRing::staging(device)),
            layer_output_given: Cell::new(None),
            recorded: Cell::new([false; TIMED_PASSES as usize]),
        }
    }

    /// Replaces the reflectors. The set is a [`ValidatedSet`] (from
    /// [`ValidatedSet::load`], [`ValidatedSet::from_json_str`] or [`ValidatedSet::new`] on
    /// a set built or edited in memory), so every invariant of the format holds and this
    /// cannot fail. Cheap: no pipeline is rebuilt.
    pub fn set_reflectors(&mut self, set: &ValidatedSet) {
        self.table = ShapeTable::from_set(set);
        self.table_dirty = true;
    }

    /// The reflectors as the runtime holds them.
    pub fn shapes(&self) -> &ShapeTable {
        &self.table
    }

    /// Plans the frame and packs what the GPU needs into an upload of its own, which
    /// [`Self::encode`] copies in where it records the passes. Call before [`Self::encode`]
    /// once per view and frame; several views may be prepared and encoded (prepare, encode,
    /// prepare, encode) before one submit, each with its own camera.
    ///
    /// With a reduced [`crate::ResolutionTier`] the plan is built for the reduced viewport.
    ///
    /// Returns the plan (shared, cheap to keep: the renderer holds the same one until the
    /// next `prepare`).
    pub fn prepare(&mut self, camera: &Camera, viewport: [u32; 2]) -> Arc<FramePlan> {
        let [plan] = self.prepare_views([camera], viewport);
        plan
    }

    /// Plans each view, makes the frame buffers fit every plan, and packs each view's upload.
    pub(crate) fn prepare_views<const N: usize>(
        &mut self,
        cameras: [&Camera; N],
        viewport: [u32; 2],
    ) -> [Arc<FramePlan>; N] {
        let tier = self.settings.resolution;
        let planned = tier.reduced(viewport);
        let reduced_active = planned != viewport;
        if reduced_active && self.reduced.as_ref().is_none_or(|r| r.size != planned) {
            self.reduced = Some(ReducedTargets::new(&self.device, planned));
        }
        let mut params = self.plan_params;
        if params.layers == Choice::Auto && !self.layer_output_given.get().unwrap_or(true) {
            // The last encode gave the layers nowhere to go: do not compute them.
            params.layers = Choice::Off;
        }
        if params.subgroup_cull == Choice::Auto && !crate::passes::projection::has_subgroups(&self.device) {
            params.subgroup_cull = Choice::Off;
        }
        if params.fused_lists == Choice::Auto && self.cpu_adapter {
            params.fused_lists = Choice::Off;
        }
        if self.debug.writes {
            // Debug write masks record each visible shape; a merged group writes as one.
            params.plane_groups = Choice::Off;
            params.parallel_trees = Choice::Off;
        }
        let plans = cameras.map(|camera| {
            let mut plan = FramePlan::build_for_output(&self.table, camera, planned, viewport, &params);
            if let Some(layout) = self.debug.encoding {
                plan.encoding = layout;
            }
            if !plan.is_empty() {
                self.projection.prepare_variant(&self.device, self.variant(&plan));
                self.reflection.prepare_variant(&self.device, self.reflection_variant(false, false));
                if plan.indirect && plan.layers.is_empty() {
                    self.classify.prepare_without_layers(&self.device);
                }
                if self.debug.block_lists_box_only {
                    self.block_lists.prepare_box_only(&self.device);
                }
                if self.debug.full_stretch_walk {
                    self.layer_reflection.prepare_full_stretch(&self.device);
                }
                if self.debug.shared_upsample && reduced_active {
                    self.upsample.prepare_shared(&self.device);
                }
                if reduced_active {
                    self.upsample.prepare_probe(&self.device, self.debug.upsample_probe);
                }
            }
            Arc::new(plan)
        });
        let fits = self
            .buffers
            .as_ref()
            .is_some_and(|b| plans.iter().all(|p| b.fits(&self.table, p, self.debug.writes)));
        if self.table_dirty || !fits {
            let all: Vec<&FramePlan> = plans.iter().map(|p| p.as_ref()).collect();
            self.buffers = Some(FrameBuffers::new(&self.device, &self.table, &all, self.debug.writes));
            self.table_dirty = false;
        }
        // The last frame's upload memory, reused (a fresh allocation of megabytes a frame
        // costs page faults on every frame with thousands of shapes).
        let mut recycled: Vec<UploadMemory> = std::mem::take(&mut self.views)
            .into_iter()
            .filter_map(|v| v.upload.map(FrameUpload::into_memory))
            .collect();
        self.views = cameras
            .iter()
            .zip(&plans)
            .map(|(camera, plan)| PreparedView {
                plan: Arc::clone(plan),
                upload: self.upload(camera, plan, reduced_active, recycled.pop().unwrap_or_default()),
                full_viewport: viewport,
                reduced_active,
            })
            .collect();
        plans
    }

    /// How many copy commands the last view `encode` recorded carried its upload (one for
    /// a level of a few hundred shapes: tests and diagnostics).
    #[doc(hidden)]
    pub fn last_upload_copy_count(&self) -> usize {
        self.upload_copies.get()
    }

    /// How many buffers `encode` has created for the frame uploads: staging buffers, and
    /// the current frame buffers' bound ones (they are reused once their frame's commands
    /// have run: tests and diagnostics).
    #[doc(hidden)]
    pub fn upload_buffers_created(&self) -> usize {
        let bound = self
            .buffers
            .as_ref()
            .and_then(|b| b.bindable_uploads.as_ref())
            .map_or(0, |r| r.borrow().created());
        self.upload_ring.borrow().created() + bound
    }

    /// The plan of the last [`Self::prepare`].
    pub fn plan(&self) -> Option<&FramePlan> {
        self.views.first().map(|v| v.plan.as_ref())
    }

    /// The reflection pass's variant for a frame with (or without) normal maps and glossy.
    fn reflection_variant(&self, normal_maps: bool, glossy: bool) -> ReflectionVariant {
        ReflectionVariant {
            normal_maps,
            glossy,
            holes: self.settings.holes,
            ablation: self.debug.reflection_ablation,
            quads: self.debug.reflection_quads,
            leave_next: self.debug.clear_pass_every_frame,
            tile_loop: (!self.debug.reflection_indirect_dispatch)
                .then(|| self.debug.reflection_tile_loop.unwrap_or(TILE_LOOP_GROUPS)),
        }
    }

    fn variant(&self, plan: &FramePlan) -> ProjectionVariant {
        ProjectionVariant {
            tile_culling: plan.tile_culling,
            super_tiles: plan.super_tiles,
            fused_lists: plan.fused_lists,
            parallel_rule: plan.parallel_rule,
            occluder_tests: plan.occluder_tests,
            path_blockers: plan.path_blockers,
            depth_occlusion: plan.depth_occlusion,
            layers: !plan.layers.is_empty(),
            debug_writes: self.debug.writes,
            debug_tile_lists: self.debug.writes && self.debug.tile_lists,
            source_boxes: !plan.source_rects.is_empty(),
            uniform_tests: plan.uniform_tests,
            parallel_trees: !plan.trees.is_empty(),
            subgroup_cull: plan.subgroup_cull,
            spread_quads: self.debug.spread_quads,
            occlusion_first: plan.occlusion_first,
            no_inside_entries: self.debug.no_inside_entries,
            box_reduction: self.debug.box_reduction,
            list_prefetch: self.debug.list_prefetch,
            occupancy_pad_kib: self.debug.occupancy_pad_kib,
            ablation: self.debug.projection_ablation,
        }
    }

    /// What `encode` copies into the frame buffers for this view (`None` for an empty plan:
    /// nothing is encoded), in `memory` (the last frame's, refilled); `reduced`: the plan
    /// is a reduced tier's.
    fn upload(
        &self,
        camera: &Camera,
        plan: &FramePlan,
        reduced: bool,
        mut memory: UploadMemory,
    ) -> Option<FrameUpload> {
        let [w, h] = plan.viewport;
        let b = self.buffers.as_ref().expect("prepare_views allocates the buffers");
        if plan.is_empty() {
            return None;
        }
        self.table.gpu_shapes_into(camera.position, &mut memory.shapes);

        let clip_from_rel = camera.clip_from_relative(plan.aspect);
        // Invert in f64: the reversed-Z and infinite projections are badly conditioned.
        let rel_from_clip = DMat4::from_cols_array(&clip_from_rel.to_cols_array().map(f64::from)).inverse();
        let uniforms = FrameUniforms {
            clip_from_rel: clip_from_rel.to_cols_array_2d(),
            rel_from_clip: rel_from_clip.as_mat4().to_cols_array_2d(),
            resolution: [w as f32, h as f32, 1.0 / w as f32, 1.0 / h as f32],
            size: [w, h],
            visible_count: plan.visible.len() as u32,
            flags: self.settings.flags()
                | self.debug.write_mode.flags()
                | if plan.occluder_tests { FLAG_OCCLUDER_TESTS } else { 0 }
                | if reduced || self.debug.layer_every_tile { FLAG_LAYER_EVERY_TILE } else { 0 },
            far_depth: camera.projection.far_depth(),
            plane_epsilon: PLANE_EPSILON,
            layer_count: plan.layers.len() as u32,
            tested_count: plan.tested.len() as u32,
            layer_origin: plan.layer_rect.min,
            layer_extent: [
                plan.layer_rect.max[0].saturating_sub(plan.layer_rect.min[0]),
                plan.layer_rect.max[1].saturating_sub(plan.layer_rect.min[1]),
            ],
            encoding: plan.encoding.gpu_params(),
            border_fade_px: self.settings.border_fade_px(plan.viewport),
            _pad1: [0; 3],
        };
        let layers: Vec<GpuLayer> = plan
            .layers
            .iter()
            .map(|l| GpuLayer {
                rect_min: l.rect.min,
                rect_max: l.rect.max,
                offset: l.offset,
                shape: l.shape,
                kind: kind_code(l.kind),
                _pad: 0,
            })
            .collect();
        memory.tests.fill(&self.table, plan, camera.position);
        let taps = self.debug.glossy_taps.unwrap_or(crate::glossy::GLOSSY_TAPS);
        let glossy = glossy_shapes(&self.table, plan, camera.position, taps);
        debug_assert!(b.fits(&self.table, plan, self.debug.writes));
        Some(FrameUpload::new(
            &[
                (UploadTarget::Uniforms, bytemuck::bytes_of(&uniforms)),
                (UploadTarget::Visible, bytemuck::cast_slice(&plan.visible)),
                (UploadTarget::ScreenRects, bytemuck::cast_slice(&plan.screen_rects)),
                (UploadTarget::Layers, bytemuck::cast_slice(&layers)),
                (UploadTarget::SourceRects, bytemuck::cast_slice(&plan.source_rects)),
                (
                    UploadTarget::Glossy,
                    if plan.glossy.is_empty() { &[] } else { bytemuck::bytes_of(&glossy) },
                ),
            ],
            memory,
        ))
    }

    /// Records the last prepared view's passes into `encoder` (nothing when the plan is
    /// empty), starting with the copies of its upload. Calling it again for the same
    /// `prepare` records the same frame again.
    ///
    /// Encodes take the renderer's two intermediate buffers by turns, and a full-screen
    /// reflection pass clears the one the next encode takes (no clear pass then): submit
    /// the encoders in the order they were encoded, and drop none that holds an encode
    /// (after one is dropped unsubmitted, call [`Self::forget_cleared`]).
    ///
    /// # Panics
    /// If [`Self::prepare`] was not called first.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, inputs: &FrameInputs<'_>) {
        let view = self.views.first().expect("prepare() before encode()");
        self.dispatches.set(0);
        self.encode_view(encoder, view, inputs);
    }

    /// Dispatches recorded by the last [`Self::encode`] (0 when nothing was visible).
    pub fn last_dispatch_count(&self) -> u32 {
        self.dispatches.get()
    }

    /// Whether GPU timestamps are recorded (the device has `TIMESTAMP_QUERY`).
    pub fn has_timestamps(&self) -> bool {
        self.timer.is_some()
    }

    /// Records no GPU timestamps from now on ([`Self::read_timings`] gives `None`, and
    /// `DebugOptions::frame_span` times nothing): for a caller that times the frame
    /// between timestamps of its own.
    pub fn stop_timestamps(&mut self) {
        self.timer = None;
    }

    /// Waits for the last submitted frame and returns its GPU time per pass, when the
    /// device supports timestamps and the last plan ran passes; `None` at once (without
    /// waiting) when it ran none (an empty plan).
    pub fn read_timings(&self) -> Option<PassTimings> {
        let ran = self.passes_recorded();
        if !ran.contains(&true) {
            return None;
        }
        self.timer.as_ref()?.read(&self.device, ran)
    }

    /// Forgets that the next encode's intermediate buffer was cleared by the last one: for
    /// an application that dropped an encoder holding an encode without submitting it, so
    /// that the next encode clears its buffers in the clear pass.
    pub fn forget_cleared(&self) {
        if let Some(b) = &self.buffers {
            b.forget_clean();
        }
    }

    /// Which timed passes (classify, clear, projection, reflection, layers, as in
    /// [`PassTimings::passes`]) the last [`Self::encode`] recorded. A pass recorded but
    /// without a time in [`Self::read_timings`] had timestamps the adapter got wrong.
    pub fn passes_recorded(&self) -> [bool; TIMED_PASSES as usize] {
        self.recorded.get()
    }

    /// The intermediate buffer (one u32 per pixel, row-major, padded to 16 bytes) of the
    /// last [`Self::encode`] (encodes take two buffers by turns), for debug views and tests.
    /// With indirect dispatch only active tiles are meaningful. `None` before the first
    /// [`Self::prepare`].
    pub fn intermediate_buffer(&self) -> Option<&wgpu::Buffer> {
        self.buffers.as_ref().map(|b| &b.intermediate[b.last_slot()])
    }

    /// With [`DebugOptions::writes`], one u32 per pixel: bit `k % 32` set when the pixel was
    /// written for the `k`-th shape of the plan's visible list.
    pub fn debug_writes_buffer(&self) -> Option<&wgpu::Buffer> {
        self.buffers.as_ref().filter(|_| self.debug.writes).map(|b| &b.debug_writes)
    }

    /// The super-tile counts and lists of the last frame that built them (layout in
    /// `crates/ppr-runtime/shaders/super_tile_lists.wgsl`), for debug views and tests.
    pub fn super_tile_lists_buffer(&self) -> Option<&wgpu::Buffer> {
        self.buffers.as_ref().map(|b| &b.super_lists)
    }

    /// The active-tile list of the last frame (count, the indirect dispatch arguments x, y,
    /// z, tile indices), for debug views and tests.
    pub fn active_tiles_buffer(&self) -> Option<&wgpu::Buffer> {
        self.buffers.as_ref().map(|b| &b.active_tiles[b.last_slot()])
    }
}

/// One view's part of a `prepare`: its plan, the upload `encode` copies in before its
/// passes, and the full-size viewport (the plan's is reduced in the reduced tiers).
pub(crate) struct PreparedView {
    pub plan: Arc<FramePlan>,
    pub upload: Option<FrameUpload>,
    pub full_viewport: [u32; 2],
    pub reduced_active: bool,
}
