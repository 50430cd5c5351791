//! The G-buffer textures of one view: colour, depth, world normal and reflector id.

/// The colour and depth formats (what the runtime reads) and the texture-with-view type
/// are `ppr-scene-gpu`'s, shared with the walkthrough.
pub use ppr_scene_gpu::{COLOR_FORMAT, DEPTH_FORMAT, Target};

/// Format of the world-normal target (xyz: unit normal, w: 1 where geometry was drawn).
pub const NORMAL_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Format of the reflector-id target (0: none, i + 1: reflector i).
pub const REFLECTOR_ID_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

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
