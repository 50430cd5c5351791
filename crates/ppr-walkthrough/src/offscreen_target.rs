//! An image to render the final frame into without a window: the headless mode's target
//! and the windowed mode's screenshot.

use anyhow::Result;
use image::RgbaImage;

use crate::frame_targets::Target;
use crate::texture_readback::read_rgba8;

/// Format of offscreen frames (what a PNG holds).
pub const OFFSCREEN_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// A render target that can be read back.
pub struct OffscreenTarget {
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
}

impl OffscreenTarget {
    pub fn new(device: &wgpu::Device, [width, height]: [u32; 2]) -> Self {
        // COPY_DST: stereo frames copy each eye into its half.
        use wgpu::TextureUsages as U;
        let usage = U::RENDER_ATTACHMENT | U::COPY_SRC | U::COPY_DST;
        let size = [width.max(1), height.max(1)];
        let Target { texture, view } =
            Target::new(device, "walkthrough offscreen frame", size, OFFSCREEN_FORMAT, usage);
        Self { texture, view }
    }

    /// The image as rendered (sRGB).
    ///
    /// # Errors
    /// When the readback fails.
    pub fn read(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<RgbaImage> {
        read_rgba8(device, queue, &self.texture)
    }
}
