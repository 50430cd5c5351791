//! The G-buffer textures of one view: colour, depth, world normal and reflector id.

/// Format of the linear HDR colour target (what the runtime reads).
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Format of the depth target (what the runtime reads).
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Format of the world-normal target (xyz: unit normal, w: 1 where geometry was drawn).
pub const NORMAL_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Format of the reflector-id target (0: none, i + 1: reflector i).
pub const REFLECTOR_ID_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

/// One texture and its default view.
pub struct Target {
    /// The texture.
    pub texture: wgpu::Texture,
    /// A view of the whole texture (depth-only for the depth target).
    pub view: wgpu::TextureView,
}

impl Target {
    /// A 2D texture of `size` with the given format and usage.
    pub fn new(
        device: &wgpu::Device,
        label: &str,
        size: [u32; 2],
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
    ) -> Self {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        });
        let aspect = if format.is_depth_stencil_format() {
            wgpu::TextureAspect::DepthOnly
        } else {
            wgpu::TextureAspect::All
        };
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some(label),
            aspect,
            ..Default::default()
        });
        Self { texture, view }
    }
}

/// The render targets of the scene raster for one view; all can be sampled and copied.
pub struct GBuffer {
    /// Width and height in pixels.
    pub size: [u32; 2],
    /// Linear HDR colour ([`COLOR_FORMAT`]).
    pub color: Target,
    /// Depth ([`DEPTH_FORMAT`]), standard or reversed as the camera's projection says.
    pub depth: Target,
    /// World normal ([`NORMAL_FORMAT`]).
    pub normal: Target,
    /// Reflector id ([`REFLECTOR_ID_FORMAT`]).
    pub reflector_id: Target,
}

impl GBuffer {
    /// Allocates the targets; `label` prefixes the texture labels.
    pub fn new(device: &wgpu::Device, size: [u32; 2], label: &str) -> Self {
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC;
        let size = [size[0].max(1), size[1].max(1)];
        Self {
            size,
            color: Target::new(device, &format!("{label}: colour"), size, COLOR_FORMAT, usage),
            depth: Target::new(device, &format!("{label}: depth"), size, DEPTH_FORMAT, usage),
            normal: Target::new(device, &format!("{label}: normal"), size, NORMAL_FORMAT, usage),
            reflector_id: Target::new(
                device,
                &format!("{label}: reflector id"),
                size,
                REFLECTOR_ID_FORMAT,
                usage,
            ),
        }
    }
}
