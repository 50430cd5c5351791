//! Tile classification: the list of tiles that show a visible reflector, the clear of their
//! pixels in the intermediate buffer (and of the layers' atlas), and the indirect dispatch
//! arguments of the reflection pass over them.

use super::bind_group_cache::BindGroupCache;
use super::projection::{BLOCK, block_groups};
use super::{compute_pipeline, flag, loaded_texture_entry, storage_entry, uniform_entry};
use crate::plan::ScreenRect;

pub const WGSL: &str = include_str!("../../shaders/tile_classify.wgsl");

/// Largest block coordinate a [`block_range`] holds (8 bits each); blocks beyond it (past
/// 8 160 pixels) share it.
const MAX_BLOCK_COORD: u32 = 255;

/// The 32 x 32-pixel blocks that `rect` (exclusive max) touches, packed into one word as
/// the classification reads it: the first block's x and y, then the last block's x and y,
/// 8 bits each from the low byte up. A coordinate past [`MAX_BLOCK_COORD`] is clamped to
/// it, and so is the block's in the shader: the range then holds more blocks, never fewer
/// (clamping keeps the order). An empty rectangle holds none (its first block after its
/// last). A quarter of the screen rectangle's 16 bytes: every workgroup of the
/// classification reads every visible shape's range, which at 10 000 visible shapes is
/// most of its time.
pub fn block_range(rect: &ScreenRect) -> u32 {
    if rect.area() == 0 {
        return MAX_BLOCK_COORD;
    }
    let coord = |v: u32| (v / BLOCK).min(MAX_BLOCK_COORD);
    let [x0, y0] = rect.min.map(coord);
    let [x1, y1] = rect.max.map(|v| coord(v - 1));
    x0 | y0 << 8 | x1 << 16 | y1 << 24
}

/// Bytes before the tile indices in the active-tile buffer (count + padding).
pub const ACTIVE_TILES_HEADER: u64 = 16;

/// Buffers and views the classification reads and writes.
pub struct ClassifyBindings<'a> {
    pub uniforms: &'a wgpu::Buffer,
    pub depth: &'a wgpu::TextureView,
    pub shapes: &'a wgpu::Buffer,
    pub visible: &'a wgpu::Buffer,
    /// Per visible shape: the blocks its screen rectangle touches ([`block_range`]).
    pub block_ranges: &'a wgpu::Buffer,
    pub active_tiles: &'a wgpu::Buffer,
    pub dispatch_args: &'a wgpu::Buffer,
    pub tile_flags: &'a wgpu::Buffer,
    /// Layer reflectors of the frame (glass, water): reflectors seen through them count.
    pub layers: &'a wgpu::Buffer,
    /// Cleared over the active tiles (unless the clear pass does it, [`TileClassifyPass::encode`]).
    pub intermediate: &'a wgpu::Buffer,
    /// The layers' atlas, cleared over the frame's layer regions (unless the clear pass
    /// does it).
    pub atlas: &'a wgpu::Buffer,
}

/// The tile classification pass (one dispatch: its blocks append their active tiles and
/// raise the indirect arguments).
pub struct TileClassifyPass {
    /// With the clear of the active tiles.
    classify: wgpu::ComputePipeline,
    /// Bench only, built on request ([`Self::prepare_separate_clear`]): without it.
    separate_clear: Option<wgpu::ComputePipeline>,
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
            separate_clear: None,
            module,
            layout,
            bind_groups: BindGroupCache::default(),
        }
    }

    /// Builds the classification that leaves the clear to the clear pass (bench only; the
    /// renderer asks for it when `DebugOptions::tile_clear_pass` is set).
    pub fn prepare_separate_clear(&mut self, device: &wgpu::Device) {
        if self.separate_clear.is_none() {
            let constants = [("CLEAR_TILES", flag(false))];
            let label = "ppr tile classify (separate clear)";
            self.separate_clear =
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
                    wgpu::BindGroupEntry { binding: 0, resource: b.uniforms.as_entire_binding() },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(b.depth),
                    },
                    wgpu::BindGroupEntry { binding: 2, resource: b.shapes.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 3, resource: b.visible.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 4, resource: b.block_ranges.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 5, resource: b.active_tiles.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 6, resource: b.dispatch_args.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 7, resource: b.tile_flags.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 8, resource: b.layers.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 9, resource: b.intermediate.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 10, resource: b.atlas.as_entire_binding() },
                ],
            },
        )
    }

    /// Records the classification of every tile, with `clear_tiles` the clear of the active
    /// tiles' pixels (else the clear pass must do it, after [`Self::prepare_separate_clear`]),
    /// and the indirect arguments (one dispatch). The active-tile count and the arguments
    /// must be zero beforehand: the renderer clears them in the encoder before every
    /// classification (not once per `prepare`: a second encode would append).
    pub fn encode(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        bind_group: &wgpu::BindGroup,
        viewport: [u32; 2],
        clear_tiles: bool,
    ) {
        // One workgroup per 2 × 2 tiles.
        let (x, y) = block_groups(viewport);
        pass.set_bind_group(0, bind_group, &[]);
        let classify = if clear_tiles {
            &self.classify
        } else {
            self.separate_clear.as_ref().expect("prepare_separate_clear() before encode()")
        };
        pass.set_pipeline(classify);
        pass.dispatch_workgroups(x, y, 1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Whether the packed range holds block `b`, as `tile_classify.wgsl` tests it.
    fn holds(range: u32, b: [u32; 2]) -> bool {
        let b = b.map(|v| v.min(MAX_BLOCK_COORD));
        let byte = |i: u32| (range >> (8 * i)) & 0xff;
        b[0] >= byte(0) && b[1] >= byte(1) && b[0] <= byte(2) && b[1] <= byte(3)
    }

    /// Whether the rectangle overlaps block `b`'s pixels (the test before the ranges).
    fn overlaps(r: &ScreenRect, b: [u32; 2]) -> bool {
        let lo = b.map(|v| v * BLOCK);
        r.min[0] < lo[0] + BLOCK && r.max[0] > lo[0] && r.min[1] < lo[1] + BLOCK && r.max[1] > lo[1]
    }

    proptest! {
        /// Below the clamp the range holds exactly the blocks the rectangle overlaps; past
        /// it, at least those.
        #[test]
        fn a_block_range_holds_the_blocks_its_rectangle_overlaps(
            x in 0u32..9000, y in 0u32..9000, w in 0u32..600, h in 0u32..600,
            bx in 0u32..290, by in 0u32..290,
        ) {
            let r = ScreenRect { min: [x, y], max: [x + w, y + h] };
            let range = block_range(&r);
            let b = [bx, by];
            if bx < MAX_BLOCK_COORD && by < MAX_BLOCK_COORD {
                prop_assert_eq!(holds(range, b), overlaps(&r, b), "{:?} block {:?}", r, b);
            } else if overlaps(&r, b) {
                prop_assert!(holds(range, b), "{:?} block {:?}", r, b);
            }
        }
    }

    #[test]
    fn an_empty_rectangle_holds_no_block() {
        for r in [ScreenRect { min: [40, 40], max: [40, 90] }, ScreenRect { min: [0, 0], max: [0, 0] }] {
            let range = block_range(&r);
            assert!((0..8).all(|x| (0..8).all(|y| !holds(range, [x, y]))), "{r:?}");
        }
    }
}
