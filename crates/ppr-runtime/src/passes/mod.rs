//! The GPU passes: one struct per pass, owning its pipelines and bind-group layout.

mod bind_group_cache;
pub mod block_lists;
pub mod clear;
pub mod downsample;
pub mod layer_reflection;
pub mod projection;
pub mod reflection;
pub mod super_tile_lists;
pub mod tile_classify;
pub mod upsample;

pub use block_lists::BlockListPass;
pub use clear::ClearPass;
pub use downsample::DownsamplePass;
pub use layer_reflection::LayerReflectionPass;
pub use projection::{Ablation, BoxReduction, ProjectionPass, ProjectionVariant};
pub use reflection::ReflectionPass;
pub use super_tile_lists::SuperTileListPass;
pub use tile_classify::TileClassifyPass;
pub use upsample::UpsamplePass;

/// Workgroup edge of the 2-D per-pixel passes (16 × 16 = 256 threads), as in the WGSL.
pub const TILE: u32 = 16;

pub(crate) fn storage_entry(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

pub(crate) fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A depth (or any float) texture read with `textureLoad` only. Depth is bound as an
/// unfilterable float texture: naga's GLSL output cannot `textureLoad` depth textures.
pub(crate) fn loaded_texture_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: false },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// A float texture the pass samples (filtered: the scene colour).
pub(crate) fn sampled_texture_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: true },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// A filtering sampler.
pub(crate) fn sampler_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
        count: None,
    }
}

/// A bilinear sampler clamped to the edge.
pub(crate) fn linear_sampler(device: &wgpu::Device, label: &str) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some(label),
        address_mode_u: wgpu::AddressMode::ClampToEdge,
        address_mode_v: wgpu::AddressMode::ClampToEdge,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    })
}

/// A storage texture the pass writes.
pub(crate) fn write_texture_entry(binding: u32, format: wgpu::TextureFormat) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format,
            view_dimension: wgpu::TextureViewDimension::D2,
        },
        count: None,
    }
}

/// A compute pipeline of `entry` in the pass's WGSL, with override constants.
pub(crate) fn compute_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    module: &wgpu::ShaderModule,
    entry: &str,
    constants: &[(&str, f64)],
) -> wgpu::ComputePipeline {
    #[cfg(feature = "pipeline-log")]
    crate::pipeline_log::record_pipeline(label, module, entry, constants);
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(layout)],
        immediate_size: 0,
    });
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: Some(&pipeline_layout),
        module,
        entry_point: Some(entry),
        // Every pass writes the workgroup memory it reads before it reads it (the box slots,
        // the pass bits, the lists: `tile_test.wgsl`, `fused_lists.wgsl`,
        // `tile_classify.wgsl`), so the zeroing WebGPU asks for at every workgroup's start
        // (stores and a barrier) is left out.
        compilation_options: wgpu::PipelineCompilationOptions {
            constants,
            zero_initialize_workgroup_memory: false,
        },
        cache: None,
    })
}

/// Workgroups to cover a `width × height` viewport with [`TILE`]² tiles.
pub fn tile_groups([w, h]: [u32; 2]) -> (u32, u32) {
    (w.div_ceil(TILE), h.div_ceil(TILE))
}

/// A buffer or a range of one, to bind (a part of the frame upload is a range of its
/// buffer: `crate::upload_layout`).
#[derive(Clone, Copy, Debug)]
pub struct BufferPart<'a> {
    pub buffer: &'a wgpu::Buffer,
    pub offset: u64,
    /// `None`: to the buffer's end.
    pub size: Option<wgpu::BufferSize>,
}

impl<'a> BufferPart<'a> {
    pub fn binding(self) -> wgpu::BindingResource<'a> {
        wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer: self.buffer,
            offset: self.offset,
            size: self.size,
        })
    }
}

impl<'a> From<&'a wgpu::Buffer> for BufferPart<'a> {
    fn from(buffer: &'a wgpu::Buffer) -> Self {
        Self { buffer, offset: 0, size: None }
    }
}

/// A bind-group entry for a whole buffer or a range of one.
pub(crate) fn buffer_entry<'a>(binding: u32, buffer: impl Into<BufferPart<'a>>) -> wgpu::BindGroupEntry<'a> {
    wgpu::BindGroupEntry { binding, resource: buffer.into().binding() }
}

/// 0.0 or 1.0, as override constants take booleans.
pub(crate) fn flag(on: bool) -> f64 {
    if on { 1.0 } else { 0.0 }
}
