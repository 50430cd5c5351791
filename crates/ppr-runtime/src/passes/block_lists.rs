//! Block-list pass: per 32 × 32-pixel block, the visible shapes that may reflect some pixel
//! of it, so that the tiled projection's pixels test only those.

use super::bind_group_cache::BindGroupCache;
use super::projection::block_groups;
use super::{
    BufferPart, buffer_entry, compute_pipeline, flag, loaded_texture_entry, storage_entry, uniform_entry,
};

pub const WGSL: &str = include_str!("../../shaders/block_lists.wgsl");

/// Entries of one block's list (`BLOCK_LIST_CAPACITY` of `tile_test.wgsl`); a block with
/// more candidates lists none and its pixels test its super-tile's list or every visible
/// shape.
pub const BLOCK_LIST_CAPACITY: u32 = 256;

/// Bytes of the block-list buffer of a viewport: a count per block, then a list of
/// [`BLOCK_LIST_CAPACITY`] entries per block.
pub fn block_lists_size(viewport: [u32; 2]) -> u64 {
    let (x, y) = block_groups(viewport);
    4 * u64::from(x) * u64::from(y) * (1 + u64::from(BLOCK_LIST_CAPACITY))
}

/// Buffers and views the pass reads and writes.
pub struct BlockListBindings<'a> {
    pub uniforms: BufferPart<'a>,
    pub depth: &'a wgpu::TextureView,
    /// Per visible shape, its test planes (`ShapeTest`).
    pub tests: BufferPart<'a>,
    /// Per visible shape, its source box (read with source boxes).
    pub source_boxes: BufferPart<'a>,
    /// Super-tile counts and lists (read with super-tiles).
    pub super_lists: &'a wgpu::Buffer,
    pub block_lists: &'a wgpu::Buffer,
}

/// The block-list pass.
pub struct BlockListPass {
    /// By (source boxes, super-tiles).
    pipelines: [[wgpu::ComputePipeline; 2]; 2],
    /// Bench only, built on request ([`Self::prepare_box_only`]): the pass up to the box
    /// of each block's positions, without the lists (by source boxes).
    box_only: Option<[wgpu::ComputePipeline; 2]>,
    module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    bind_groups: BindGroupCache,
}

impl BlockListPass {
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr block lists"),
            entries: &[
                uniform_entry(0),
                loaded_texture_entry(1),
                storage_entry(2, true),
                storage_entry(3, true),
                storage_entry(4, true),
                storage_entry(5, false),
            ],
        });
        let module = crate::shader::module_with(
            device,
            "ppr block lists",
            &[crate::shader::VIEW, crate::shader::TILE_TEST],
            WGSL,
        );
        let pipelines = [false, true].map(|boxes| {
            [false, true].map(|supers| {
                let constants = [("SOURCE_BOXES", flag(boxes)), ("SUPER_TILES", flag(supers))];
                compute_pipeline(device, "ppr block lists", &layout, &module, "main", &constants)
            })
        });
        Self { pipelines, box_only: None, module, layout, bind_groups: BindGroupCache::default() }
    }

    /// Builds the box-only pipelines (bench only; the renderer asks for them when
    /// `DebugOptions::block_lists_box_only` is set).
    pub fn prepare_box_only(&mut self, device: &wgpu::Device) {
        if self.box_only.is_none() {
            let (layout, module) = (&self.layout, &self.module);
            self.box_only = Some([false, true].map(|boxes| {
                let constants = [("SOURCE_BOXES", flag(boxes)), ("BOX_ONLY", 1.0)];
                compute_pipeline(device, "ppr block lists (box only)", layout, module, "main", &constants)
            }));
        }
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &BlockListBindings<'_>) -> wgpu::BindGroup {
        self.bind_groups.get(
            device,
            &wgpu::BindGroupDescriptor {
                label: Some("ppr block lists"),
                layout: &self.layout,
                entries: &[
                    buffer_entry(0, b.uniforms),
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(b.depth),
                    },
                    buffer_entry(2, b.tests),
                    buffer_entry(3, b.source_boxes),
                    buffer_entry(4, b.super_lists),
                    buffer_entry(5, b.block_lists),
                ],
            },
        )
    }

    /// Records the pass over the viewport's blocks (with `box_only`, bench only, the pass
    /// up to each block's box: no lists, what the projection then reads is wrong).
    pub fn encode(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        bind_group: &wgpu::BindGroup,
        viewport: [u32; 2],
        (source_boxes, super_tiles): (bool, bool),
        box_only: bool,
    ) {
        let (x, y) = block_groups(viewport);
        let pipeline = if box_only {
            &self.box_only.as_ref().expect("prepare_box_only() before encode()")[usize::from(source_boxes)]
        } else {
            &self.pipelines[usize::from(source_boxes)][usize::from(super_tiles)]
        };
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}
