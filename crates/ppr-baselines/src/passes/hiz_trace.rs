//! The Hi-Z trace pass (`hiz_trace.wgsl`): one reflection ray per reflector pixel walked
//! through the [`crate::HiZPyramid`].

use super::{
    OUTPUT_FORMAT, bind_group_layout, buffer, compute_pipeline, float_texture_entry, pixel_constants,
    pixel_groups, storage_entry, storage_texture_entry, uint_texture_entry, uniform_entry, view,
};
use crate::shader;

/// What the trace reads and writes.
pub struct HiZTraceBindings<'a> {
    /// `BaselineFrame` uniform.
    pub frame: &'a wgpu::Buffer,
    /// `HiZParams` uniform.
    pub params: &'a wgpu::Buffer,
    /// Reflector planes, indexed by reflector id − 1.
    pub planes: &'a wgpu::Buffer,
    /// The pyramid's atlas.
    pub pyramid: &'a wgpu::TextureView,
    /// The pyramid's `HiZLevels` uniform.
    pub levels: &'a wgpu::Buffer,
    /// Scene depth.
    pub depth: &'a wgpu::TextureView,
    /// Reflector id per pixel.
    pub reflector_id: &'a wgpu::TextureView,
    /// Scene colour.
    pub color: &'a wgpu::TextureView,
    /// Reflection output.
    pub output: &'a wgpu::TextureView,
}

/// Traces one reflection ray per reflector pixel through the pyramid.
pub struct HiZTracePass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl HiZTracePass {
    /// Builds the pipeline.
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = bind_group_layout(
            device,
            "hi-z trace",
            &[
                uniform_entry(0),
                uniform_entry(1),
                storage_entry(2, true),
                float_texture_entry(3),
                float_texture_entry(4),
                uint_texture_entry(5),
                float_texture_entry(6),
                storage_texture_entry(7, OUTPUT_FORMAT),
                uniform_entry(8),
            ],
        );
        let module = shader::module(device, "hi-z trace", shader::with_hiz_layout(shader::HIZ_TRACE));
        let pipeline = compute_pipeline(device, "hi-z trace", &layout, &module, "main", &pixel_constants());
        Self { pipeline, layout }
    }

    /// The bind group over `b`.
    pub fn bind_group(&self, device: &wgpu::Device, b: &HiZTraceBindings<'_>) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("hi-z trace"),
            layout: &self.layout,
            entries: &[
                buffer(0, b.frame),
                buffer(1, b.params),
                buffer(2, b.planes),
                view(3, b.pyramid),
                view(4, b.depth),
                view(5, b.reflector_id),
                view(6, b.color),
                view(7, b.output),
                buffer(8, b.levels),
            ],
        })
    }

    /// Records the trace over a `size` viewport.
    pub fn encode(&self, pass: &mut wgpu::ComputePass<'_>, bind_group: &wgpu::BindGroup, size: [u32; 2]) {
        let (x, y) = pixel_groups(size);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}
