//! The SSPR resolve pass (`sspr_resolve.wgsl`): reflector pixels decode their plane's
//! hash and take the source pixel's colour.

use super::{
    OUTPUT_FORMAT, bind_group_layout, buffer, compute_pipeline, float_texture_entry, pixel_constants,
    pixel_groups, storage_entry, storage_texture_entry, uint_texture_entry, uniform_entry, view,
};
use crate::shader;

/// What the resolve reads and writes.
pub struct SsprResolveBindings<'a> {
    /// `BaselineFrame` uniform.
    pub frame: &'a wgpu::Buffer,
    /// Reflector planes (with their layer), indexed by reflector id − 1.
    pub planes: &'a wgpu::Buffer,
    /// Reflector id per pixel.
    pub reflector_id: &'a wgpu::TextureView,
    /// Scene colour.
    pub color: &'a wgpu::TextureView,
    /// The projection hash.
    pub hash: &'a wgpu::Buffer,
    /// Reflection output.
    pub output: &'a wgpu::TextureView,
}

/// Turns the projection hash into the reflection.
pub struct SsprResolvePass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl SsprResolvePass {
    /// Builds the pipeline.
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = bind_group_layout(
            device,
            "sspr resolve",
            &[
                uniform_entry(0),
                storage_entry(1, true),
                uint_texture_entry(2),
                float_texture_entry(3),
                storage_entry(4, true),
                storage_texture_entry(5, OUTPUT_FORMAT),
            ],
        );
        let module = shader::module(device, "sspr resolve", shader::with_common(shader::SSPR_RESOLVE));
        let pipeline = compute_pipeline(device, "sspr resolve", &layout, &module, "main", &pixel_constants());
        Self { pipeline, layout }
    }

    /// The bind group over `b`.
    pub fn bind_group(&self, device: &wgpu::Device, b: &SsprResolveBindings<'_>) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sspr resolve"),
            layout: &self.layout,
            entries: &[
                buffer(0, b.frame),
                buffer(1, b.planes),
                view(2, b.reflector_id),
                view(3, b.color),
                buffer(4, b.hash),
                view(5, b.output),
            ],
        })
    }

    /// Records the resolve over a `size` viewport.
    pub fn encode(&self, pass: &mut wgpu::ComputePass<'_>, bind_group: &wgpu::BindGroup, size: [u32; 2]) {
        let (x, y) = pixel_groups(size);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}
