//! An image to render the final frame into without a window: the headless mode's target
//! and the windowed mode's screenshot.

use anyhow::Result;
use image::RgbaImage;

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
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("walkthrough offscreen frame"),
            size: wgpu::Extent3d { width: width.max(1), height: height.max(1), depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: OFFSCREEN_FORMAT,
            // COPY_DST: stereo frames copy each eye into its half.
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
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
