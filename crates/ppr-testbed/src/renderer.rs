//! Renders a level: the main G-buffer and the exact mirrored reference, for any camera.

use ppr_format::ReflectorSet;
use ppr_runtime::Camera;
use ppr_scene_gpu::LevelMeshes;

use crate::bounce_composite::{BounceCompositePass, BounceTargets};
use crate::bounce_plan::{BounceParent, BouncePlan, BounceRoot, BounceScene, plan_bounces};
use crate::composite::CompositeParams;
use crate::gbuffer::{GBUFFER_SURFACES, GBufferDraw, GBufferPass, ViewKind};
use crate::gbuffer_targets::GBuffer;
use crate::glossy_accumulate::{GlossyAccumulatePass, GlossyBindings, GlossyStats};
use crate::glossy_plan::{GlossyPlan, plan_glossy, rough_plane_count, sample_uniform};
use crate::glossy_resolve::GlossyResolvePass;
use crate::glossy_views::GlossyParams;
use crate::level::Level;
use crate::mirror_camera::{MirrorClipping, mirrored_view};
use crate::mirror_chain::ChainedView;
use crate::reference::{MirrorReference, OnScreenTolerance, ReferenceBindings, ReferenceTargets};
use crate::reflector_planes::{ReflectorPlane, group_by_plane, may_be_visible};
use crate::scene_layouts::{SceneLayouts, gbuffer_layouts};
use crate::view::{Lighting, ReflectorMaskParams, ReflectorShape, ViewBindings, ViewUniform};

/// Linear background colour of the testbed (what a view shows where nothing is drawn).
pub const DEFAULT_BACKGROUND: [f64; 4] = [0.05, 0.07, 0.11, 1.0];

/// Everything that decides how a frame looks, apart from the camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// The light.
    pub lighting: Lighting,
    /// How reflector pixels are recognised.
    pub mask: ReflectorMaskParams,
    /// Linear colour where nothing is drawn, in the main and the mirrored views.
    pub background: [f64; 4],
    /// Tolerances of the reference's on-screen test.
    pub on_screen: OnScreenTolerance,
    /// Near plane of the mirrored views; [`MirrorClipping::Oblique`] for the exact reference.
    pub mirror_clipping: MirrorClipping,
    /// Bounces of the reference: 1 shows other mirrors in a reflection with their own
    /// colour; `N` composites each mirror seen in a mirrored view with its own reflection,
    /// recursively to depth `N` (`mix(colour, reflection, CompositeParams::default()
    /// .reflectivity)`, the composite's formula). 1 to 4 are useful.
    pub reference_bounces: u32,
    /// Most views beyond the first bounce per frame (the recursion's cost cap: views are
    /// planned breadth first, so the deepest bounces go first; the frame's summary counts
    /// those skipped).
    pub max_bounce_views: usize,
    /// The exact glossy reference on reflectors with roughness (off by default: rough
    /// reflectors then show their mirror reflection). Its views show other reflectors with
    /// their own colour (one bounce), whatever [`Self::reference_bounces`] says.
    pub glossy: GlossyParams,
}

/// [`RenderSettings::max_bounce_views`] by default: every second-bounce view of the
/// bench's generated mirror rooms (at most 185, `mirror-room-6`; the corridor 36–77), so
/// their 2-bounce references are exact; a third bounce in the corridor would need ~580.
pub const DEFAULT_MAX_BOUNCE_VIEWS: usize = 256;

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            lighting: Lighting::default(),
            mask: ReflectorMaskParams::default(),
            background: DEFAULT_BACKGROUND,
            on_screen: OnScreenTolerance::default(),
            mirror_clipping: MirrorClipping::Oblique,
            reference_bounces: 1,
            max_bounce_views: DEFAULT_MAX_BOUNCE_VIEWS,
            glossy: GlossyParams::off(),
        }
    }
}

/// What [`LevelRenderer::prepare`] decided for a frame.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameSummary {
    /// Width and height in pixels.
    pub size: [u32; 2],
    /// Plane groups of the reflector set.
    pub planes: usize,
    /// Indices of the plane groups whose mirrored view is rendered this frame.
    pub rendered_planes: Vec<usize>,
    /// Views rendered beyond the first bounce ([`RenderSettings::reference_bounces`]).
    pub bounce_views: usize,
    /// Views beyond the first bounce left out by [`RenderSettings::max_bounce_views`].
    pub bounce_views_skipped: usize,
    /// Views of the glossy reference ([`RenderSettings::glossy`]).
    pub glossy_views: usize,
}

struct FrameTargets {
    main: GBuffer,
    reference: ReferenceTargets,
    bindings: ReferenceBindings,
    glossy: Option<(GlossyBindings, wgpu::BindGroup)>,
}

/// A level on the GPU with the passes that render it: G-buffer and exact reference.
pub struct LevelRenderer {
    layouts: SceneLayouts,
    gbuffer_pass: GBufferPass,
    reference_pass: MirrorReference,
    bounce_pass: BounceCompositePass,
    bounce_targets: Option<BounceTargets>,
    bounce_plan: BouncePlan,
    glossy_accumulate: GlossyAccumulatePass,
    glossy_resolve: GlossyResolvePass,
    glossy_plan: GlossyPlan,
    meshes: LevelMeshes,
    reflectors: ReflectorSet,
    planes: Vec<ReflectorPlane>,
    views: ViewBindings,
    frame: Option<FrameTargets>,
    summary: FrameSummary,
    camera: Option<Camera>,
    /// How frames look; read at the next [`LevelRenderer::prepare`].
    pub settings: RenderSettings,
}

impl LevelRenderer {
    /// Uploads `level` and builds the passes.
    ///
    /// # Panics
    /// If `level` breaks the invariants of [`Level::validate`].
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, level: &Level, reflectors: &ReflectorSet) -> Self {
        let layouts = gbuffer_layouts(device);
        let gbuffer_pass = GBufferPass::new(device, &layouts);
        let reference_pass = MirrorReference::new(device);
        let bounce_pass = BounceCompositePass::new(device);
        let meshes = LevelMeshes::new(device, queue, &layouts, level, &GBUFFER_SURFACES);
        let views = ViewBindings::new(device, &layouts, 1, 1);
        let mut renderer = Self {
            layouts,
            gbuffer_pass,
            reference_pass,
            bounce_pass,
            bounce_targets: None,
            bounce_plan: BouncePlan::default(),
            glossy_accumulate: GlossyAccumulatePass::new(device),
            glossy_resolve: GlossyResolvePass::new(device),
            glossy_plan: GlossyPlan::default(),
            meshes,
            reflectors: ReflectorSet::new(""),
            planes: Vec::new(),
            views,
            frame: None,
            summary: FrameSummary {
                size: [0, 0],
                planes: 0,
                rendered_planes: Vec::new(),
                bounce_views: 0,
                bounce_views_skipped: 0,
                glossy_views: 0,
            },
            camera: None,
            settings: RenderSettings::default(),
        };
        renderer.set_reflectors(device, reflectors);
        renderer
    }

    /// Replaces the reflector set (the mask and the reference follow it from the next frame).
    pub fn set_reflectors(&mut self, device: &wgpu::Device, reflectors: &ReflectorSet) {
        self.reflectors = reflectors.clone();
        self.planes = group_by_plane(reflectors);
        let slots = 1 + u32::try_from(self.planes.len()).expect("fewer than 2^32 planes");
        self.views = ViewBindings::new(device, &self.layouts, slots, reflectors.reflectors.len());
        self.frame = None;
        self.bounce_targets = None;
    }

    /// The reflector set in use.
    pub fn reflectors(&self) -> &ReflectorSet {
        &self.reflectors
    }

    /// The plane groups of the reflector set.
    pub fn planes(&self) -> &[ReflectorPlane] {
        &self.planes
    }

    /// Allocates targets for `size` if needed and uploads everything the frame seen by
    /// `camera` needs: camera-relative transforms and shapes, view and resolve uniforms.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        camera: &Camera,
        size: [u32; 2],
    ) -> &FrameSummary {
        let size = [size[0].max(1), size[1].max(1)];
        if self.frame.as_ref().is_none_or(|f| f.main.size != size) {
            let main = GBuffer::new(device, size, "main gbuffer");
            let reference = ReferenceTargets::new(device, size);
            let planes = u32::try_from(self.planes.len()).expect("fewer than 2^32 planes");
            let bindings = self.reference_pass.bindings(
                device,
                &main,
                &reference,
                planes,
                self.reflectors.reflectors.len(),
            );
            self.frame = Some(FrameTargets { main, reference, bindings, glossy: None });
            self.bounce_targets = None;
        }
        let bounces = self.settings.reference_bounces.max(1);
        self.allocate_bounces(device, queue, size, bounces);
        self.allocate_glossy(device, size, bounces);
        let frame = self.frame.as_ref().expect("allocated above");
        let aspect = f64::from(size[0]) / f64::from(size[1]);
        let s = &self.settings;
        self.meshes.update_camera(queue, camera.position);
        self.views.write_shapes(queue, &ReflectorShape::from_set(&self.reflectors, camera.position));
        let shape_count =
            u32::try_from(self.reflectors.reflectors.len()).expect("fewer than 2^32 reflectors");
        let main_view =
            ViewUniform::new(camera.clip_from_relative(aspect as f32), &s.lighting, &s.mask, shape_count);
        self.views.write_view(queue, 0, &main_view);

        let mut plane_of = vec![u32::MAX; self.reflectors.reflectors.len()];
        let mut rendered = Vec::new();
        let mut roots = Vec::new();
        // Later bounces need the mirrored views' reflector ids (one bounce keeps them off,
        // as before bounces existed).
        let mirrored_shapes = if bounces > 1 { shape_count } else { 0 };
        for (k, group) in self.planes.iter().enumerate() {
            let slot = u32::try_from(k).expect("fewer than 2^32 planes");
            for &m in &group.members {
                plane_of[m] = slot;
            }
            if !may_be_visible(&self.reflectors, group, camera, aspect) {
                continue;
            }
            let Some(mirrored) = mirrored_view(camera, aspect, &group.plane, s.mirror_clipping) else {
                continue;
            };
            let view =
                ViewUniform::new(mirrored.clip_from_rel.as_mat4(), &s.lighting, &s.mask, mirrored_shapes);
            self.views.write_view(queue, 1 + slot, &view);
            frame.bindings.write_plane(queue, slot, camera, size, &mirrored, &s.on_screen);
            rendered.push(k);
            let reflection = group.plane.reflection_relative_to(camera.position);
            roots.push(BounceRoot { plane: k, chain: ChainedView { view: mirrored, reflection } });
        }
        frame.bindings.write_plane_of_reflector(queue, &plane_of);
        self.bounce_plan = if bounces > 1 {
            let scene = BounceScene {
                set: &self.reflectors,
                planes: &self.planes,
                camera,
                aspect,
                clipping: s.mirror_clipping,
            };
            plan_bounces(&scene, &roots, bounces, s.max_bounce_views)
        } else {
            BouncePlan::default()
        };
        let first_bounce_slot = 1 + u32::try_from(self.planes.len()).expect("fewer than 2^32 planes");
        for (i, v) in self.bounce_plan.views.iter().enumerate() {
            let shapes = if v.depth < bounces { shape_count } else { 0 };
            let view = ViewUniform::new(v.chain.view.clip_from_rel.as_mat4(), &s.lighting, &s.mask, shapes);
            let slot = first_bounce_slot + u32::try_from(i).expect("fewer than 2^32 views");
            self.views.write_view(queue, slot, &view);
        }
        let mut glossy_plan =
            plan_glossy(&self.reflectors, &self.planes, &rendered, camera, aspect, &s.glossy);
        glossy_plan.first_view_slot = self.first_glossy_slot(bounces);
        if let Some((glossy, _)) = &frame.glossy {
            glossy.write_reflectors(queue, &glossy_plan.reflectors);
            let first_view = glossy_plan.first_view_slot;
            for gp in &glossy_plan.planes {
                let slot = u32::try_from(gp.plane).expect("fewer than 2^32 planes");
                for (i, v) in gp.views.iter().enumerate() {
                    let index = gp.first + u32::try_from(i).expect("fewer than 2^32 views");
                    let view = ViewUniform::new(v.clip_from_rel.as_mat4(), &s.lighting, &s.mask, 0);
                    self.views.write_view(queue, first_view + index, &view);
                    glossy.write_sample(
                        queue,
                        index,
                        &sample_uniform(camera, aspect, &self.planes[gp.plane], slot, v),
                    );
                }
            }
        }
        self.glossy_plan = glossy_plan;
        self.camera = Some(*camera);
        self.summary = FrameSummary {
            size,
            planes: self.planes.len(),
            rendered_planes: rendered,
            bounce_views: self.bounce_plan.views.len(),
            bounce_views_skipped: self.bounce_plan.skipped,
            glossy_views: self.glossy_plan.view_count() as usize,
        };
        &self.summary
    }

    /// The first view slot of the glossy reference: after the main view, the planes and
    /// the room of the later bounces.
    fn first_glossy_slot(&self, bounces: u32) -> u32 {
        let planes = u32::try_from(self.planes.len()).expect("fewer than 2^32 planes");
        let bounce_room = if bounces > 1 {
            u32::try_from(self.settings.max_bounce_views).unwrap_or(u32::MAX / 2)
        } else {
            0
        };
        1 + planes + bounce_room
    }

    /// Room for the glossy reference's views and its sums, when the settings ask for it.
    fn allocate_glossy(&mut self, device: &wgpu::Device, size: [u32; 2], bounces: u32) {
        let samples = self.settings.glossy.samples;
        let rough =
            u32::try_from(rough_plane_count(&self.reflectors, &self.planes)).expect("fewer than 2^32 planes");
        if samples == 0 || rough == 0 {
            return;
        }
        let needed = rough * samples;
        let slots = self.first_glossy_slot(bounces) + needed;
        let shapes = self.reflectors.reflectors.len();
        if !self.views.fits(slots, shapes) {
            self.views = ViewBindings::new(device, &self.layouts, slots, shapes);
        }
        let frame = self.frame.as_mut().expect("allocated before the glossy reference");
        if frame.glossy.as_ref().is_none_or(|(g, _)| !g.fits(needed, shapes, size)) {
            let bindings =
                self.glossy_accumulate.bindings(device, &frame.main, &frame.reference.mirror, needed, shapes);
            let group = self.glossy_resolve.bind_group(device, &frame.main, &bindings);
            frame.glossy = Some((bindings, group));
        }
    }

    /// Room for the later bounces' views and their scratch targets, when the settings ask
    /// for more than one bounce.
    fn allocate_bounces(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, size: [u32; 2], bounces: u32) {
        if bounces <= 1 {
            return;
        }
        let planes = u32::try_from(self.planes.len()).expect("fewer than 2^32 planes");
        let views = u32::try_from(self.settings.max_bounce_views).unwrap_or(u32::MAX - 1 - planes);
        let slots = 1 + planes + views;
        let shapes = self.reflectors.reflectors.len();
        if !self.views.fits(slots, shapes) {
            self.views = ViewBindings::new(device, &self.layouts, slots, shapes);
        }
        if self.bounce_targets.as_ref().is_none_or(|t| !t.fits(size, bounces)) {
            let frame = self.frame.as_ref().expect("allocated before the bounces");
            self.bounce_targets = Some(self.bounce_pass.targets(
                device,
                queue,
                size,
                bounces,
                &frame.reference.mirror,
                frame.bindings.plane_of_reflector(),
                self.planes.len(),
            ));
        }
    }

    /// Records the main G-buffer pass of the prepared frame.
    ///
    /// # Panics
    /// If [`LevelRenderer::prepare`] was never called.
    pub fn encode_gbuffer(&self, encoder: &mut wgpu::CommandEncoder) {
        let (frame, camera) = self.prepared();
        let draw = GBufferDraw {
            targets: &frame.main,
            slot: 0,
            kind: ViewKind::Direct,
            depth: camera.projection.depth,
            background: self.settings.background,
        };
        self.gbuffer_pass.encode(encoder, &self.meshes, &self.views, &draw);
    }

    /// Records the exact reference of the prepared frame (after [`Self::encode_gbuffer`]):
    /// one mirrored G-buffer pass and one resolve per rendered plane.
    ///
    /// # Panics
    /// If [`LevelRenderer::prepare`] was never called.
    pub fn encode_reference(&self, encoder: &mut wgpu::CommandEncoder) {
        let (frame, camera) = self.prepared();
        if self.summary.rendered_planes.is_empty() {
            self.reference_pass.encode_clear(encoder, &frame.reference);
            return;
        }
        for (n, &k) in self.summary.rendered_planes.iter().enumerate() {
            let slot = u32::try_from(k).expect("fewer than 2^32 planes");
            let draw = GBufferDraw {
                targets: &frame.reference.mirror,
                slot: 1 + slot,
                kind: ViewKind::Mirrored,
                depth: camera.projection.depth,
                background: self.settings.background,
            };
            self.gbuffer_pass.encode(encoder, &self.meshes, &self.views, &draw);
            self.encode_bounces(encoder, BounceParent::Plane(k), &frame.reference.mirror);
            self.reference_pass.encode_resolve(encoder, &frame.reference, &frame.bindings, slot, n == 0);
        }
        self.encode_glossy(encoder);
    }

    /// Records the glossy reference's views, their accumulation and the resolve over the
    /// mirror reference (after it).
    fn encode_glossy(&self, encoder: &mut wgpu::CommandEncoder) {
        let (frame, camera) = self.prepared();
        let Some((glossy, resolve_group)) = &frame.glossy else { return };
        if self.glossy_plan.planes.is_empty() {
            return;
        }
        self.glossy_accumulate.encode_clear(encoder, glossy);
        let first_view = self.glossy_plan.first_view_slot;
        for gp in &self.glossy_plan.planes {
            for i in 0..gp.views.len() {
                let index = gp.first + u32::try_from(i).expect("fewer than 2^32 views");
                let draw = GBufferDraw {
                    targets: &frame.reference.mirror,
                    slot: first_view + index,
                    kind: ViewKind::Mirrored,
                    depth: camera.projection.depth,
                    background: self.settings.background,
                };
                self.gbuffer_pass.encode(encoder, &self.meshes, &self.views, &draw);
                self.glossy_accumulate.encode(encoder, glossy, index);
            }
        }
        self.glossy_resolve.encode(encoder, &frame.reference, resolve_group);
    }

    /// The effective sample size of the glossy reference of the last rendered frame (waits
    /// for the GPU); `None` when the frame had no glossy views.
    ///
    /// # Errors
    /// A readback error.
    pub fn glossy_stats(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Option<Result<GlossyStats, crate::TestbedError>> {
        let (glossy, _) = self.frame.as_ref()?.glossy.as_ref()?;
        (!self.glossy_plan.planes.is_empty()).then(|| glossy.read_stats(device, queue))
    }

    /// Records the later-bounce views seen in `parent` (drawn into `parent_target`),
    /// depth first: each view's own children are blended into it before it is blended
    /// into its parent.
    fn encode_bounces(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        parent: BounceParent,
        parent_target: &GBuffer,
    ) {
        let (Some(targets), Some(camera)) = (&self.bounce_targets, &self.camera) else { return };
        let first_slot = 1 + u32::try_from(self.planes.len()).expect("fewer than 2^32 planes");
        for (i, v) in self.bounce_plan.children(parent) {
            let target = &targets.scratch[(v.depth - 2) as usize];
            let draw = GBufferDraw {
                targets: target,
                slot: first_slot + u32::try_from(i).expect("fewer than 2^32 views"),
                kind: if v.depth % 2 == 0 { ViewKind::Direct } else { ViewKind::Mirrored },
                depth: camera.projection.depth,
                background: self.settings.background,
            };
            self.gbuffer_pass.encode(encoder, &self.meshes, &self.views, &draw);
            self.encode_bounces(encoder, BounceParent::View(i), target);
            let reflectivity = CompositeParams::default().reflectivity;
            self.bounce_pass.encode(encoder, targets, parent_target, v.depth, v.plane, reflectivity);
        }
    }

    /// Prepares, records and submits the G-buffer and the reference for `camera`.
    pub fn render(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        camera: &Camera,
        size: [u32; 2],
    ) -> FrameSummary {
        let summary = self.prepare(device, queue, camera, size).clone();
        let mut encoder = device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("level renderer frame") });
        self.encode_gbuffer(&mut encoder);
        self.encode_reference(&mut encoder);
        queue.submit([encoder.finish()]);
        summary
    }

    /// The main view's G-buffer of the prepared frame.
    ///
    /// # Panics
    /// If [`LevelRenderer::prepare`] was never called.
    pub fn gbuffer(&self) -> &GBuffer {
        &self.prepared().0.main
    }

    /// The reference outputs of the prepared frame.
    ///
    /// # Panics
    /// If [`LevelRenderer::prepare`] was never called.
    pub fn reference(&self) -> &ReferenceTargets {
        &self.prepared().0.reference
    }

    fn prepared(&self) -> (&FrameTargets, &Camera) {
        match (&self.frame, &self.camera) {
            (Some(f), Some(c)) => (f, c),
            _ => panic!("LevelRenderer::prepare must be called before encoding or reading targets"),
        }
    }
}
