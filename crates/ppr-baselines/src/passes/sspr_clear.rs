//! The SSPR hash clear (`sspr_clear.wgsl`): zeroes every layer of the projection hash.

use super::{bind_group_layout, buffer, compute_pipeline, storage_entry, uniform_entry};
use crate::gpu_types::ClearUniform;
use crate::shader;

/// Threads per workgroup, given to the WGSL as the `GROUP_SIZE` override constant.
pub const CLEAR_GROUP_SIZE: u32 = 256;
/// Workgroups per row of the dispatch grid (the limit of one dimension).
const ROW_GROUPS: u32 = 65535;

/// Zeroes the projection hash buffer.
pub struct SsprClearPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl SsprClearPass {
    /// Builds the pipeline.
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = bind_group_layout(device, "sspr clear", &[uniform_entry(0), storage_entry(1, false)]);
        let module = shader::module(device, "sspr clear", shader::SSPR_CLEAR.to_owned());
        let constants = [("GROUP_SIZE", f64::from(CLEAR_GROUP_SIZE))];
        let pipeline = compute_pipeline(device, "sspr clear", &layout, &module, "main", &constants);
        Self { pipeline, layout }
    }

    /// The uniform clearing `count` values (with the dispatch grid's row length).
    pub fn uniform(count: u32) -> ClearUniform {
        ClearUniform { count, row: ROW_GROUPS * CLEAR_GROUP_SIZE, _pad: [0; 2] }
    }

    /// The bind group over the clear uniform and the hash buffer.
    pub fn bind_group(
        &self,
        device: &wgpu::Device,
        params: &wgpu::Buffer,
        hash: &wgpu::Buffer,
    ) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sspr clear"),
            layout: &self.layout,
            entries: &[buffer(0, params), buffer(1, hash)],
        })
    }

    /// Records the clear of `count` values.
    pub fn encode(&self, pass: &mut wgpu::ComputePass<'_>, bind_group: &wgpu::BindGroup, count: u32) {
        let groups = count.div_ceil(CLEAR_GROUP_SIZE).max(1);
        let x = groups.min(ROW_GROUPS);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, groups.div_ceil(x), 1);
    }
}
