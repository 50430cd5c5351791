//! The Hi-Z pyramid build (`hiz_build.wgsl`): linear depth into level 0, then one 2 × 2
//! min-downsample dispatch per level, all in one compute pass (wgpu puts a barrier
//! between dispatches that use the atlas as a read-write storage texture).

use super::{
    bind_group_layout, buffer, compute_pipeline, float_texture_entry, pixel_constants, pixel_groups,
    read_write_storage_texture_entry, storage_texture_entry, uniform_entry, view,
};
use crate::hiz_pyramid::{HIZ_FORMAT, HiZPyramid};
use crate::shader;

/// Builds a [`HiZPyramid`] from a depth buffer.
pub struct HiZBuildPass {
    linearize: wgpu::ComputePipeline,
    downsample: wgpu::ComputePipeline,
    level0_layout: wgpu::BindGroupLayout,
    downsample_layout: wgpu::BindGroupLayout,
}

impl HiZBuildPass {
    /// Builds the two pipelines.
    pub fn new(device: &wgpu::Device) -> Self {
        let level0_layout = bind_group_layout(
            device,
            "hi-z build: level 0",
            &[uniform_entry(0), float_texture_entry(1), storage_texture_entry(2, HIZ_FORMAT)],
        );
        let downsample_layout = bind_group_layout(
            device,
            "hi-z build: downsample",
            &[uniform_entry(3), uniform_entry(4), read_write_storage_texture_entry(5, HIZ_FORMAT)],
        );
        let module = shader::module(device, "hi-z build", shader::with_hiz_layout(shader::HIZ_BUILD));
        let constants = pixel_constants();
        Self {
            linearize: compute_pipeline(
                device,
                "hi-z build: level 0",
                &level0_layout,
                &module,
                "linearize",
                &constants,
            ),
            downsample: compute_pipeline(
                device,
                "hi-z build: downsample",
                &downsample_layout,
                &module,
                "downsample",
                &constants,
            ),
            level0_layout,
            downsample_layout,
        }
    }

    /// The bind group of level 0: the frame uniform, the depth buffer and the pyramid.
    pub fn level0_bind_group(
        &self,
        device: &wgpu::Device,
        frame: &wgpu::Buffer,
        depth: &wgpu::TextureView,
        pyramid: &HiZPyramid,
    ) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("hi-z build: level 0"),
            layout: &self.level0_layout,
            entries: &[buffer(0, frame), view(1, depth), view(2, pyramid.view())],
        })
    }

    /// The bind group building one level: the pyramid's `HiZLevels` uniform, the level's
    /// `DownsampleParams` uniform and the atlas.
    pub fn downsample_bind_group(
        &self,
        device: &wgpu::Device,
        levels: &wgpu::Buffer,
        level: &wgpu::Buffer,
        atlas: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("hi-z build: downsample"),
            layout: &self.downsample_layout,
            entries: &[buffer(3, levels), buffer(4, level), view(5, atlas)],
        })
    }

    /// Records the whole build into `pass`: level 0, then every further level.
    pub fn encode(&self, pass: &mut wgpu::ComputePass<'_>, level0: &wgpu::BindGroup, pyramid: &HiZPyramid) {
        let (x, y) = pixel_groups(pyramid.size());
        pass.set_pipeline(&self.linearize);
        pass.set_bind_group(0, level0, &[]);
        pass.dispatch_workgroups(x, y, 1);
        pass.set_pipeline(&self.downsample);
        for (l, group) in (1..).zip(pyramid.downsample_groups()) {
            let (x, y) = pixel_groups(HiZPyramid::level_size(pyramid.size(), l));
            pass.set_bind_group(0, group, &[]);
            pass.dispatch_workgroups(x, y, 1);
        }
    }
}
