//! Super-tile list pass: per 64 × 64-pixel super-tile, the visible shapes that may reflect
//! some pixel of it, so that the tiled projection's 16 × 16 tiles test only those.

use super::bind_group_cache::BindGroupCache;
use super::{BufferPart, compute_pipeline, flag, loaded_texture_entry, storage_entry, uniform_entry};

pub const WGSL: &str = include_str!("../../shaders/super_tile_lists.wgsl");

/// Edge of a super-tile in pixels (`SUPER_TILE_SIZE` of `tile_test.wgsl`).
pub const SUPER_TILE: u32 = 64;

/// Entries of one super-tile's list (`SUPER_LIST_CAPACITY` of `tile_test.wgsl`); a
/// super-tile with more candidates lists none and its tiles test every visible shape.
pub const SUPER_LIST_CAPACITY: u32 = 1024;

/// Super-tiles covering a `width × height` viewport: (columns, rows).
pub fn super_tile_grid([w, h]: [u32; 2]) -> (u32, u32) {
    (w.div_ceil(SUPER_TILE), h.div_ceil(SUPER_TILE))
}

/// Bytes of the super-tile list buffer of a viewport: a count per super-tile, then a list
/// of [`SUPER_LIST_CAPACITY`] entries per super-tile.
pub fn super_lists_size(viewport: [u32; 2]) -> u64 {
    let (x, y) = super_tile_grid(viewport);
    4 * u64::from(x) * u64::from(y) * (1 + u64::from(SUPER_LIST_CAPACITY))
}

/// Buffers and views the pass reads and writes.
pub struct SuperTileBindings<'a> {
    pub uniforms: BufferPart<'a>,
    pub depth: &'a wgpu::TextureView,
    /// Per visible shape, its test planes (`ShapeTest`).
    pub tests: BufferPart<'a>,
    /// Per visible shape, its source box (read with source boxes).
    pub source_boxes: BufferPart<'a>,
    pub super_lists: &'a wgpu::Buffer,
}

/// The super-tile list pass.
pub struct SuperTileListPass {
    /// Without and with source boxes.
    pipelines: [wgpu::ComputePipeline; 2],
    layout: wgpu::BindGroupLayout,
    bind_groups: BindGroupCache,
}

impl SuperTileListPass {
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr super-tile lists"),
            entries: &[
                uniform_entry(0),
                loaded_texture_entry(1),
                storage_entry(2, true),
                storage_entry(3, true),
                storage_entry(4, false),
            ],
        });
        let module = crate::shader::module_with(
            device,
            "ppr super-tile lists",
            &[crate::shader::VIEW, crate::shader::TILE_TEST],
            WGSL,
        );
        let pipelines = [false, true].map(|boxes| {
            let constants = [("SOURCE_BOXES", flag(boxes))];
            compute_pipeline(device, "ppr super-tile lists", &layout, &module, "main", &constants)
        });
        Self { pipelines, layout, bind_groups: BindGroupCache::default() }
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &SuperTileBindings<'_>) -> wgpu::BindGroup {
        self.bind_groups.get(
            device,
            &wgpu::BindGroupDescriptor {
                label: Some("ppr super-tile lists"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: b.uniforms.binding() },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(b.depth),
                    },
                    wgpu::BindGroupEntry { binding: 2, resource: b.tests.binding() },
                    wgpu::BindGroupEntry { binding: 3, resource: b.source_boxes.binding() },
                    wgpu::BindGroupEntry { binding: 4, resource: b.super_lists.as_entire_binding() },
                ],
            },
        )
    }

    /// Records the pass over the viewport's super-tiles.
    pub fn encode(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        bind_group: &wgpu::BindGroup,
        viewport: [u32; 2],
        source_boxes: bool,
    ) {
        let (x, y) = super_tile_grid(viewport);
        pass.set_pipeline(&self.pipelines[usize::from(source_boxes)]);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}
