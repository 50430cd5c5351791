//! The ray-march pass of brute-force and low-quality SSR (`ssr_march.wgsl`).

use super::{
    OUTPUT_FORMAT, bind_group_layout, buffer, compute_pipeline, float_texture_entry, pixel_constants,
    pixel_groups, storage_entry, storage_texture_entry, uint_texture_entry, uniform_entry, view,
};
use crate::shader;

/// What the march reads and writes.
pub struct SsrMarchBindings<'a> {
    /// `BaselineFrame` uniform.
    pub frame: &'a wgpu::Buffer,
    /// `SsrParams` uniform.
    pub params: &'a wgpu::Buffer,
    /// Reflector planes, indexed by reflector id − 1.
    pub planes: &'a wgpu::Buffer,
    /// Scene depth.
    pub depth: &'a wgpu::TextureView,
    /// Reflector id per pixel.
    pub reflector_id: &'a wgpu::TextureView,
    /// Scene colour.
    pub color: &'a wgpu::TextureView,
    /// Reflection output.
    pub output: &'a wgpu::TextureView,
}

/// What the march writes in the alpha of a found reflection.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MarchAlpha {
    /// 1: the technique's output as it is.
    #[default]
    Found,
    /// The distance from the reflector to the hit, metres (for a roughness blur).
    HitDistance,
}

/// Marches one reflection ray per reflector pixel and writes the colour it hits.
pub struct SsrMarchPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl SsrMarchPass {
    /// Builds the pipeline (alpha 1 where a reflection was found).
    pub fn new(device: &wgpu::Device) -> Self {
        Self::with_alpha(device, MarchAlpha::Found)
    }

    /// Builds the pipeline writing `alpha` where a reflection was found.
    pub fn with_alpha(device: &wgpu::Device, alpha: MarchAlpha) -> Self {
        let layout = bind_group_layout(
            device,
            "ssr march",
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
        let module = shader::module(device, "ssr march", shader::with_common(shader::SSR_MARCH));
        let [group] = pixel_constants();
        let hit_distance = ("OUTPUT_HIT_DISTANCE", if alpha == MarchAlpha::HitDistance { 1.0 } else { 0.0 });
        let pipeline =
            compute_pipeline(device, "ssr march", &layout, &module, "main", &[group, hit_distance]);
        Self { pipeline, layout }
    }

    /// The bind group over `b`.
    pub fn bind_group(&self, device: &wgpu::Device, b: &SsrMarchBindings<'_>) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ssr march"),
            layout: &self.layout,
            entries: &[
                buffer(0, b.frame),
                buffer(1, b.params),
                buffer(2, b.planes),
                view(3, b.depth),
                view(4, b.reflector_id),
                view(5, b.color),
                view(6, b.output),
            ],
        })
    }

    /// Records the march over a `size` viewport.
    pub fn encode(&self, pass: &mut wgpu::ComputePass<'_>, bind_group: &wgpu::BindGroup, size: [u32; 2]) {
        let (x, y) = pixel_groups(size);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}
