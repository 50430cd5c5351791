//! The textures of one view, sized with the window: what the forward pass writes and what
//! PPR reads and writes.
//!
//! | texture | format | written by | read by |
//! | --- | --- | --- | --- |
//! | `color` | `Rgba16Float` (linear HDR) | forward pass | PPR reflection pass, composite |
//! | `reflection_weight` | `R8Unorm` | forward pass | composite |
//! | `depth` | `Depth32Float` | forward pass | PPR (classify, projection) |
//! | `reflection` | `Rgba16Float`, storage | PPR reflection pass | composite |

/// The lit scene colour's format (what PPR reflects), the depth format PPR reads, and a
/// texture with its view: `ppr-scene-gpu`'s, the testbed's G-buffer's too.
pub use ppr_scene_gpu::{COLOR_FORMAT, DEPTH_FORMAT, Target};

/// Format of the per-pixel reflection weight.
pub const WEIGHT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R8Unorm;

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
