//! ssr-glossy's roughness blur (`ssr_glossy_blur.wgsl`): the march's reflection gathered
//! over a disc sized by the reflector's alpha and the hit distance.

use super::{
    OUTPUT_FORMAT, bind_group_layout, buffer, compute_pipeline, float_texture_entry, pixel_constants,
    pixel_groups, storage_entry, storage_texture_entry, uint_texture_entry, uniform_entry, view,
};
use crate::shader;

/// What the blur reads and writes.
pub struct SsrGlossyBlurBindings<'a> {
    /// `BaselineFrame` uniform.
    pub frame: &'a wgpu::Buffer,
    /// `GlossyBlurParams` uniform.
    pub params: &'a wgpu::Buffer,
    /// GGX alpha per reflector (`f32`, indexed by reflector id − 1).
    pub alphas: &'a wgpu::Buffer,
    /// Scene depth.
    pub depth: &'a wgpu::TextureView,
    /// Reflector id per pixel.
    pub reflector_id: &'a wgpu::TextureView,
    /// The march's reflection, alpha = hit distance ([`super::MarchAlpha::HitDistance`]).
    pub march: &'a wgpu::TextureView,
    /// Reflection output.
    pub output: &'a wgpu::TextureView,
}

/// Blurs the marched reflection of rough reflectors.
pub struct SsrGlossyBlurPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl SsrGlossyBlurPass {
    /// Builds the pipeline.
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = bind_group_layout(
            device,
            "ssr glossy blur",
            &[
                uniform_entry(0),
                uniform_entry(1),
                storage_entry(2, true),
                float_texture_entry(3),
                uint_texture_entry(4),
                float_texture_entry(5),
                storage_texture_entry(6, OUTPUT_FORMAT),
            ],
        );
        let module = shader::module(device, "ssr glossy blur", shader::with_common(shader::SSR_GLOSSY_BLUR));
        let pipeline =
            compute_pipeline(device, "ssr glossy blur", &layout, &module, "main", &pixel_constants());
        Self { pipeline, layout }
    }

    /// The bind group over `b`.
    pub fn bind_group(&self, device: &wgpu::Device, b: &SsrGlossyBlurBindings<'_>) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ssr glossy blur"),
            layout: &self.layout,
            entries: &[
                buffer(0, b.frame),
                buffer(1, b.params),
                buffer(2, b.alphas),
                view(3, b.depth),
                view(4, b.reflector_id),
                view(5, b.march),
                view(6, b.output),
            ],
        })
    }

    /// Records the blur over a `size` viewport.
    pub fn encode(&self, pass: &mut wgpu::ComputePass<'_>, bind_group: &wgpu::BindGroup, size: [u32; 2]) {
        let (x, y) = pixel_groups(size);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}
