//! Projection pass: mirror every pixel against the visible reflectors and `atomicMin` the
//! encoded offset into the intermediate buffer.

use super::{compute_pipeline, storage_entry, tile_groups, uniform_entry};

const WGSL: &str = include_str!("../../../../shaders/ppr/projection.wgsl");

/// Buffers and views the projection pass reads and writes.
pub struct ProjectionBindings<'a> {
    pub uniforms: &'a wgpu::Buffer,
    pub depth: &'a wgpu::TextureView,
    pub shapes: &'a wgpu::Buffer,
    pub visible: &'a wgpu::Buffer,
    pub occluders: &'a wgpu::Buffer,
    pub intermediate: &'a wgpu::Buffer,
}

/// The projection pass.
pub struct ProjectionPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl ProjectionPass {
    pub fn new(device: &wgpu::Device) -> Self {
        let depth = wgpu::BindGroupLayoutEntry {
            binding: 1,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Texture {
                // A depth texture bound as unfilterable float: naga's GLSL output cannot
                // `textureLoad` from depth textures, and the pass only loads.
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr projection"),
            entries: &[
                uniform_entry(0),
                depth,
                storage_entry(2, true),
                storage_entry(3, true),
                storage_entry(4, true),
                storage_entry(5, false),
            ],
        });
        let pipeline = compute_pipeline(device, "ppr projection", &layout, WGSL);
        Self { pipeline, layout }
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &ProjectionBindings<'_>) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ppr projection"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: b.uniforms.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(b.depth) },
                wgpu::BindGroupEntry { binding: 2, resource: b.shapes.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 3, resource: b.visible.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 4, resource: b.occluders.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 5, resource: b.intermediate.as_entire_binding() },
            ],
        })
    }

    pub fn encode(&self, pass: &mut wgpu::ComputePass<'_>, bind_group: &wgpu::BindGroup, viewport: [u32; 2]) {
        let (x, y) = tile_groups(viewport);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}
