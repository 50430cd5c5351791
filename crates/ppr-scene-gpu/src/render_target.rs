//! One 2D texture with its default view, and the formats every scene raster writes and
//! the runtime reads.

/// Format of the linear HDR colour target (what the runtime reflects).
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Format of the depth target (what the runtime reads).
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// One texture and its default view.
pub struct Target {
    /// The texture.
    pub texture: wgpu::Texture,
    /// A view of the whole texture (depth-only for a depth format).
    pub view: wgpu::TextureView,
}

impl Target {
    /// A 2D texture of `size` with the given format and usage.
    pub fn new(
        device: &wgpu::Device,
        label: &str,
        [width, height]: [u32; 2],
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
    ) -> Self {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        });
        let aspect =
            if format.has_depth_aspect() { wgpu::TextureAspect::DepthOnly } else { wgpu::TextureAspect::All };
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some(label),
            aspect,
            ..Default::default()
        });
        Self { texture, view }
    }
}
