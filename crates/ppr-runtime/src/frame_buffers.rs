//! The GPU buffers of a frame, sized for a viewport and a reflector set.

use std::cell::{Cell, RefCell};

use wgpu::util::DeviceExt;

use crate::gpu_types::{FrameUniforms, GpuGlossyShapes, GpuLayer, GpuShape, GpuShapeTest};
use crate::passes::BufferPart;
use crate::passes::block_lists::block_lists_size;
use crate::passes::super_tile_lists::super_lists_size;
use crate::passes::tile_classify::ACTIVE_TILES_HEADER;
use crate::plan::FramePlan;
use crate::plan::{MAX_LAYERS, UNIFORM_TESTS_CAPACITY};
use crate::plane_groups::plane_group_words_offset;
use crate::shapes::ShapeTable;
use crate::upload_layout::{UploadLayout, UploadTarget};
use crate::upload_ring::UploadRing;

/// Buffers reallocated only when the viewport or the set changes.
pub(crate) struct FrameBuffers {
    /// Every part of the frame upload (uniforms, shapes, lists, tests, plane groups), each
    /// a range of it ([`Self::parts`]), so that a frame fills them with one copy or a few.
    pub upload: wgpu::Buffer,
    pub upload_layout: UploadLayout,
    /// On devices with `MAPPABLE_PRIMARY_BUFFERS`: buffers laid out as [`Self::upload`]
    /// (the plane groups' static words in place), which an encode writes its parts into
    /// and binds instead of copying them into [`Self::upload`].
    pub bindable_uploads: Option<RefCell<UploadRing>>,
    pub occluders: wgpu::Buffer,
    /// Two intermediate buffers used by turns ([`Self::take_slot`]): a direct-dispatch
    /// reflection pass clears the one the next encode uses, which then needs no clear pass.
    pub intermediate: [wgpu::Buffer; 2],
    /// The classification's active-tile lists, one per slot as the intermediate buffer:
    /// the count, the indirect dispatch arguments (x, y, z, from byte 4) and the tile
    /// indices. An indirect frame's classification zeroes the other slot's count and
    /// arguments for the next encode ([`Self::take_counters`]).
    pub active_tiles: [wgpu::Buffer; 2],
    pub tile_flags: wgpu::Buffer,
    pub debug_writes: wgpu::Buffer,
    /// 16 bytes no pass reads or writes: bound where a layout asks for a writable buffer
    /// that the frame's pipeline leaves alone (the indirect reflection's next-slot
    /// bindings), so that wgpu puts no barrier before that dispatch for a buffer an earlier
    /// one wrote.
    pub placeholder: wgpu::Buffer,
    /// Atlas of the layer reflectors' regions (grown on demand), one per slot as the
    /// intermediate buffer.
    pub atlas: [wgpu::Buffer; 2],
    /// Super-tile counts and lists (full size only once a plan uses super-tiles).
    pub super_lists: wgpu::Buffer,
    /// Block counts and lists (full size only once a plan uses tile culling).
    pub block_lists: wgpu::Buffer,
    viewport: [u32; 2],
    shape_count: usize,
    debug: bool,
    /// The slot the next encode takes.
    next_slot: Cell<usize>,
    /// Per slot: whether its intermediate buffer and atlas hold the clear value everywhere
    /// (a reflection pass cleared them after their last use).
    clean: Cell<[bool; 2]>,
    /// Per slot: whether its active-tile count and dispatch arguments are zero (an indirect
    /// frame's classification zeroed them after their last use).
    counters_clean: Cell<[bool; 2]>,
}

impl FrameBuffers {
    /// Buffers that serve every plan of `plans` (views of one viewport: a mono frame's one
    /// plan, or a stereo frame's two).
    pub fn new(device: &wgpu::Device, table: &ShapeTable, plans: &[&FramePlan], debug: bool) -> Self {
        let plan = plans[0];
        debug_assert!(plans.iter().all(|p| p.viewport == plan.viewport), "one viewport per frame");
        let layer_pixels = plans.iter().map(|p| p.layer_pixels).max().unwrap_or(0);
        let super_tiles = plans.iter().any(|p| p.super_tiles);
        // The block lists live in memory only when their own pass builds them.
        let tile_culling = plans.iter().any(|p| p.tile_culling && !p.fused_lists);
        let [w, h] = plan.viewport;
        let storage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
        let readable = storage | wgpu::BufferUsages::COPY_SRC;
        let buffer = |label: &str, size: u64, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16),
                usage,
                mapped_at_creation: false,
            })
        };
        let pixels = u64::from(w) * u64::from(h);
        let n = table.shapes.len() as u64;
        let occluders =
            if table.occluder_indices.is_empty() { vec![0u32; 4] } else { table.occluder_indices.clone() };
        let group_words = plane_groups_words(table);
        let upload_layout = UploadLayout::new(
            |target| match target {
                UploadTarget::Uniforms => std::mem::size_of::<FrameUniforms>() as u64,
                UploadTarget::Glossy => std::mem::size_of::<GpuGlossyShapes>() as u64,
                UploadTarget::Layers => (MAX_LAYERS * std::mem::size_of::<GpuLayer>()) as u64,
                UploadTarget::Shapes => n * std::mem::size_of::<GpuShape>() as u64,
                UploadTarget::Visible => 4 * n,
                UploadTarget::ScreenRects | UploadTarget::SourceRects => 16 * n,
                // The loop's tests (entries and layers), then the parallel trees' members:
                // each shape at most once, plus one entry per tree.
                UploadTarget::Tests => 2 * n * std::mem::size_of::<GpuShapeTest>() as u64,
                UploadTarget::PlaneGroups => 4 * group_words.len() as u64,
            },
            {
                let limits = device.limits();
                u64::from(
                    limits
                        .min_storage_buffer_offset_alignment
                        .max(limits.min_uniform_buffer_offset_alignment),
                )
            },
            (UNIFORM_TESTS_CAPACITY * std::mem::size_of::<GpuShapeTest>()) as u64,
        );
        let bindable_uploads =
            device.features().contains(wgpu::Features::MAPPABLE_PRIMARY_BUFFERS).then(|| {
                let fixed = (
                    upload_layout.range(UploadTarget::PlaneGroups).start,
                    bytemuck::cast_slice(&group_words).to_vec(),
                );
                RefCell::new(UploadRing::bindable(device, upload_layout.size(), fixed))
            });
        Self {
            upload: upload_buffer(device, &group_words, &upload_layout),
            upload_layout,
            bindable_uploads,
            occluders: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("ppr occluder lists"),
                contents: bytemuck::cast_slice(&occluders),
                usage: storage,
            }),
            intermediate: ["ppr intermediate buffer 0", "ppr intermediate buffer 1"]
                .map(|label| buffer(label, (pixels * 4).next_multiple_of(16), readable)),
            active_tiles: ["ppr active tiles 0", "ppr active tiles 1"].map(|label| {
                let size = ACTIVE_TILES_HEADER + 4 * u64::from(plan.tile_count());
                buffer(label, size, readable | wgpu::BufferUsages::INDIRECT)
            }),
            tile_flags: buffer("ppr tile flags", 4 * u64::from(plan.tile_count()), storage),
            debug_writes: buffer("ppr debug writes", if debug { pixels * 4 } else { 16 }, readable),
            placeholder: buffer("ppr placeholder", 16, storage),
            atlas: ["ppr layer atlas 0", "ppr layer atlas 1"]
                .map(|label| buffer(label, 4 * atlas_capacity(layer_pixels, pixels), readable)),
            super_lists: buffer(
                "ppr super-tile lists",
                if super_tiles { super_lists_size(plan.viewport) } else { 16 },
                readable,
            ),
            block_lists: buffer(
                "ppr block lists",
                if tile_culling { block_lists_size(plan.viewport) } else { 16 },
                readable,
            ),
            viewport: plan.viewport,
            shape_count: table.shapes.len(),
            debug,
            next_slot: Cell::new(0),
            clean: Cell::new([false; 2]),
            counters_clean: Cell::new([false; 2]),
        }
    }

    /// The upload's parts in `upload`: [`Self::upload`], or a buffer of
    /// [`Self::bindable_uploads`].
    pub fn parts<'a>(&'a self, upload: &'a wgpu::Buffer) -> UploadParts<'a> {
        UploadParts { buffer: upload, layout: &self.upload_layout }
    }

    /// The slot (of [`Self::intermediate`] and [`Self::atlas`]) an encode uses, and whether
    /// its buffers are clean; the next call returns the other slot. The slot is dirty from
    /// here on (the encode's projection writes it).
    ///
    /// The slots' states follow the encodes, so the command buffers must reach the GPU in
    /// the order they were encoded (as `ReflectionRenderer::encode` requires).
    pub fn take_slot(&self) -> (usize, bool) {
        let slot = self.next_slot.get();
        self.next_slot.set(1 - slot);
        let mut clean = self.clean.get();
        let was_clean = clean[slot];
        clean[slot] = false;
        self.clean.set(clean);
        (slot, was_clean)
    }

    /// Marks `slot`'s buffers clean: a pass recorded after the last use of them cleared
    /// them whole.
    pub fn mark_clean(&self, slot: usize) {
        let mut clean = self.clean.get();
        clean[slot] = true;
        self.clean.set(clean);
    }

    /// Marks both slots dirty (their next encodes clear them in the clear pass, and their
    /// counts before the classification).
    pub fn forget_clean(&self) {
        self.clean.set([false; 2]);
        self.counters_clean.set([false; 2]);
    }

    /// Whether `slot`'s active-tile count and dispatch arguments are zero, for an encode
    /// whose classification appends to them (dirty from here on).
    pub fn take_counters(&self, slot: usize) -> bool {
        let mut clean = self.counters_clean.get();
        let was_clean = clean[slot];
        clean[slot] = false;
        self.counters_clean.set(clean);
        was_clean
    }

    /// Marks `slot`'s active-tile count and dispatch arguments zero: a classification
    /// recorded after their last use zeroed them.
    pub fn mark_counters_clean(&self, slot: usize) {
        let mut clean = self.counters_clean.get();
        clean[slot] = true;
        self.counters_clean.set(clean);
    }

    /// The slot the last [`Self::take_slot`] returned.
    pub fn last_slot(&self) -> usize {
        1 - self.next_slot.get()
    }

    /// Whether these buffers serve `plan` over `table`.
    pub fn fits(&self, table: &ShapeTable, plan: &FramePlan, debug: bool) -> bool {
        self.viewport == plan.viewport
            && self.shape_count == table.shapes.len()
            && self.debug == debug
            && self.atlas[0].size() >= 4 * u64::from(plan.layer_pixels)
            && (!plan.super_tiles || self.super_lists.size() >= super_lists_size(plan.viewport))
            && (!plan.tile_culling
                || plan.fused_lists
                || self.block_lists.size() >= block_lists_size(plan.viewport))
    }
}

/// The frame upload's parts as one encode binds them: ranges of the buffer its upload is
/// in, laid out by the frame buffers' [`UploadLayout`].
#[derive(Clone, Copy)]
pub(crate) struct UploadParts<'a> {
    buffer: &'a wgpu::Buffer,
    layout: &'a UploadLayout,
}

impl<'a> UploadParts<'a> {
    /// `target`'s range, to bind.
    pub fn part(&self, target: UploadTarget) -> BufferPart<'a> {
        self.range_of(self.layout.range(target))
    }

    /// The loop's tests as a uniform array: the first bytes of the tests' part.
    pub fn uniform_tests(&self) -> BufferPart<'a> {
        self.range_of(self.layout.uniform_tests())
    }

    fn range_of(&self, range: std::ops::Range<u64>) -> BufferPart<'a> {
        BufferPart {
            buffer: self.buffer,
            offset: range.start,
            size: wgpu::BufferSize::new(range.end - range.start),
        }
    }
}

/// Atlas values to allocate for `layer_pixels` in a viewport of `pixels`: whole eighths of
/// the viewport (at least 1 024 values), so that a layer growing on screen frame by frame
/// re-creates the buffers a few times, not at every frame.
fn atlas_capacity(layer_pixels: u32, pixels: u64) -> u64 {
    if layer_pixels == 0 {
        return 4;
    }
    u64::from(layer_pixels).next_multiple_of((pixels / 8).max(1024).next_multiple_of(4))
}

/// The plane groups' part as a new frame buffer holds it: room for every group's header
/// (zeros until a frame writes them), then the static words, in whole vec4s (the projection
/// also reads it as `array<vec4<u32>>`).
fn plane_groups_words(table: &ShapeTable) -> Vec<u32> {
    let mut words = vec![0u32; plane_group_words_offset(table) as usize];
    words.extend(&table.plane_groups.words);
    words.resize(words.len().max(4).next_multiple_of(4), 0);
    words
}

/// The upload buffer, zero but for the plane groups' static words (which stay: no copy
/// reaches them, the frames write the headers before them).
fn upload_buffer(device: &wgpu::Device, group_words: &[u32], layout: &UploadLayout) -> wgpu::Buffer {
    let mut bytes = vec![0u8; layout.size() as usize];
    let groups = layout.range(UploadTarget::PlaneGroups).start as usize;
    let words: &[u8] = bytemuck::cast_slice(group_words);
    bytes[groups..groups + words.len()].copy_from_slice(words);
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("ppr frame upload parts"),
        contents: &bytes,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
    })
}
