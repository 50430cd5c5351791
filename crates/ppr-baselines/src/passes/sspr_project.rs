//! The SSPR projection pass (`sspr_project.wgsl`): every pixel above a layered plane
//! writes its hash `y << 16 | x` with `atomicMax` where its mirror image projects.

use super::{
    bind_group_layout, buffer, compute_pipeline, float_texture_entry, pixel_constants, pixel_groups,
    storage_entry, uniform_entry, view,
};
use crate::shader;

/// What the projection reads and writes.
pub struct SsprProjectBindings<'a> {
    /// `BaselineFrame` uniform.
    pub frame: &'a wgpu::Buffer,
    /// `SsprParams` uniform.
    pub params: &'a wgpu::Buffer,
    /// One plane per hash layer.
    pub layers: &'a wgpu::Buffer,
    /// Scene depth.
    pub depth: &'a wgpu::TextureView,
    /// The projection hash (one `u32` per pixel per layer, cleared to 0).
    pub hash: &'a wgpu::Buffer,
}

/// Scatters every pixel's hash to where its mirror image lands.
pub struct SsprProjectPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl SsprProjectPass {
    /// Builds the pipeline.
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = bind_group_layout(
            device,
            "sspr project",
            &[
                uniform_entry(0),
                uniform_entry(1),
                storage_entry(2, true),
                float_texture_entry(3),
                storage_entry(4, false),
            ],
        );
        let module = shader::module(device, "sspr project", shader::with_common(shader::SSPR_PROJECT));
        let pipeline = compute_pipeline(device, "sspr project", &layout, &module, "main", &pixel_constants());
        Self { pipeline, layout }
    }

    /// The bind group over `b`.
    pub fn bind_group(&self, device: &wgpu::Device, b: &SsprProjectBindings<'_>) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sspr project"),
            layout: &self.layout,
            entries: &[
                buffer(0, b.frame),
                buffer(1, b.params),
                buffer(2, b.layers),
                view(3, b.depth),
                buffer(4, b.hash),
            ],
        })
    }

    /// Records the projection over a `size` viewport.
    pub fn encode(&self, pass: &mut wgpu::ComputePass<'_>, bind_group: &wgpu::BindGroup, size: [u32; 2]) {
        let (x, y) = pixel_groups(size);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}
