//! The forward pass's bind-group layouts, shared by the pass and the meshes it draws.

/// Bind-group layouts of the forward pass: view (0), material (1), draw (2).
pub struct ForwardLayouts {
    pub view: wgpu::BindGroupLayout,
    pub material: wgpu::BindGroupLayout,
    pub draw: wgpu::BindGroupLayout,
}

impl ForwardLayouts {
    pub(crate) fn new(device: &wgpu::Device) -> Self {
        let uniform = |binding, dynamic| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: dynamic,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = |label, entries: &[wgpu::BindGroupLayoutEntry]| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries })
        };
        Self {
            view: layout("walkthrough forward: view", &[uniform(0, false)]),
            material: layout(
                "walkthrough forward: material",
                &[
                    uniform(0, false),
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
            ),
            draw: layout("walkthrough forward: draw", &[uniform(0, true)]),
        }
    }
}
