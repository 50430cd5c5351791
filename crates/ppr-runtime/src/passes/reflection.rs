//! Reflection pass: decode, fill holes, filtered and unfiltered samples, anti-bleeding.

use super::bind_group_cache::BindGroupCache;
use super::tile_classify::ACTIVE_TILES_ARGS;
use super::{
    BufferPart, compute_pipeline, flag, linear_sampler, loaded_texture_entry, sampled_texture_entry,
    sampler_entry, storage_entry, tile_groups, uniform_entry,
};

use std::collections::HashMap;

pub const WGSL: &str = include_str!("../../shaders/reflection.wgsl");

/// Format of the reflection output (colour + confidence alpha).
pub const OUTPUT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Buffers and views the reflection pass reads and writes.
pub struct ReflectionBindings<'a> {
    pub uniforms: BufferPart<'a>,
    pub intermediate: &'a wgpu::Buffer,
    pub color: &'a wgpu::TextureView,
    pub output: &'a wgpu::TextureView,
    pub active_tiles: &'a wgpu::Buffer,
    pub depth: &'a wgpu::TextureView,
    /// Shading normals (world space, xyz); any float texture when normal maps are off.
    pub normals: &'a wgpu::TextureView,
    /// The frame's glossy reflectors (`GpuGlossyShapes`).
    pub glossy: BufferPart<'a>,
    /// The next encode's intermediate buffer and atlas (the other slot of
    /// `FrameBuffers`), cleared by the direct-dispatch pipelines.
    pub next_intermediate: &'a wgpu::Buffer,
    pub next_atlas: &'a wgpu::Buffer,
    /// A storage part of the upload buffer (which `uniforms` and `glossy` are parts of),
    /// which the shader does not read: bound (read-only) so that the reflection uses the
    /// upload buffer as the layer pass before it in the same compute pass does (uniform and
    /// storage). wgpu puts a barrier before a dispatch wherever a buffer's use changes, even
    /// between two reads; without this binding the reflection waited there for the layer
    /// pass to end instead of running beside it.
    pub upload_storage: BufferPart<'a>,
}

/// Which reflection pipeline a frame runs (beside direct or indirect dispatch).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ReflectionVariant {
    /// Perturb by the frame's shading normals on normal-mapped reflectors.
    pub normal_maps: bool,
    /// Blur the reflections of reflectors with roughness (`glossy.wgsl`).
    pub glossy: bool,
    /// The frame fills holes (`ReflectionSettings::holes`; a uniform flag, the pipeline
    /// only picks the layout by it).
    pub holes: bool,
    /// Leave parts out to time the rest (bench only).
    pub ablation: ReflectionAblation,
    /// Two by two pixels per invocation sharing their neighbourhood reads (`main_quads`)
    /// for mirrors with hole filling in direct dispatch, instead of one pixel per
    /// invocation (`main`); the same image (bench only; `runs_quads` says why). Indirect
    /// dispatch, glossy, normal maps and frames without hole filling always take one pixel
    /// per invocation.
    pub quads: bool,
    /// Direct dispatch leaves the next encode's buffers as they are, for the clear pass to
    /// clear (bench only: the layout before the twenty-fourth session, the same image).
    pub leave_next: bool,
    /// Indirect frames run at most this many workgroups, which walk the active-tile list
    /// (a direct dispatch; override `TILE_LOOP`), instead of one workgroup per active tile
    /// by indirect dispatch (`None`: bench only, the same image). `ReflectionPass::new`
    /// builds the default's pipelines with [`crate::TILE_LOOP_GROUPS`].
    pub tile_loop: Option<u32>,
}

/// What an ablated reflection pass leaves out (bench only: `ppr-bench runtime
/// --projection-profile` times each to show where the pass's time goes; never a correct
/// image).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ReflectionAblation {
    /// The real pass.
    #[default]
    None,
    /// Returns at once: the launch.
    Empty,
    /// Reads the intermediate buffer, fills holes and decodes, and stores the offset: no
    /// colour read, no glossy blur.
    NoColour,
    /// Also reads the colour (filtered, unfiltered, anti-bleeding), but no glossy blur.
    NoGlossy,
}

impl ReflectionAblation {
    fn code(self) -> f64 {
        match self {
            Self::None => 0.0,
            Self::Empty => 1.0,
            Self::NoColour => 2.0,
            Self::NoGlossy => 3.0,
        }
    }
}

impl ReflectionVariant {
    fn index(self) -> usize {
        usize::from(self.normal_maps) | usize::from(self.glossy) << 1
    }

    /// The pipeline of this variant under direct or indirect dispatch.
    fn key(self, indirect: bool) -> PipelineKey {
        let dispatch = (indirect, indirect && self.tile_loop.is_some());
        (dispatch, self.index(), (!self.runs_quads(indirect), self.ablation), self.clears_next(indirect))
    }

    /// Whether the pass clears the next encode's buffers: in direct dispatch, which visits
    /// every pixel, unless `leave_next`.
    pub fn clears_next(self, indirect: bool) -> bool {
        !indirect && !self.leave_next
    }

    /// Whether the pass runs `main_quads` (the `quads` field asked for, mirrors with hole
    /// filling in direct dispatch). Not by default since the fourteenth session: with
    /// wgpu's loop bounding the quads took the H200's full-screen 4K mirror pass from
    /// 0.147-0.159 to 0.121-0.134 ms; without it (`shader::runtime_checks`) one pixel per
    /// invocation takes 0.059-0.068 ms against the quads' 0.078-0.084, and 0.020-0.021
    /// against 0.031-0.033 at 1080p (docs/perf/runtime.md).
    fn runs_quads(self, indirect: bool) -> bool {
        self.quads && self.holes && !(indirect || self.glossy || self.normal_maps)
    }
}

/// Pipelines by indirect (and the tile loop), [`ReflectionVariant::index`], one pixel per
/// invocation and ablation, and whether it clears the next encode's buffers
/// ([`ReflectionVariant::key`]).
type PipelineKey = ((bool, bool), usize, (bool, ReflectionAblation), bool);

/// Pixels per workgroup side of `main_quads` (16 x 16 invocations of 2 x 2 pixels).
const QUAD_BLOCK: u32 = 32;

/// The reflection pass.
pub struct ReflectionPass {
    /// Pipelines: the default layout's built at once, others (bench only) by
    /// [`Self::prepare_variant`].
    pipelines: HashMap<PipelineKey, wgpu::ComputePipeline>,
    module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    bind_groups: BindGroupCache,
    sampler: wgpu::Sampler,
}

impl ReflectionPass {
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr reflection"),
            entries: &[
                uniform_entry(0),
                storage_entry(1, true),
                sampled_texture_entry(2),
                sampler_entry(3),
                wgpu::BindGroupLayoutEntry {
                    binding: 4,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format: OUTPUT_FORMAT,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
                storage_entry(5, true),
                loaded_texture_entry(7),
                loaded_texture_entry(8),
                uniform_entry(9),
                storage_entry(10, false),
                storage_entry(11, false),
                storage_entry(12, true),
            ],
        });
        let module = crate::shader::module_with(
            device,
            "ppr reflection",
            &[crate::shader::VIEW, crate::shader::SHADING, crate::shader::GLOSSY],
            WGSL,
        );
        let sampler = linear_sampler(device, "ppr reflection linear");
        let mut pass = Self {
            pipelines: HashMap::new(),
            module,
            layout,
            bind_groups: BindGroupCache::default(),
            sampler,
        };
        pass.prepare_variant(
            device,
            ReflectionVariant { tile_loop: Some(crate::TILE_LOOP_GROUPS), ..ReflectionVariant::default() },
        );
        pass
    }

    fn pipeline(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        module: &wgpu::ShaderModule,
        ((indirect, tile_loop), index, (pixel_per_thread, ablation), clear_next): PipelineKey,
    ) -> wgpu::ComputePipeline {
        let (normal_maps, glossy) = (index & 1 != 0, index & 2 != 0);
        let label = format!(
            "ppr reflection indirect={indirect} tile_loop={tile_loop} normal_maps={normal_maps} \
             glossy={glossy} pixel_per_thread={pixel_per_thread} ablation={ablation:?} \
             clear_next={clear_next}"
        );
        let constants = [
            ("INDIRECT", flag(indirect)),
            ("TILE_LOOP", flag(tile_loop)),
            ("NORMAL_MAPS", flag(normal_maps)),
            ("GLOSSY", flag(glossy)),
            ("ABLATION", ablation.code()),
            ("CLEAR_NEXT", flag(clear_next)),
        ];
        let entry = if pixel_per_thread { "main" } else { "main_quads" };
        compute_pipeline(device, &label, layout, module, entry, &constants)
    }

    /// Builds the pipelines of `variant`'s layout and ablation (every dispatch, normal-map,
    /// glossy and hole-filling variant, so that settings may change after `prepare`) unless
    /// they exist.
    pub fn prepare_variant(&mut self, device: &wgpu::Device, variant: ReflectionVariant) {
        for indirect in [false, true] {
            for index in 0..4 {
                for holes in [false, true] {
                    let (normal_maps, glossy) = (index & 1 != 0, index & 2 != 0);
                    let key = ReflectionVariant { normal_maps, glossy, holes, ..variant }.key(indirect);
                    if !self.pipelines.contains_key(&key) {
                        let p = Self::pipeline(device, &self.layout, &self.module, key);
                        self.pipelines.insert(key, p);
                    }
                }
            }
        }
    }

    fn pipeline_for(&self, indirect: bool, variant: ReflectionVariant) -> &wgpu::ComputePipeline {
        self.pipelines.get(&variant.key(indirect)).expect("variant prepared in prepare()")
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &ReflectionBindings<'_>) -> wgpu::BindGroup {
        self.bind_groups.get(
            device,
            &wgpu::BindGroupDescriptor {
                label: Some("ppr reflection"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: b.uniforms.binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: b.intermediate.as_entire_binding() },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: wgpu::BindingResource::TextureView(b.color),
                    },
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: wgpu::BindingResource::Sampler(&self.sampler),
                    },
                    wgpu::BindGroupEntry {
                        binding: 4,
                        resource: wgpu::BindingResource::TextureView(b.output),
                    },
                    wgpu::BindGroupEntry { binding: 5, resource: b.active_tiles.as_entire_binding() },
                    wgpu::BindGroupEntry {
                        binding: 7,
                        resource: wgpu::BindingResource::TextureView(b.depth),
                    },
                    wgpu::BindGroupEntry {
                        binding: 8,
                        resource: wgpu::BindingResource::TextureView(b.normals),
                    },
                    wgpu::BindGroupEntry { binding: 9, resource: b.glossy.binding() },
                    wgpu::BindGroupEntry { binding: 10, resource: b.next_intermediate.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 11, resource: b.next_atlas.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 12, resource: b.upload_storage.binding() },
                ],
            },
        )
    }

    /// Records the pass over the whole viewport.
    pub fn encode(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        bind_group: &wgpu::BindGroup,
        viewport: [u32; 2],
        variant: ReflectionVariant,
    ) {
        let (x, y) = if variant.runs_quads(false) {
            let [w, h] = viewport;
            (w.div_ceil(QUAD_BLOCK), h.div_ceil(QUAD_BLOCK))
        } else {
            tile_groups(viewport)
        };
        pass.set_pipeline(self.pipeline_for(false, variant));
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }

    /// Records the pass over the active tiles (indirect arguments from the classify pass,
    /// in `active_tiles`' header, or with the tile loop a direct dispatch of at most
    /// `tile_count` workgroups).
    pub fn encode_tiles(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        bind_group: &wgpu::BindGroup,
        active_tiles: &wgpu::Buffer,
        tile_count: u32,
        variant: ReflectionVariant,
    ) {
        pass.set_pipeline(self.pipeline_for(true, variant));
        pass.set_bind_group(0, bind_group, &[]);
        if let Some(groups) = variant.tile_loop {
            pass.dispatch_workgroups(tile_count.min(groups).max(1), 1, 1);
        } else {
            pass.dispatch_workgroups_indirect(active_tiles, ACTIVE_TILES_ARGS);
        }
    }
}
