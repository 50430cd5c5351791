//! Copies a float texture into a reflection output (`texture_copy.wgsl`): a compute pass,
//! so it works on outputs with only `STORAGE_BINDING` and is timed like the others.

use super::{
    OUTPUT_FORMAT, bind_group_layout, compute_pipeline, float_texture_entry, pixel_constants, pixel_groups,
    storage_texture_entry, view,
};
use crate::shader;

/// Copies a same-sized texture into the output, texel for texel.
pub struct TextureCopyPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl TextureCopyPass {
    /// Builds the pipeline.
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = bind_group_layout(
            device,
            "texture copy",
            &[float_texture_entry(0), storage_texture_entry(1, OUTPUT_FORMAT)],
        );
        let module = shader::module(device, "texture copy", shader::TEXTURE_COPY.to_owned());
        let pipeline = compute_pipeline(device, "texture copy", &layout, &module, "main", &pixel_constants());
        Self { pipeline, layout }
    }

    /// The bind group copying `source` into `output`.
    pub fn bind_group(
        &self,
        device: &wgpu::Device,
        source: &wgpu::TextureView,
        output: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("texture copy"),
            layout: &self.layout,
            entries: &[view(0, source), view(1, output)],
        })
    }

    /// Records the copy over a `size` viewport.
    pub fn encode(&self, pass: &mut wgpu::ComputePass<'_>, bind_group: &wgpu::BindGroup, size: [u32; 2]) {
        let (x, y) = pixel_groups(size);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}
