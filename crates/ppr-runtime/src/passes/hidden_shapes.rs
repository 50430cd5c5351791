//! Hidden-shape pass: finds the projection's tests whose reflector no pixel shows (behind
//! nearer walls at every pixel of its screen rectangle) and empties their source boxes, so
//! that the projection and its lists skip them (`shaders/hidden_shapes.wgsl`).

use super::projection::block_groups;
use super::{buffer_entry, compute_pipeline, flag, loaded_texture_entry, storage_entry, uniform_entry};

pub const WGSL: &str = include_str!("../../shaders/hidden_shapes.wgsl");

/// The `hidden_rects` entry of a test that is never skipped (a parallel tree).
pub const KEEP_RECT: [u32; 4] = [u32::MAX; 4];

/// Buffers and views the pass reads and writes.
pub struct HiddenShapeBindings<'a> {
    pub uniforms: &'a wgpu::Buffer,
    pub depth: &'a wgpu::TextureView,
    pub shapes: &'a wgpu::Buffer,
    /// Per test, its planes (`ShapeTest`).
    pub tests: &'a wgpu::Buffer,
    pub layers: &'a wgpu::Buffer,
    /// Per test, the screen rectangle its writes land in ([`KEEP_RECT`]: never skipped).
    pub hidden_rects: &'a wgpu::Buffer,
    /// Per test, whether some pixel may show it (cleared before the pass).
    pub seen: &'a wgpu::Buffer,
    /// Per test, its source box: emptied for the tests no pixel shows.
    pub source_boxes: &'a wgpu::Buffer,
}

/// The hidden-shape pass.
pub struct HiddenShapePass {
    /// `mark` without and with layers.
    mark: [wgpu::ComputePipeline; 2],
    apply: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl HiddenShapePass {
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr hidden shapes"),
            entries: &[
                uniform_entry(0),
                loaded_texture_entry(1),
                storage_entry(2, true),
                storage_entry(3, true),
                storage_entry(4, true),
                storage_entry(5, true),
                storage_entry(6, false),
                storage_entry(7, false),
            ],
        });
        let module = crate::shader::module_with(
            device,
            "ppr hidden shapes",
            &[crate::shader::VIEW, crate::shader::TILE_TEST],
            WGSL,
        );
        let mark = [false, true].map(|layers| {
            compute_pipeline(
                device,
                "ppr hidden shapes",
                &layout,
                &module,
                "mark",
                &[("LAYERS", flag(layers))],
            )
        });
        let apply = compute_pipeline(device, "ppr hidden shapes (apply)", &layout, &module, "apply", &[]);
        Self { mark, apply, layout }
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &HiddenShapeBindings<'_>) -> wgpu::BindGroup {
        let entry = buffer_entry;
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ppr hidden shapes"),
            layout: &self.layout,
            entries: &[
                entry(0, b.uniforms),
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(b.depth) },
                entry(2, b.shapes),
                entry(3, b.tests),
                entry(4, b.layers),
                entry(5, b.hidden_rects),
                entry(6, b.seen),
                entry(7, b.source_boxes),
            ],
        })
    }

    /// Records both dispatches (the blocks of the viewport, then one invocation per test)
    /// into `pass`; `seen` must have been cleared before it.
    pub fn encode(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        bind_group: &wgpu::BindGroup,
        viewport: [u32; 2],
        tests: u32,
        layers: bool,
    ) {
        let (x, y) = block_groups(viewport);
        pass.set_bind_group(0, bind_group, &[]);
        pass.set_pipeline(&self.mark[usize::from(layers)]);
        pass.dispatch_workgroups(x, y, 1);
        pass.set_pipeline(&self.apply);
        pass.dispatch_workgroups(tests.div_ceil(64), 1, 1);
    }
}
