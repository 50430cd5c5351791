//! The GPU passes of the baselines: one struct per pass, owning its pipeline and
//! bind-group layout (built once in `new`); `encode` only records.

pub mod hiz_build;
pub mod hiz_trace;
pub mod sspr_clear;
pub mod sspr_project;
pub mod sspr_resolve;
pub mod ssr_glossy_blur;
pub mod ssr_march;
pub mod texture_copy;

pub use hiz_build::HiZBuildPass;
pub use hiz_trace::HiZTracePass;
pub use sspr_clear::SsprClearPass;
pub use sspr_project::SsprProjectPass;
pub use sspr_resolve::SsprResolvePass;
pub use ssr_glossy_blur::SsrGlossyBlurPass;
pub use ssr_march::{MarchAlpha, SsrMarchPass};
pub use texture_copy::TextureCopyPass;

/// Workgroup edge of the per-pixel passes (8 × 8 threads), given to the WGSL as the
/// `GROUP_EDGE` override constant.
pub const GROUP_EDGE: u32 = 8;

/// Format of every pass's reflection output.
pub const OUTPUT_FORMAT: wgpu::TextureFormat = ppr_testbed::technique::REFLECTION_FORMAT;

/// Workgroups covering a `width × height` viewport with [`GROUP_EDGE`]² tiles.
pub fn pixel_groups([w, h]: [u32; 2]) -> (u32, u32) {
    (w.div_ceil(GROUP_EDGE), h.div_ceil(GROUP_EDGE))
}

/// The override constants of a per-pixel pass.
pub(crate) fn pixel_constants() -> [(&'static str, f64); 1] {
    [("GROUP_EDGE", f64::from(GROUP_EDGE))]
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

/// A float texture read with `textureLoad` only. Depth is bound this way too, as an
/// unfilterable float texture: naga's GLSL output cannot `textureLoad` depth textures.
pub(crate) fn float_texture_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    texture_entry(binding, wgpu::TextureSampleType::Float { filterable: false })
}

/// A `u32` texture (reflector ids).
pub(crate) fn uint_texture_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    texture_entry(binding, wgpu::TextureSampleType::Uint)
}

fn texture_entry(binding: u32, sample_type: wgpu::TextureSampleType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Texture {
            sample_type,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// A write-only storage texture of `format`.
pub(crate) fn storage_texture_entry(binding: u32, format: wgpu::TextureFormat) -> wgpu::BindGroupLayoutEntry {
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

/// A read-write storage texture of `format`.
pub(crate) fn read_write_storage_texture_entry(
    binding: u32,
    format: wgpu::TextureFormat,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::ReadWrite,
            format,
            view_dimension: wgpu::TextureViewDimension::D2,
        },
        count: None,
    }
}

pub(crate) fn buffer(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource: buffer.as_entire_binding() }
}

pub(crate) fn view(binding: u32, view: &wgpu::TextureView) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource: wgpu::BindingResource::TextureView(view) }
}

/// A bind-group layout over `entries`.
pub(crate) fn bind_group_layout(
    device: &wgpu::Device,
    label: &str,
    entries: &[wgpu::BindGroupLayoutEntry],
) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries })
}

/// A compute pipeline of `entry` in `module`, with override constants.
pub(crate) fn compute_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    module: &wgpu::ShaderModule,
    entry: &str,
    constants: &[(&str, f64)],
) -> wgpu::ComputePipeline {
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
        compilation_options: wgpu::PipelineCompilationOptions { constants, ..Default::default() },
        cache: None,
    })
}
