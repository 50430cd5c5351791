//! Projection pass: mirror every pixel against the candidate reflectors and `atomicMin`
//! the encoded offset into the intermediate buffer. Shader variants are pipelines built
//! on first use from the WGSL's override constants.

use super::bind_group_cache::BindGroupCache;
use std::collections::HashMap;

use super::{
    BufferPart, buffer_entry, compute_pipeline, flag, loaded_texture_entry, storage_entry, uniform_entry,
};

pub const WGSL: &str = include_str!("../../shaders/projection.wgsl");

/// Edge of the pixel block one workgroup projects (`BLOCK_SIZE` of `tile_test.wgsl`):
/// 16 × 16 threads, four pixels each.
pub const BLOCK: u32 = 32;

/// Workgroups of the projection (and of the block-list pass) over a viewport.
pub fn block_groups([w, h]: [u32; 2]) -> (u32, u32) {
    (w.div_ceil(BLOCK), h.div_ceil(BLOCK))
}

/// Whether `device` has subgroup operations (the projection's subgroup culling uses them).
pub fn has_subgroups(device: &wgpu::Device) -> bool {
    device.features().contains(wgpu::Features::SUBGROUP)
}

/// Which projection shader runs (the WGSL's override constants).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct ProjectionVariant {
    /// Per-block shape lists ([`super::BlockListPass`], dispatched first).
    pub tile_culling: bool,
    /// With `tile_culling`: a block whose list overflowed takes its super-tile's list
    /// ([`super::SuperTileListPass`]) instead of every visible shape.
    pub super_tiles: bool,
    /// With `tile_culling`: the projection builds its block's list itself (in workgroup
    /// memory; [`crate::PlanParams::fused_lists`]) and no block-list pass runs before it.
    pub fused_lists: bool,
    /// Only the nearest of parallel shapes reflects a pixel.
    pub parallel_rule: bool,
    /// The seed's occluder tests (lists of occluding reflectors).
    pub occluder_tests: bool,
    /// A passing member's write first tests its path blocker (`crate::path_blockers`).
    pub path_blockers: bool,
    /// Occlusion against the depth buffer at each write's target.
    pub depth_occlusion: bool,
    /// Glass and water layers exist this frame.
    pub layers: bool,
    /// Record per source pixel which visible shapes it wrote for.
    pub debug_writes: bool,
    /// Record per pixel its block's candidate-list length instead (needs `debug_writes`).
    pub debug_tile_lists: bool,
    /// Blocks skip shapes whose source box ([`crate::FramePlan::source_rects`]) they miss.
    pub source_boxes: bool,
    /// The shape tests come from the uniform copy (binding 12), not the storage buffer.
    pub uniform_tests: bool,
    /// Some test stands for a parallel tree (`crate::parallel_trees`): its pixels walk it.
    pub parallel_trees: bool,
    /// Each subgroup visits only the candidates whose box test passes against the box of
    /// its pixels' positions (`subgroup_cull.wgsl`; on a device without
    /// [`wgpu::Features::SUBGROUP`] each invocation alone: the same writes, slower).
    pub subgroup_cull: bool,
    /// Bench only: a thread's four pixels one in each 16 × 16 quarter of the block (the
    /// layout before the compact one, whose subgroups cover 32 × 4 pixels). Frames that
    /// walk parallel trees take it anyway ([`Self::spread_quads`]).
    pub spread_quads: bool,
    /// A write tests the depth occlusion at its target before its encoding rather than
    /// after (the same buffer; [`crate::PlanParams::occlusion_first`]).
    pub occlusion_first: bool,
    /// Bench only (the same image): the block lists built in the projection flag no entry
    /// as lying wholly inside its shape's pyramid, so every pixel runs the side
    /// tests (`INSIDE_ENTRY` of `tile_test.wgsl`).
    pub no_inside_entries: bool,
    /// Bench only (the same lists): how the fused lists reduce the box of the block's
    /// positions (`SUBGROUP_BOX` of `fused_lists.wgsl`).
    pub box_reduction: BoxReduction,
    /// Bench only (the same lists): the fused lists load their first chunk's candidates
    /// and shape tests before the box reduction's barriers (`LIST_PREFETCH`).
    pub list_prefetch: bool,
    /// Bench only (the same image): KiB of workgroup memory no frame uses, added so that
    /// fewer workgroups fit on a multiprocessor at once: what the pass's time owes to its
    /// occupancy (`occupancy_pad.wgsl`). Clamped to what the device allows beside the
    /// pass's own.
    pub occupancy_pad_kib: u32,
    /// Leave parts out to time the rest (bench only; never a correct image).
    pub ablation: Ablation,
}

impl ProjectionVariant {
    /// Whether a thread's four pixels lie in the four quarters of the block rather than
    /// in two nearby rows: asked for, or walking parallel trees without subgroup culling
    /// (on the H200 the 10 000-tread stairway's walk took 2.65 ms in the compact layout
    /// against 2.36 spread; every other frame is as fast or faster compact,
    /// docs/perf/runtime.md).
    pub fn spread_quads(&self) -> bool {
        self.spread_quads || (self.parallel_trees && !self.subgroup_cull)
    }
}

/// How the block lists the projection builds reduce the box of the block's positions
/// (bench only: every choice gives the same box and lists).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum BoxReduction {
    /// Every invocation in the workgroup's atomics (eight copies of each bound), four
    /// barriers.
    #[default]
    Atomics,
    /// Each subgroup's box first, then one invocation a subgroup in the atomics. On a
    /// device without [`wgpu::Features::SUBGROUP`] every invocation takes part, as with
    /// [`Self::Atomics`].
    SubgroupAtomics,
    /// Each subgroup's box into a slot of workgroup memory, then every subgroup reduces
    /// the slots: one barrier, no atomics. Needs subgroups at least 8 wide
    /// ([`wgpu::AdapterInfo::subgroup_min_size`]); elsewhere [`Self::SubgroupAtomics`].
    SubgroupSlots,
}

/// What an ablated projection leaves out (bench only: `ppr-bench runtime
/// --projection-profile` times each to show where the pass's time goes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Ablation {
    /// The real pass.
    #[default]
    None,
    /// Returns at once: the launch.
    Empty,
    /// Reads depth and reconstructs positions only.
    PositionOnly,
    /// Also runs each shape's tests, but projects and writes nothing.
    TestsOnly,
    /// Projects and writes, with a value that needs no encoding.
    NoEncode,
    /// Projects and encodes, but does not write.
    NoWrite,
    /// Everything but the `atomicMin`: the plain load, the encoding and the occlusion test
    /// run (with nothing written, no write loses at the load), the atomic does not.
    NoAtomic,
}

impl Ablation {
    fn code(self) -> f64 {
        match self {
            Self::None => 0.0,
            Self::Empty => 1.0,
            Self::PositionOnly => 2.0,
            Self::TestsOnly => 3.0,
            Self::NoEncode => 4.0,
            Self::NoWrite => 5.0,
            Self::NoAtomic => 6.0,
        }
    }
}

/// Buffers and views the projection pass reads and writes.
pub struct ProjectionBindings<'a> {
    pub uniforms: BufferPart<'a>,
    pub depth: &'a wgpu::TextureView,
    pub shapes: BufferPart<'a>,
    /// Per projection test (visible shape or merged plane group), then per layer: its test planes (`ShapeTest` of
    /// `tile_test.wgsl`).
    pub tests: BufferPart<'a>,
    pub occluders: &'a wgpu::Buffer,
    pub intermediate: &'a wgpu::Buffer,
    pub debug_writes: &'a wgpu::Buffer,
    pub layers: BufferPart<'a>,
    pub atlas: &'a wgpu::Buffer,
    /// Super-tile counts and lists (read with `super_tiles`; any buffer otherwise).
    pub super_lists: &'a wgpu::Buffer,
    /// Per visible shape, then per layer, its source box (read with `source_boxes`).
    pub source_boxes: BufferPart<'a>,
    /// Block counts and lists (read with `tile_culling`; any buffer otherwise).
    pub block_lists: &'a wgpu::Buffer,
    /// The first shape tests as a uniform buffer (read with `uniform_tests`).
    pub uniform_tests: BufferPart<'a>,
    /// The merged plane groups' headers and grids (`crate::plane_groups`) and the frame's
    /// parallel trees (`crate::parallel_trees`).
    pub plane_groups: BufferPart<'a>,
}

/// Workgroup memory the projection's own variables may take (the fused lists' list and
/// box, `tile_test.wgsl`'s slots, what the driver adds), kept free beside the occupancy pad.
const OWN_WORKGROUP_BYTES: u32 = 10 * 1024;

/// Words of the occupancy pad for `kib` KiB, within a device's `limit` bytes of workgroup
/// memory beside [`OWN_WORKGROUP_BYTES`].
fn occupancy_pad_words(kib: u32, limit: u32) -> u32 {
    (kib * 1024).min(limit.saturating_sub(OWN_WORKGROUP_BYTES)) / 4
}

/// `occupancy_pad.wgsl` with an array of `words` words, or its no-op without (`words` 0).
pub fn occupancy_pad_source(words: u32) -> String {
    if words == 0 {
        return "fn touch_occupancy_pad(lid: u32) {}\n".to_owned();
    }
    format!("const OCCUPANCY_PAD_WORDS: u32 = {words}u;\n{}", crate::shader::OCCUPANCY_PAD)
}

/// The projection pass.
pub struct ProjectionPass {
    /// The shader modules by (subgroup operations, fused lists), built on first use: the
    /// subgroup ones only on devices with [`wgpu::Features::SUBGROUP`], and the fused
    /// lists' workgroup memory only in the variants that use it.
    /// With the occupancy pad's words (0: none) as the key's third part.
    modules: HashMap<(bool, bool, u32), wgpu::ShaderModule>,
    subgroups: bool,
    /// Subgroups are at least 8 wide: [`BoxReduction::SubgroupSlots`] runs as itself.
    subgroup_slots: bool,
    layout: wgpu::BindGroupLayout,
    bind_groups: BindGroupCache,
    pipelines: HashMap<ProjectionVariant, wgpu::ComputePipeline>,
}

impl ProjectionPass {
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr projection"),
            entries: &[
                uniform_entry(0),
                loaded_texture_entry(1),
                storage_entry(2, true),
                storage_entry(3, true),
                storage_entry(4, true),
                storage_entry(5, false),
                storage_entry(6, false),
                storage_entry(7, true),
                storage_entry(8, false),
                storage_entry(9, true),
                storage_entry(10, true),
                storage_entry(11, true),
                uniform_entry(12),
                storage_entry(13, true),
                // The same buffer as 13, read as vec4s: a parallel tree's node is two loads.
                storage_entry(14, true),
            ],
        });
        let subgroups = has_subgroups(device);
        let subgroup_slots = subgroups && device.adapter_info().subgroup_min_size >= 8;
        let mut pass = Self {
            modules: HashMap::new(),
            subgroups,
            subgroup_slots,
            layout,
            bind_groups: BindGroupCache::default(),
            pipelines: HashMap::new(),
        };
        pass.prepare_variant(device, ProjectionVariant::default());
        pass
    }

    /// Builds the pipeline of `variant` unless it exists.
    pub fn prepare_variant(&mut self, device: &wgpu::Device, v: ProjectionVariant) {
        if self.pipelines.contains_key(&v) {
            return;
        }
        let constants = [
            ("TILE_CULLING", flag(v.tile_culling)),
            ("SUPER_TILES", flag(v.tile_culling && v.super_tiles)),
            ("FUSED_LISTS", flag(v.tile_culling && v.fused_lists)),
            ("PARALLEL_RULE", flag(v.parallel_rule)),
            ("OCCLUDER_TESTS", flag(v.occluder_tests)),
            ("PATH_BLOCKERS", flag(v.path_blockers)),
            ("DEPTH_OCCLUSION", flag(v.depth_occlusion)),
            ("LAYERS", flag(v.layers)),
            ("DEBUG_WRITES", flag(v.debug_writes)),
            ("DEBUG_TILE_LISTS", flag(v.debug_tile_lists)),
            ("SOURCE_BOXES", flag(v.source_boxes)),
            ("UNIFORM_TESTS", flag(v.uniform_tests)),
            ("PARALLEL_TREES", flag(v.parallel_trees)),
            ("SUBGROUP_CULL", flag(v.subgroup_cull)),
            ("OCCLUSION_FIRST", flag(v.occlusion_first)),
            ("QUAD_ROW_STEP", if v.spread_quads() { 16.0 } else { 2.0 }),
            ("INSIDE_ENTRIES", flag(!v.no_inside_entries)),
            ("SUBGROUP_BOX", self.box_reduction_code(v.box_reduction)),
            ("LIST_PREFETCH", flag(v.list_prefetch)),
            ("ABLATION", v.ablation.code()),
        ];
        let label = format!("ppr projection {v:?}");
        let subgroup_ops = (v.subgroup_cull || v.box_reduction != BoxReduction::Atomics) && self.subgroups;
        let module = self.module(device, subgroup_ops, v.tile_culling && v.fused_lists, v.occupancy_pad_kib);
        let pipeline = compute_pipeline(device, &label, &self.layout, &module, "main", &constants);
        self.pipelines.insert(v, pipeline);
    }

    /// `SUBGROUP_BOX` for `r` on this device (slots only where subgroups are 8 wide or more).
    fn box_reduction_code(&self, r: BoxReduction) -> f64 {
        match r {
            BoxReduction::Atomics => 0.0,
            BoxReduction::SubgroupSlots if self.subgroup_slots => 2.0,
            BoxReduction::SubgroupAtomics | BoxReduction::SubgroupSlots => 1.0,
        }
    }

    /// The module with (or without) subgroup operations and the fused lists' code, and
    /// `pad_kib` KiB of [`ProjectionVariant::occupancy_pad_kib`].
    fn module(
        &mut self,
        device: &wgpu::Device,
        subgroups: bool,
        fused: bool,
        pad_kib: u32,
    ) -> wgpu::ShaderModule {
        use crate::shader::{
            FUSED_LISTS, FUSED_LISTS_STUB, SUBGROUP_CULL, SUBGROUP_CULL_FALLBACK, TILE_TEST, VIEW,
            module_with,
        };
        let pad_words = occupancy_pad_words(pad_kib, device.limits().max_compute_workgroup_storage_size);
        let module = self.modules.entry((subgroups, fused, pad_words)).or_insert_with(|| {
            let cull = if subgroups { SUBGROUP_CULL } else { SUBGROUP_CULL_FALLBACK };
            let lists = if fused { FUSED_LISTS } else { FUSED_LISTS_STUB };
            let pad = occupancy_pad_source(pad_words);
            let label =
                format!("ppr projection (subgroups {subgroups}, fused lists {fused}, pad {pad_words} words)");
            module_with(device, &label, &[VIEW, TILE_TEST, cull, lists, &pad], WGSL)
        });
        module.clone()
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &ProjectionBindings<'_>) -> wgpu::BindGroup {
        self.bind_groups.get(
            device,
            &wgpu::BindGroupDescriptor {
                label: Some("ppr projection"),
                layout: &self.layout,
                entries: &[
                    buffer_entry(0, b.uniforms),
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(b.depth),
                    },
                    buffer_entry(2, b.shapes),
                    buffer_entry(3, b.tests),
                    buffer_entry(4, b.occluders),
                    buffer_entry(5, b.intermediate),
                    buffer_entry(6, b.debug_writes),
                    buffer_entry(7, b.layers),
                    buffer_entry(8, b.atlas),
                    buffer_entry(9, b.super_lists),
                    buffer_entry(10, b.source_boxes),
                    buffer_entry(11, b.block_lists),
                    buffer_entry(12, b.uniform_tests),
                    buffer_entry(13, b.plane_groups),
                    buffer_entry(14, b.plane_groups),
                ],
            },
        )
    }

    /// Records the pass with `variant` (prepared beforehand).
    ///
    /// # Panics
    /// If [`Self::prepare_variant`] was not called for `variant`.
    pub fn encode(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        bind_group: &wgpu::BindGroup,
        viewport: [u32; 2],
        variant: ProjectionVariant,
    ) {
        let (x, y) = block_groups(viewport);
        pass.set_pipeline(self.pipelines.get(&variant).expect("variant prepared in prepare()"));
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}
