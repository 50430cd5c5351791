//! Clear pass: fills the intermediate buffer with the clear value (four u32 per thread).

use super::{compute_pipeline, storage_entry};

const WGSL: &str = include_str!("../../../../shaders/ppr/clear.wgsl");
/// Threads per workgroup, as in `clear.wgsl`.
const GROUP: u32 = 256;

/// The clear pass.
pub struct ClearPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl ClearPass {
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr clear"),
            entries: &[storage_entry(0, false)],
        });
        let pipeline = compute_pipeline(device, "ppr clear", &layout, WGSL);
        Self { pipeline, layout }
    }

    /// The bind group for an intermediate buffer.
    pub fn bind_group(&self, device: &wgpu::Device, intermediate: &wgpu::Buffer) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ppr clear"),
            layout: &self.layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: intermediate.as_entire_binding() }],
        })
    }

    /// Records the clear of `vec4_count` four-value groups.
    pub fn encode(&self, pass: &mut wgpu::ComputePass<'_>, bind_group: &wgpu::BindGroup, vec4_count: u32) {
        let groups = vec4_count.div_ceil(GROUP);
        let x = groups.min(65535);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, groups.div_ceil(x), 1);
    }
}
