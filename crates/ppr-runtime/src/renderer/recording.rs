//! `ReflectionRenderer::encode_view`: one prepared view's upload copies and compute passes,
//! recorded as its `PassLayout` lays them out.

use super::{FrameInputs, PreparedView, ReflectionRenderer};
use crate::frame_buffers::{FrameBuffers, UploadParts};
use crate::frame_upload::MAX_COPY_GAP;
use crate::pass_layout::PassLayout;
use crate::passes::block_lists::BlockListBindings;
use crate::passes::clear::ClearBindings;
use crate::passes::downsample::DownsampleBindings;
use crate::passes::layer_reflection::{LayerBindings, LayerGroups, LayerPlacement};
use crate::passes::projection::ProjectionBindings;
use crate::passes::reflection::{ReflectionBindings, ReflectionVariant};
use crate::passes::super_tile_lists::SuperTileBindings;
use crate::passes::tile_classify::{ACTIVE_TILES_HEADER, ClassifyBindings};
use crate::passes::upsample::{UpsampleBindings, UpsampleProbe, UpsampleVariant};
use crate::plan::FramePlan;
use crate::reduced_targets::ReducedTargets;
use crate::timestamps::{
    CLASSIFY, CLEAR, DOWNSAMPLE, LAYERS, PROJECTION, PROJECTION_REFLECTION, PassTimer, REFLECTION, UPSAMPLE,
};
use crate::upload_layout::UploadTarget;

/// What one encode records with: the renderer's passes, the view's plan, buffers and
/// textures, its layout, and the bind groups of the dispatches that go into more than one
/// place by the layout.
struct FrameRecorder<'a> {
    r: &'a ReflectionRenderer,
    plan: &'a FramePlan,
    b: &'a FrameBuffers,
    /// The upload's parts where this encode's passes read them.
    parts: UploadParts<'a>,
    layout: PassLayout,
    /// Each pass's own timestamps (not while the bench times the frame's span).
    timer: Option<&'a PassTimer>,
    /// This encode's slot of the intermediate buffer and atlas.
    slot: usize,
    /// The depth the passes read (the reduced tier's own when it runs).
    depth: &'a wgpu::TextureView,
    classify: Option<wgpu::BindGroup>,
    layers: Option<wgpu::BindGroup>,
    reflection: Option<(wgpu::BindGroup, ReflectionVariant)>,
}

impl<'a> FrameRecorder<'a> {
    fn intermediate(&self) -> &'a wgpu::Buffer {
        &self.b.intermediate[self.slot]
    }

    fn atlas(&self) -> &'a wgpu::Buffer {
        &self.b.atlas[self.slot]
    }

    fn count(&self, n: u32) {
        self.r.dispatches.set(self.r.dispatches.get() + n);
    }

    /// A compute pass with timed pass `index`'s timestamps (none while the span is timed).
    fn begin<'e>(
        &self,
        encoder: &'e mut wgpu::CommandEncoder,
        label: &str,
        index: u32,
    ) -> wgpu::ComputePass<'e> {
        encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(label),
            timestamp_writes: self.timer.map(|t| t.writes(index)),
        })
    }

    fn record_classify(&self, pass: &mut wgpu::ComputePass<'_>) {
        let Some(bg) = &self.classify else { return };
        self.r.classify.encode(pass, bg, self.plan.viewport, !self.plan.layers.is_empty());
        // It clears the other slot whole for the next encode (unless the bench asks for a
        // clear pass every frame), and zeroes its active-tile count and arguments.
        if !self.r.debug.clear_pass_every_frame {
            self.b.mark_clean(1 - self.slot);
        }
        self.b.mark_counters_clean(1 - self.slot);
        self.count(1);
    }

    fn record_layers(&self, pass: &mut wgpu::ComputePass<'_>) {
        let Some(bg) = &self.layers else { return };
        // The reduced tiers (and the bench's `layer_every_tile`) shade every tile of the
        // layers' common rectangle (PPR_FLAG_LAYER_EVERY_TILE), the others only the tiles
        // their layers' own rectangles meet.
        let groups = if self.layout.reduced || self.r.debug.layer_every_tile {
            let rect = self.plan.layer_rect;
            LayerGroups::EveryTile([rect.max[0] - rect.min[0], rect.max[1] - rect.min[1]])
        } else {
            LayerGroups::LayerTiles(self.plan.layer_tiles())
        };
        self.r.layer_reflection.encode(pass, bg, groups, self.r.debug.full_stretch_walk);
        self.count(1);
    }

    /// The reflection, with the layers before or after it where they go with it.
    fn record_reflection(&self, pass: &mut wgpu::ComputePass<'_>) {
        let Some((bg, variant)) = &self.reflection else { return };
        let placement = self.r.debug.layer_placement;
        let layers_here = self.layout.layers_with_reflection;
        if layers_here && placement == LayerPlacement::BeforeReflection {
            self.record_layers(pass);
        }
        if self.plan.indirect {
            let tiles = &self.b.active_tiles[self.slot];
            self.r.reflection.encode_tiles(pass, bg, tiles, self.plan.tile_count(), *variant);
        } else {
            self.r.reflection.encode(pass, bg, self.plan.viewport, *variant);
        }
        if variant.clears_next(self.plan.indirect) {
            self.b.mark_clean(1 - self.slot);
        }
        self.count(1);
        if layers_here && placement == LayerPlacement::AfterReflection {
            self.record_layers(pass);
        }
    }

    /// The clear pass: the intermediate buffer and the atlas, as the layout says.
    fn record_clear(&self, encoder: &mut wgpu::CommandEncoder) {
        let device = &self.r.device;
        let bindings = |intermediate| ClearBindings { intermediate };
        let mut pass = self.begin(encoder, "ppr clear", CLEAR);
        if self.layout.clear_main {
            let bg = self.r.clear.bind_group(device, &bindings(self.intermediate()));
            self.r.clear.encode_all(&mut pass, &bg, (self.intermediate().size() / 16) as u32);
            self.count(1);
        }
        if self.layout.clear_atlas {
            let bg = self.r.clear.bind_group(device, &bindings(self.atlas()));
            self.r.clear.encode_all(&mut pass, &bg, self.plan.layer_pixels.div_ceil(4));
            self.count(1);
        }
    }

    /// The projection's compute pass: the classification and the lists before it where
    /// they go there, the reflection after it where it goes there.
    fn record_projection_pass(&self, encoder: &mut wgpu::CommandEncoder) {
        let (r, b, plan, depth, parts) = (self.r, self.b, self.plan, self.depth, self.parts);
        let bg = r.projection.bind_group(
            &r.device,
            &ProjectionBindings {
                uniforms: parts.part(UploadTarget::Uniforms),
                depth,
                shapes: parts.part(UploadTarget::Shapes),
                tests: parts.part(UploadTarget::Tests),
                occluders: &b.occluders,
                intermediate: self.intermediate(),
                debug_writes: &b.debug_writes,
                layers: parts.part(UploadTarget::Layers),
                atlas: self.atlas(),
                super_lists: &b.super_lists,
                source_boxes: parts.part(UploadTarget::SourceRects),
                block_lists: &b.block_lists,
                uniform_tests: parts.uniform_tests(),
                plane_groups: parts.part(UploadTarget::PlaneGroups),
            },
        );
        let with_reflection = self.layout.reflection_with_projection;
        let index = if with_reflection { PROJECTION_REFLECTION } else { PROJECTION };
        let mut pass = self.begin(encoder, "ppr projection", index);
        if self.layout.classify_with_projection {
            self.record_classify(&mut pass);
        }
        let source_boxes = !plan.source_rects.is_empty();
        if plan.super_tiles {
            // In the projection's compute pass: its timestamps cover the lists too, and the
            // next dispatches see this one's writes.
            let lists = r.super_tile_lists.bind_group(
                &r.device,
                &SuperTileBindings {
                    uniforms: parts.part(UploadTarget::Uniforms),
                    depth,
                    tests: parts.part(UploadTarget::Tests),
                    source_boxes: parts.part(UploadTarget::SourceRects),
                    super_lists: &b.super_lists,
                },
            );
            r.super_tile_lists.encode(&mut pass, &lists, plan.viewport, source_boxes);
            self.count(1);
        }
        if plan.tile_culling && !plan.fused_lists {
            let lists = r.block_lists.bind_group(
                &r.device,
                &BlockListBindings {
                    uniforms: parts.part(UploadTarget::Uniforms),
                    depth,
                    tests: parts.part(UploadTarget::Tests),
                    source_boxes: parts.part(UploadTarget::SourceRects),
                    super_lists: &b.super_lists,
                    block_lists: &b.block_lists,
                },
            );
            let choices = (source_boxes, plan.super_tiles);
            r.block_lists.encode(&mut pass, &lists, plan.viewport, choices, r.debug.block_lists_box_only);
            self.count(1);
        }
        r.projection.encode(&mut pass, &bg, plan.viewport, r.variant(plan));
        self.count(1);
        if with_reflection {
            self.record_reflection(&mut pass);
        }
    }
}

impl ReflectionRenderer {
    /// Records one prepared view's passes (its upload's copies first).
    pub(crate) fn encode_view(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        view: &PreparedView,
        inputs: &FrameInputs<'_>,
    ) {
        let plan = &view.plan;
        // What the frame says about a layer output: one given says "wanted"; none given
        // while the plan has layers says "nowhere to go"; none given without layers (a
        // renderer that passes one only when the plan has layers) says nothing.
        match (inputs.layer_output.is_some(), plan.layers.is_empty()) {
            (true, _) => self.layer_output_given.set(Some(true)),
            (false, false) => self.layer_output_given.set(Some(false)),
            (false, true) => {}
        }
        if plan.is_empty() {
            self.recorded.set(Default::default());
            self.upload_copies.set(0);
            return;
        }
        let device = &self.device;
        let b = self.buffers.as_ref().expect("prepare() allocates the buffers");
        // This encode's slot of the intermediate buffer and atlas, and whether the last
        // encode's reflection pass left them cleared.
        let (slot, clean) = b.take_slot();
        let (intermediate, atlas) = (&b.intermediate[slot], &b.atlas[slot]);
        // A reduced tier runs the passes on its own reduced depth and outputs (normal maps
        // off); the reflection reads the full-size colour.
        let reduced = if view.reduced_active { self.reduced.as_ref() } else { None };
        let layout =
            PassLayout::new(plan, &self.debug, clean, inputs.layer_output.is_some(), reduced.is_some());
        // The frame's span (bench), or each pass's own timestamps.
        let span = self.debug.frame_span;
        let span_timer = self.timer.as_ref().filter(|_| span && PassTimer::spans(device));
        let depth = reduced.map_or(inputs.depth, |r| &r.depth.view);
        let color = inputs.color;
        let output = reduced.map_or(inputs.output, |r| &r.output.view);
        let layer_output = inputs.layer_output.map(|o| reduced.map_or(o, |r| &r.layer_output.view));
        let normals = if reduced.is_some() { None } else { inputs.normals };
        // This prepared frame's uniforms, shapes and lists: on a device that maps bindable
        // buffers, written here into one that the passes bind (no copy, no barrier behind
        // one); elsewhere copied into the upload buffer below, after the span's start.
        let upload = view.upload.as_ref().expect("prepare() builds the upload");
        let bound_upload = b.bindable_uploads.is_some() && !self.debug.copied_upload;
        let upload_buffer = if bound_upload { upload.stage_bindable(encoder, b) } else { b.upload.clone() };
        let parts = b.parts(&upload_buffer);

        let classify = layout.classify.then(|| {
            self.classify.bind_group(
                device,
                &ClassifyBindings {
                    uniforms: parts.part(UploadTarget::Uniforms),
                    depth,
                    shapes: parts.part(UploadTarget::Shapes),
                    visible: parts.part(UploadTarget::Visible),
                    screen_rects: parts.part(UploadTarget::ScreenRects),
                    active_tiles: &b.active_tiles[slot],
                    next_active_tiles: &b.active_tiles[1 - slot],
                    tile_flags: &b.tile_flags,
                    layers: parts.part(UploadTarget::Layers),
                    next_intermediate: &b.intermediate[1 - slot],
                    next_atlas: &b.atlas[1 - slot],
                },
            )
        });
        let layers = layer_output.filter(|_| layout.layers).map(|layer_output| {
            self.layer_reflection.bind_group(
                device,
                &LayerBindings {
                    uniforms: parts.part(UploadTarget::Uniforms),
                    atlas,
                    layers: parts.part(UploadTarget::Layers),
                    shapes: parts.part(UploadTarget::Shapes),
                    depth,
                    color,
                    output: layer_output,
                    intermediate,
                    active_tiles: &b.active_tiles[slot],
                },
            )
        });
        let reflection = layout.has_main.then(|| {
            let bg = self.reflection.bind_group(
                device,
                &ReflectionBindings {
                    uniforms: parts.part(UploadTarget::Uniforms),
                    intermediate,
                    color,
                    output,
                    active_tiles: &b.active_tiles[slot],
                    depth,
                    normals: normals.unwrap_or(color),
                    glossy: parts.part(UploadTarget::Glossy),
                    // Indirect frames' reflection clears nothing (their classification
                    // cleared the other slot, which this dispatch then must not bind as
                    // writable: a buffer written by one dispatch and bound writable by the
                    // next gets a barrier between them, here between the layers and the
                    // reflection).
                    next_intermediate: if plan.indirect { &b.placeholder } else { &b.intermediate[1 - slot] },
                    next_atlas: if plan.indirect { &b.placeholder } else { &b.atlas[1 - slot] },
                    upload_storage: parts.part(UploadTarget::Shapes),
                },
            );
            let variant = self.reflection_variant(
                plan.normal_maps && normals.is_some(),
                self.settings.glossy && !plan.glossy.is_empty(),
            );
            (bg, variant)
        });
        let frame = FrameRecorder {
            r: self,
            plan,
            b,
            parts,
            layout,
            timer: self.timer.as_ref().filter(|_| !span),
            slot,
            depth,
            classify,
            layers,
            reflection,
        };

        // The frame's span begins before its copies: everything this encode records.
        if let Some(t) = span_timer {
            t.write_span(encoder, false);
        }
        // Copied in here (not at the submit), so that each encode runs with the camera it
        // was prepared for.
        let copies = if bound_upload {
            0
        } else {
            let max_gap = (!self.debug.separate_upload_copies).then_some(MAX_COPY_GAP);
            upload.encode_copies(encoder, b, &mut self.upload_ring.borrow_mut(), max_gap)
        };
        self.upload_copies.set(copies);
        if let Some(r) = reduced {
            let bg = self.downsample.bind_group(
                device,
                &DownsampleBindings {
                    uniforms: parts.part(UploadTarget::Uniforms),
                    full_depth: inputs.depth,
                    reduced_depth: &r.depth.view,
                },
            );
            let mut pass = frame.begin(encoder, "ppr downsample", DOWNSAMPLE);
            self.downsample.encode(&mut pass, &bg, plan.viewport);
            frame.count(1);
        }
        if layout.classify {
            // The classification counts the active tiles and raises the dispatch arguments
            // from zero, at every encode: zeroed by the last classification (which zeroes
            // the other slot's), else here.
            if !b.take_counters(slot) || self.debug.clear_pass_every_frame {
                encoder.clear_buffer(&b.active_tiles[slot], 0, Some(ACTIVE_TILES_HEADER));
            }
            if !layout.classify_with_projection {
                let mut pass = frame.begin(encoder, "ppr tile classify", CLASSIFY);
                frame.record_classify(&mut pass);
            }
        }
        if layout.clears() {
            frame.record_clear(encoder);
        }
        frame.record_projection_pass(encoder);
        if layout.has_main && !layout.reflection_with_projection {
            let mut pass = frame.begin(encoder, "ppr reflection", REFLECTION);
            frame.record_reflection(&mut pass);
        }
        if layout.layers_own_pass() {
            let mut pass = frame.begin(encoder, "ppr layer reflection", LAYERS);
            frame.record_layers(&mut pass);
        }
        if let Some(r) = reduced {
            self.encode_upsample(encoder, view, inputs, r, parts, frame.timer.map(|t| t.writes(UPSAMPLE)));
            frame.count(u32::from(layout.has_main) + u32::from(layout.layers));
        }
        if let Some(t) = span_timer {
            t.write_span(encoder, true);
        }
        if let Some(t) = &self.timer {
            t.resolve(encoder);
        }
        self.recorded.set(layout.recorded(span, span_timer.is_some()));
    }

    /// The reduced tiers' last pass: the reduced reflection (and layer reflection) to the
    /// full-size outputs.
    fn encode_upsample(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        view: &PreparedView,
        inputs: &FrameInputs<'_>,
        r: &ReducedTargets,
        parts: UploadParts<'_>,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let b = self.buffers.as_ref().expect("prepare() allocates the buffers");
        let plan = &view.plan;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("ppr upsample"),
            timestamp_writes,
        });
        let bindings = |reduced_output, output| UpsampleBindings {
            uniforms: parts.part(UploadTarget::Uniforms),
            full_depth: inputs.depth,
            reduced_depth: &r.depth.view,
            reduced_output,
            output,
            tile_flags: &b.tile_flags,
        };
        let variant = UpsampleVariant { shared: self.debug.shared_upsample, ..UpsampleVariant::default() };
        if !plan.visible.is_empty() {
            let bg = self.upsample.bind_group(&self.device, &bindings(&r.output.view, inputs.output));
            let variant = UpsampleVariant { indirect: plan.indirect, ..variant };
            self.upsample.encode(&mut pass, &bg, view.full_viewport, variant, self.debug.upsample_probe);
        }
        if let (false, Some(layer_output)) = (plan.layers.is_empty(), inputs.layer_output) {
            let bg = self.upsample.bind_group(&self.device, &bindings(&r.layer_output.view, layer_output));
            // The layer rectangle at full size, and a pixel of margin each side.
            let rect = plan.layer_rect;
            let pixels = [0, 1].map(|a| {
                let scale = f64::from(view.full_viewport[a]) / f64::from(plan.viewport[a]);
                (f64::from(rect.max[a] - rect.min[a]) * scale).ceil() as u32 + 2
            });
            let layers = UpsampleVariant { layers: true, ..variant };
            self.upsample.encode(&mut pass, &bg, pixels, layers, UpsampleProbe::None);
        }
    }
}
