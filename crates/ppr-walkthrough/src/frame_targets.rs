//! The textures of one view, sized with the window: what the forward pass writes and what
//! PPR reads and writes.
//!
//! | texture | format | written by | read by |
//! | --- | --- | --- | --- |
//! | `color` | `Rgba16Float` (linear HDR) | forward pass | PPR reflection pass, composite |
//! | `reflection_weight` | `R8Unorm` | forward pass | composite |
//! | `depth` | `Depth32Float` | forward pass | PPR (classify, projection) |
//! | `reflection` | `Rgba16Float`, storage | PPR reflection pass | composite |

/// Format of the lit scene colour (what PPR reflects).
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Format of the per-pixel reflection weight.
pub const WEIGHT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R8Unorm;
/// Format of the depth buffer PPR reads.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// A texture and its default view.
pub struct Target {
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
}

impl Target {
    fn new(
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
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some(label),
            aspect: if format.has_depth_aspect() {
                wgpu::TextureAspect::DepthOnly
            } else {
                wgpu::TextureAspect::All
            },
            ..Default::default()
        });
        Self { texture, view }
    }
}

/// Every per-view texture of a frame.
pub struct FrameTargets {
    pub size: [u32; 2],
    pub color: Target,
    pub reflection_weight: Target,
    pub depth: Target,
    /// PPR's output: reflected colour, alpha its confidence (0 where none was found).
    pub reflection: Target,
}

impl FrameTargets {
    /// Textures for a `size` view (each side at least 1).
    pub fn new(device: &wgpu::Device, size: [u32; 2]) -> Self {
        use wgpu::TextureUsages as U;
        let size = [size[0].max(1), size[1].max(1)];
        Self {
            size,
            color: Target::new(
                device,
                "walkthrough scene colour",
                size,
                COLOR_FORMAT,
                U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC,
            ),
            reflection_weight: Target::new(
                device,
                "walkthrough reflection weight",
                size,
                WEIGHT_FORMAT,
                U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC,
            ),
            depth: Target::new(
                device,
                "walkthrough depth",
                size,
                DEPTH_FORMAT,
                U::RENDER_ATTACHMENT | U::TEXTURE_BINDING,
            ),
            // RENDER_ATTACHMENT only to clear it (see `WalkthroughRenderer::render`).
            reflection: Target::new(
                device,
                "walkthrough ppr reflection",
                size,
                ppr_runtime::OUTPUT_FORMAT,
                U::STORAGE_BINDING | U::TEXTURE_BINDING | U::RENDER_ATTACHMENT | U::COPY_SRC,
            ),
        }
    }
}
