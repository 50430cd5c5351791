//! Tile classification: the list of tiles that show a visible reflector and the indirect
//! dispatch arguments of the reflection pass over them; and the clear of the next encode's
//! intermediate buffer and atlas, and of its list's count and arguments.

use super::bind_group_cache::BindGroupCache;
use super::projection::block_groups;
use super::{BufferPart, compute_pipeline, flag, loaded_texture_entry, storage_entry, uniform_entry};

pub const WGSL: &str = include_str!("../../shaders/tile_classify.wgsl");

/// Bytes before the tile indices in an active-tile buffer (the count and the dispatch
/// arguments).
pub const ACTIVE_TILES_HEADER: u64 = 16;

/// Byte offset of the indirect dispatch arguments (x, y, z) in an active-tile buffer.
pub const ACTIVE_TILES_ARGS: u64 = 4;

/// Buffers and views the classification reads and writes.
pub struct ClassifyBindings<'a> {
    pub uniforms: BufferPart<'a>,
    pub depth: &'a wgpu::TextureView,
    pub shapes: BufferPart<'a>,
    pub visible: BufferPart<'a>,
    pub screen_rects: BufferPart<'a>,
    /// This encode's active-tile list (count, dispatch arguments, tiles; zero-counted).
    pub active_tiles: &'a wgpu::Buffer,
    /// The next encode's active-tile list: its count and arguments zeroed here.
    pub next_active_tiles: &'a wgpu::Buffer,
    pub tile_flags: &'a wgpu::Buffer,
    /// Layer reflectors of the frame (glass, water): reflectors seen through them count.
    pub layers: BufferPart<'a>,
    /// The next encode's intermediate buffer and atlas (the renderer's other slot), cleared
    /// whole: this encode's own slot was cleared by the encode before, so the projection,
    /// which writes it, need not wait for the classification.
    pub next_intermediate: &'a wgpu::Buffer,
    pub next_atlas: &'a wgpu::Buffer,
}

/// The tile classification pass (one dispatch: its blocks append their active tiles and
/// raise the indirect arguments).
pub struct TileClassifyPass {
    /// For frames with layers.
    classify: wgpu::ComputePipeline,
    /// The same for frames without layers (their layer list compiled out), built on
    /// request ([`Self::prepare_without_layers`]).
    without_layers: Option<wgpu::ComputePipeline>,
    module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    bind_groups: BindGroupCache,
}

impl TileClassifyPass {
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr tile classify"),
            entries: &[
                uniform_entry(0),
                loaded_texture_entry(1),
                storage_entry(2, true),
                storage_entry(3, true),
                storage_entry(4, true),
                storage_entry(5, false),
                storage_entry(6, false),
                storage_entry(7, false),
                storage_entry(8, true),
                storage_entry(9, false),
                storage_entry(10, false),
            ],
        });
        let module = crate::shader::module_with(device, "ppr tile classify", &[crate::shader::VIEW], WGSL);
        Self {
            classify: compute_pipeline(device, "ppr tile classify", &layout, &module, "classify", &[]),
            without_layers: None,
            module,
            layout,
            bind_groups: BindGroupCache::default(),
        }
    }

    /// Builds the classification for frames without layers (`LAYERS` off: the layer list
    /// and its tests compiled out). The layer code raised the kernel's
    /// registers and slowed the classification of 10 000 shapes by 0.006-0.009 ms on the
    /// H200 (docs/perf/runtime.md, twenty-fifth session).
    pub fn prepare_without_layers(&mut self, device: &wgpu::Device) {
        if self.without_layers.is_none() {
            let constants = [("LAYERS", flag(false))];
            let label = "ppr tile classify (no layers)";
            self.without_layers =
                Some(compute_pipeline(device, label, &self.layout, &self.module, "classify", &constants));
        }
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &ClassifyBindings<'_>) -> wgpu::BindGroup {
        self.bind_groups.get(
            device,
            &wgpu::BindGroupDescriptor {
                label: Some("ppr tile classify"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: b.uniforms.binding() },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(b.depth),
                    },
                    wgpu::BindGroupEntry { binding: 2, resource: b.shapes.binding() },
                    wgpu::BindGroupEntry { binding: 3, resource: b.visible.binding() },
                    wgpu::BindGroupEntry { binding: 4, resource: b.screen_rects.binding() },
                    wgpu::BindGroupEntry { binding: 5, resource: b.active_tiles.as_entire_binding() },
                    wgpu::BindGroupEntry {
                        binding: 6,
                        resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                            buffer: b.next_active_tiles,
                            offset: 0,
                            size: wgpu::BufferSize::new(ACTIVE_TILES_HEADER),
                        }),
                    },
                    wgpu::BindGroupEntry { binding: 7, resource: b.tile_flags.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 8, resource: b.layers.binding() },
                    wgpu::BindGroupEntry { binding: 9, resource: b.next_intermediate.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 10, resource: b.next_atlas.as_entire_binding() },
                ],
            },
        )
    }

    /// Records the classification of every tile, the clear of the next encode's buffers
    /// and the indirect arguments (one dispatch). The active-tile count and the arguments
    /// must be zero beforehand: the classification before zeroed them, or the renderer
    /// clears them in the encoder (`FrameBuffers::take_counters`). `layers`:
    /// the frame has layers (without, after [`Self::prepare_without_layers`], the kernel
    /// without their code runs).
    pub fn encode(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        bind_group: &wgpu::BindGroup,
        viewport: [u32; 2],
        layers: bool,
    ) {
        // One workgroup per 2 × 2 tiles.
        let (x, y) = block_groups(viewport);
        pass.set_bind_group(0, bind_group, &[]);
        let classify = if layers {
            &self.classify
        } else {
            self.without_layers.as_ref().expect("prepare_without_layers() before encode()")
        };
        pass.set_pipeline(classify);
        pass.dispatch_workgroups(x, y, 1);
    }
}
