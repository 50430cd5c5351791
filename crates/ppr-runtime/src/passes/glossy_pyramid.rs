//! Glossy pyramid pass: the scene colour reduced to 1/2 … 1/32 of the viewport over the
//! region the frame's glossy reflections read (`crates/ppr-runtime/shaders/glossy_pyramid.wgsl`).

use super::bind_group_cache::BindGroupCache;
use super::{
    BufferPart, compute_pipeline, linear_sampler, sampled_texture_entry, sampler_entry, uniform_entry,
    write_texture_entry,
};
use crate::glossy_pyramid::{FORMAT, GlossyPyramid, LEVELS, groups};
use crate::plan::ScreenRect;

pub const WGSL: &str = include_str!("../../shaders/glossy_pyramid.wgsl");

/// What the pass reads and writes.
pub struct GlossyPyramidBindings<'a> {
    pub uniforms: BufferPart<'a>,
    /// The scene colour (the frame's full-size input).
    pub color: &'a wgpu::TextureView,
    /// The frame's glossy uniform (`GpuGlossyShapes`; the pass reads its head: the region).
    pub glossy: BufferPart<'a>,
    pub pyramid: &'a GlossyPyramid,
}

/// The glossy pyramid pass.
pub struct GlossyPyramidPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    bind_groups: BindGroupCache,
    sampler: wgpu::Sampler,
}

impl GlossyPyramidPass {
    pub fn new(device: &wgpu::Device) -> Self {
        let mut entries =
            vec![uniform_entry(0), sampled_texture_entry(1), sampler_entry(2), uniform_entry(3)];
        entries.extend((0..LEVELS).map(|level| write_texture_entry(4 + level, FORMAT)));
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr glossy pyramid"),
            entries: &entries,
        });
        let module = crate::shader::module_with(device, "ppr glossy pyramid", &[], WGSL);
        let pipeline = compute_pipeline(device, "ppr glossy pyramid", &layout, &module, "main", &[]);
        let sampler = linear_sampler(device, "ppr glossy pyramid linear", false);
        Self { pipeline, layout, bind_groups: BindGroupCache::default(), sampler }
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &GlossyPyramidBindings<'_>) -> wgpu::BindGroup {
        let view =
            |binding, v| wgpu::BindGroupEntry { binding, resource: wgpu::BindingResource::TextureView(v) };
        let mut entries = vec![
            wgpu::BindGroupEntry { binding: 0, resource: b.uniforms.binding() },
            view(1, b.color),
            wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::Sampler(&self.sampler) },
            wgpu::BindGroupEntry { binding: 3, resource: b.glossy.binding() },
        ];
        entries.extend(b.pyramid.levels.iter().zip(4..).map(|(level, binding)| view(binding, level)));
        self.bind_groups.get(
            device,
            &wgpu::BindGroupDescriptor {
                label: Some("ppr glossy pyramid"),
                layout: &self.layout,
                entries: &entries,
            },
        )
    }

    /// Records the pass over `rect` (the frame's `pyramid_rect`, in the uniform too).
    pub fn encode(&self, pass: &mut wgpu::ComputePass<'_>, bind_group: &wgpu::BindGroup, rect: ScreenRect) {
        let (x, y) = groups(rect);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}
