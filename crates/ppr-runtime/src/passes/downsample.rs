//! Downsample pass of the reduced-resolution tiers: full-resolution depth to the reduced
//! size the rest of the passes run at (`crates/ppr-runtime/shaders/downsample.wgsl`).

use super::bind_group_cache::BindGroupCache;
use super::{
    BufferPart, compute_pipeline, loaded_texture_entry, tile_groups, uniform_entry, write_texture_entry,
};

pub const WGSL: &str = include_str!("../../shaders/downsample.wgsl");

/// Format of the reduced depth (read by the passes as an unfilterable float texture).
pub const REDUCED_DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

/// What the downsample pass reads and writes.
pub struct DownsampleBindings<'a> {
    /// The reduced plan's uniforms.
    pub uniforms: BufferPart<'a>,
    pub full_depth: &'a wgpu::TextureView,
    pub reduced_depth: &'a wgpu::TextureView,
}

/// The downsample pass.
pub struct DownsamplePass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    bind_groups: BindGroupCache,
}

impl DownsamplePass {
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr downsample"),
            entries: &[
                uniform_entry(0),
                loaded_texture_entry(1),
                write_texture_entry(2, REDUCED_DEPTH_FORMAT),
            ],
        });
        let module = crate::shader::module_with(device, "ppr downsample", &[crate::shader::VIEW], WGSL);
        let pipeline = compute_pipeline(device, "ppr downsample", &layout, &module, "main", &[]);
        Self { pipeline, layout, bind_groups: BindGroupCache::default() }
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &DownsampleBindings<'_>) -> wgpu::BindGroup {
        let view =
            |binding, v| wgpu::BindGroupEntry { binding, resource: wgpu::BindingResource::TextureView(v) };
        self.bind_groups.get(
            device,
            &wgpu::BindGroupDescriptor {
                label: Some("ppr downsample"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: b.uniforms.binding() },
                    view(1, b.full_depth),
                    view(2, b.reduced_depth),
                ],
            },
        )
    }

    /// Records the pass over the reduced viewport.
    pub fn encode(&self, pass: &mut wgpu::ComputePass<'_>, bind_group: &wgpu::BindGroup, reduced: [u32; 2]) {
        let (x, y) = tile_groups(reduced);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}
