//! The bind-group layouts every scene raster pass shares: view, material and draw.

/// Bind-group layouts of the scene raster (group 0 view, group 1 material, group 2 draw).
///
/// Made once per device and shared by [`crate::GBufferPass`], [`crate::LevelMeshes`] and
/// [`crate::ViewBindings`], so bind groups made by one fit the pipelines of the other.
pub struct SceneLayouts {
    /// Group 0: the view uniform (dynamic offset) and the reflector shapes (storage).
    pub view: wgpu::BindGroupLayout,
    /// Group 1: material uniform, base colour texture and its sampler.
    pub material: wgpu::BindGroupLayout,
    /// Group 2: the per-draw uniform (dynamic offset).
    pub draw: wgpu::BindGroupLayout,
}

impl SceneLayouts {
    /// Creates the three layouts.
    pub fn new(device: &wgpu::Device) -> Self {
        let vf = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let view = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("scene raster: view layout"),
            entries: &[
                uniform_entry(0, vf, true),
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: true },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
            ],
        });
        let material = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("scene raster: material layout"),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::FRAGMENT, false),
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let draw = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("scene raster: draw layout"),
            entries: &[uniform_entry(0, vf, true)],
        });
        Self { view, material, draw }
    }
}

fn uniform_entry(binding: u32, visibility: wgpu::ShaderStages, dynamic: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: dynamic,
            min_binding_size: None,
        },
        count: None,
    }
}

/// `size` rounded up to the device's uniform offset alignment (the stride of dynamic slots).
pub fn uniform_stride(device: &wgpu::Device, size: usize) -> u64 {
    let align = u64::from(device.limits().min_uniform_buffer_offset_alignment.max(16));
    (size as u64).div_ceil(align) * align
}
