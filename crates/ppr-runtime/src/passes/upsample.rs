//! Upsample pass of the reduced-resolution tiers: the reduced reflection (and layer
//! reflection) to the full-resolution outputs, edge-aware (`crates/ppr-runtime/shaders/upsample.wgsl`).

use super::bind_group_cache::BindGroupCache;
use super::reflection::OUTPUT_FORMAT;
use super::{
    BufferPart, TILE, compute_pipeline, flag, loaded_texture_entry, storage_entry, uniform_entry,
    write_texture_entry,
};

pub const WGSL: &str = include_str!("../../shaders/upsample.wgsl");

/// What the upsample pass reads and writes.
pub struct UpsampleBindings<'a> {
    /// The reduced plan's uniforms.
    pub uniforms: BufferPart<'a>,
    pub full_depth: &'a wgpu::TextureView,
    pub reduced_depth: &'a wgpu::TextureView,
    pub reduced_output: &'a wgpu::TextureView,
    pub output: &'a wgpu::TextureView,
    /// The reduced plan's tile flags (read with indirect dispatch).
    pub tile_flags: &'a wgpu::Buffer,
}

/// The upsample pass.
pub struct UpsamplePass {
    /// Pipelines by (indirect, layers).
    pipelines: [[wgpu::ComputePipeline; 2]; 2],
    layout: wgpu::BindGroupLayout,
    bind_groups: BindGroupCache,
}

impl UpsamplePass {
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr upsample"),
            entries: &[
                uniform_entry(0),
                loaded_texture_entry(1),
                loaded_texture_entry(2),
                loaded_texture_entry(3),
                write_texture_entry(4, OUTPUT_FORMAT),
                storage_entry(5, true),
            ],
        });
        let module = crate::shader::module_with(device, "ppr upsample", &[crate::shader::VIEW], WGSL);
        let pipeline = |indirect: bool, layers: bool| {
            let label = format!("ppr upsample indirect={indirect} layers={layers}");
            let constants = [("INDIRECT", flag(indirect)), ("LAYERS", flag(layers))];
            compute_pipeline(device, &label, &layout, &module, "main", &constants)
        };
        let pipelines =
            [[pipeline(false, false), pipeline(false, true)], [pipeline(true, false), pipeline(true, true)]];
        Self { pipelines, layout, bind_groups: BindGroupCache::default() }
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &UpsampleBindings<'_>) -> wgpu::BindGroup {
        let view =
            |binding, v| wgpu::BindGroupEntry { binding, resource: wgpu::BindingResource::TextureView(v) };
        self.bind_groups.get(
            device,
            &wgpu::BindGroupDescriptor {
                label: Some("ppr upsample"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: b.uniforms.binding() },
                    view(1, b.full_depth),
                    view(2, b.reduced_depth),
                    view(3, b.reduced_output),
                    view(4, b.output),
                    wgpu::BindGroupEntry { binding: 5, resource: b.tile_flags.as_entire_binding() },
                ],
            },
        )
    }

    /// Records the pass over `pixels` output pixels (the whole output, or with `layers`
    /// the layer rectangle's pixels at full resolution plus a margin).
    pub fn encode(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        bind_group: &wgpu::BindGroup,
        pixels: [u32; 2],
        indirect: bool,
        layers: bool,
    ) {
        pass.set_pipeline(&self.pipelines[usize::from(indirect)][usize::from(layers)]);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(pixels[0].div_ceil(TILE), pixels[1].div_ceil(TILE), 1);
    }
}
