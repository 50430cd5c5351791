//! Clear pass: fills the intermediate buffer (or the atlas) with the clear value, four u32
//! per thread, where the last encode did not leave it cleared.

use super::bind_group_cache::BindGroupCache;
use super::{compute_pipeline, storage_entry};

pub const WGSL: &str = include_str!("../../shaders/clear.wgsl");
/// Threads per workgroup of `clear_all`, as in `clear.wgsl`.
const GROUP: u32 = 256;

/// The buffer the clear pass writes.
pub struct ClearBindings<'a> {
    pub intermediate: &'a wgpu::Buffer,
}

/// The clear pass.
pub struct ClearPass {
    all: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    bind_groups: BindGroupCache,
}

impl ClearPass {
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr clear"),
            entries: &[storage_entry(0, false)],
        });
        let module = crate::shader::module(device, "ppr clear", WGSL);
        Self {
            all: compute_pipeline(device, "ppr clear", &layout, &module, "clear_all", &[]),
            layout,
            bind_groups: BindGroupCache::default(),
        }
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &ClearBindings<'_>) -> wgpu::BindGroup {
        self.bind_groups.get(
            device,
            &wgpu::BindGroupDescriptor {
                label: Some("ppr clear"),
                layout: &self.layout,
                entries: &[wgpu::BindGroupEntry { binding: 0, resource: b.intermediate.as_entire_binding() }],
            },
        )
    }

    /// Records the clear of the whole buffer (`vec4_count` four-value groups).
    pub fn encode_all(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        bind_group: &wgpu::BindGroup,
        vec4_count: u32,
    ) {
        let groups = vec4_count.div_ceil(GROUP);
        let x = groups.min(65535);
        pass.set_pipeline(&self.all);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, groups.div_ceil(x), 1);
    }
}
