//! Layer reflection pass: the reflections of glass panels and water planes, read from
//! their atlas regions, into the layer output.

use super::bind_group_cache::BindGroupCache;
use super::{
    BufferPart, TILE, compute_pipeline, linear_sampler, loaded_texture_entry, sampled_texture_entry,
    sampler_entry, storage_entry, uniform_entry,
};

pub const WGSL: &str = include_str!("../../shaders/layer_reflection.wgsl");

/// Where the layer reflection's dispatch is recorded. It reads none of what the reflection
/// pass writes (and writes none of what it reads), so in one compute pass the two
/// dispatches need no barrier between them and the GPU runs them side by side. In its own
/// pass it cost 0.011-0.015 ms more per frame on every layered frame of the demo and the
/// kitchen, at 4K and 1080p (H100, whole frames from two encoder timestamps; demo 4K
/// `cam_mirror` 0.335 -> 0.322 ms, kitchen 4K overview 0.148 -> 0.135; docs/perf/runtime.md,
/// twenty-sixth session).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum LayerPlacement {
    /// In the reflection's compute pass, before its dispatch (timed with it).
    #[default]
    BeforeReflection,
    /// In the reflection's compute pass, after its dispatch (timed with it; bench only, the
    /// same image).
    AfterReflection,
    /// Its own compute pass after the reflection's, timed on its own (the layout before the
    /// twenty-sixth session; bench only, the same image).
    OwnPass,
}

/// What the layer pass's workgroups cover.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayerGroups {
    /// A grid over the layers' common rectangle of this many pixels, one workgroup a tile
    /// (the frame's flags hold `FLAG_LAYER_EVERY_TILE`).
    EveryTile([u32; 2]),
    /// This many tiles, [`crate::plan::FramePlan::layer_tiles`]: the tiles each layer's own
    /// rectangle meets, layer after layer. Over the common rectangle of a pond and a far
    /// window most tiles meet neither, and a grid's workgroups that return at once still
    /// cost their launch and their reads of the layers (the demo's 4K overview: 18 400
    /// workgroups for about 2 000 such tiles).
    LayerTiles(u32),
}

/// Most workgroups along x in a layer-tile dispatch (wgpu's default limit is 65 535).
const LAYER_TILE_GROUPS_X: u32 = 32_768;

impl LayerGroups {
    /// The dispatch's workgroup counts (x, y).
    pub fn workgroups(self) -> [u32; 2] {
        match self {
            Self::EveryTile(extent) => [extent[0].div_ceil(TILE), extent[1].div_ceil(TILE)],
            Self::LayerTiles(0) => [0, 0],
            Self::LayerTiles(n) => {
                let x = n.min(LAYER_TILE_GROUPS_X);
                [x, n.div_ceil(x)]
            }
        }
    }
}

/// Buffers and views the layer pass reads and writes.
pub struct LayerBindings<'a> {
    pub uniforms: BufferPart<'a>,
    pub atlas: &'a wgpu::Buffer,
    pub layers: BufferPart<'a>,
    pub shapes: BufferPart<'a>,
    pub depth: &'a wgpu::TextureView,
    pub color: &'a wgpu::TextureView,
    pub output: &'a wgpu::TextureView,
    /// The frame's intermediate buffer, which the shader does not read: bound (read-only)
    /// so that where the layers and the reflection follow the projection in its compute
    /// pass, the barrier wgpu puts before this dispatch also readies the intermediate
    /// buffer for the reflection, which then runs beside it without a barrier of its own.
    pub intermediate: &'a wgpu::Buffer,
    /// The classification's active tiles, which the shader does not read either: bound
    /// (read-only) for the same reason, on frames with indirect dispatch, whose reflection
    /// reads them after the classification wrote them.
    pub active_tiles: &'a wgpu::Buffer,
}

/// The layer reflection pass.
pub struct LayerReflectionPass {
    pipeline: wgpu::ComputePipeline,
    /// Bench only, built on request ([`Self::prepare_full_stretch`]): the water edge
    /// stretch walks all its steps, also past the layer's rectangle.
    full_stretch: Option<wgpu::ComputePipeline>,
    module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    bind_groups: BindGroupCache,
    sampler: wgpu::Sampler,
}

impl LayerReflectionPass {
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr layer reflection"),
            entries: &[
                uniform_entry(0),
                storage_entry(1, true),
                storage_entry(2, true),
                storage_entry(3, true),
                loaded_texture_entry(4),
                sampled_texture_entry(5),
                sampler_entry(6),
                wgpu::BindGroupLayoutEntry {
                    binding: 7,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format: super::reflection::OUTPUT_FORMAT,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
                storage_entry(8, true),
                storage_entry(9, true),
            ],
        });
        let module = crate::shader::module_with(
            device,
            "ppr layer reflection",
            &[crate::shader::VIEW, crate::shader::SHADING],
            WGSL,
        );
        let pipeline = compute_pipeline(device, "ppr layer reflection", &layout, &module, "main", &[]);
        let sampler = linear_sampler(device, "ppr layer reflection linear");
        Self { pipeline, full_stretch: None, module, layout, bind_groups: BindGroupCache::default(), sampler }
    }

    /// Builds the full-walk pipeline (bench only; the renderer asks for it when
    /// `DebugOptions::full_stretch_walk` is set).
    pub fn prepare_full_stretch(&mut self, device: &wgpu::Device) {
        if self.full_stretch.is_none() {
            let constants = [("STRETCH_STOPS_AT_RECT", 0.0)];
            let label = "ppr layer reflection (full stretch walk)";
            self.full_stretch =
                Some(compute_pipeline(device, label, &self.layout, &self.module, "main", &constants));
        }
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &LayerBindings<'_>) -> wgpu::BindGroup {
        self.bind_groups.get(
            device,
            &wgpu::BindGroupDescriptor {
                label: Some("ppr layer reflection"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: b.uniforms.binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: b.atlas.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 2, resource: b.layers.binding() },
                    wgpu::BindGroupEntry { binding: 3, resource: b.shapes.binding() },
                    wgpu::BindGroupEntry {
                        binding: 4,
                        resource: wgpu::BindingResource::TextureView(b.depth),
                    },
                    wgpu::BindGroupEntry {
                        binding: 5,
                        resource: wgpu::BindingResource::TextureView(b.color),
                    },
                    wgpu::BindGroupEntry {
                        binding: 6,
                        resource: wgpu::BindingResource::Sampler(&self.sampler),
                    },
                    wgpu::BindGroupEntry {
                        binding: 7,
                        resource: wgpu::BindingResource::TextureView(b.output),
                    },
                    wgpu::BindGroupEntry { binding: 8, resource: b.intermediate.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 9, resource: b.active_tiles.as_entire_binding() },
                ],
            },
        )
    }

    /// Records the pass over `groups`; with `full_stretch` (bench only, the same image) the
    /// pipeline of [`Self::prepare_full_stretch`].
    pub fn encode(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        bind_group: &wgpu::BindGroup,
        groups: LayerGroups,
        full_stretch: bool,
    ) {
        let [x, y] = groups.workgroups();
        if x == 0 || y == 0 {
            return;
        }
        let pipeline = if full_stretch {
            self.full_stretch.as_ref().expect("prepare_full_stretch() before a full-walk encode")
        } else {
            &self.pipeline
        };
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}

#[cfg(test)]
mod tests {
    use super::{LAYER_TILE_GROUPS_X, LayerGroups};

    #[test]
    fn layer_dispatches_cover_their_tiles() {
        assert_eq!(LayerGroups::EveryTile([33, 16]).workgroups(), [3, 1]);
        assert_eq!(LayerGroups::LayerTiles(0).workgroups(), [0, 0]);
        assert_eq!(LayerGroups::LayerTiles(7).workgroups(), [7, 1]);
        // Past the x limit, rows of it: the shader skips the entries past the list's end.
        let n = 2 * LAYER_TILE_GROUPS_X + 5;
        let [x, y] = LayerGroups::LayerTiles(n).workgroups();
        assert!(x <= LAYER_TILE_GROUPS_X && x * y >= n && x * (y - 1) < n, "{x} x {y}");
    }
}
