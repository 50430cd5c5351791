//! A rendered frame read back to the CPU: the main G-buffer and the exact reference.

use image::Rgba32FImage;

use crate::TestbedError;
use crate::pixel_mask::PixelMask;
use crate::readback::{U32Image, read_depth, read_rgba_f32, read_texture_bytes, read_u32};
use crate::reference::ReflectedPointClass;
use crate::renderer::LevelRenderer;

/// The images of one frame.
#[derive(Clone, Debug)]
pub struct FrameImages {
    /// Linear HDR scene colour.
    pub color: Rgba32FImage,
    /// Raw depth values (standard or reversed as the camera said).
    pub depth: Vec<f32>,
    /// World normals (xyz) with w = 1 where geometry was drawn.
    pub normal: Rgba32FImage,
    /// Reflector id per pixel (0 none, i + 1 reflector i).
    pub reflector_id: U32Image,
    /// Exact reflection colour (alpha 1 on reflector pixels).
    pub reference: Rgba32FImage,
    /// Camera-relative position of the reflected point (w = 1 where geometry was hit).
    pub reference_position: Rgba32FImage,
    /// [`ReflectedPointClass`] per pixel.
    pub reference_class: U32Image,
}

impl FrameImages {
    /// Reads back the prepared and rendered frame of `renderer` (waits for the GPU).
    ///
    /// # Errors
    /// A readback error.
    pub fn read(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        renderer: &LevelRenderer,
    ) -> Result<Self, TestbedError> {
        let g = renderer.gbuffer();
        let r = renderer.reference();
        let point = read_texture_bytes(device, queue, &r.point.texture)?;
        let words: Vec<u32> =
            point.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
        let (w, h) = (r.point.texture.width(), r.point.texture.height());
        let class: Vec<u32> = words.chunks_exact(4).map(|p| p[3]).collect();
        let position = Rgba32FImage::from_fn(w, h, |x, y| {
            let p = &words[4 * (y * w + x) as usize..][..4];
            let hit = matches!(
                ReflectedPointClass::from_u32(p[3]),
                ReflectedPointClass::OnScreen | ReflectedPointClass::OffScreen
            );
            let f = |i: usize| if hit { f32::from_bits(p[i]) } else { 0.0 };
            image::Rgba([f(0), f(1), f(2), if hit { 1.0 } else { 0.0 }])
        });
        Ok(Self {
            color: read_rgba_f32(device, queue, &g.color.texture)?,
            depth: read_depth(device, queue, &g.depth.texture)?,
            normal: read_rgba_f32(device, queue, &g.normal.texture)?,
            reflector_id: read_u32(device, queue, &g.reflector_id.texture)?,
            reference: read_rgba_f32(device, queue, &r.color.texture)?,
            reference_position: position,
            reference_class: U32Image { width: w, height: h, data: class },
        })
    }

    /// Width and height in pixels.
    pub fn size(&self) -> [u32; 2] {
        [self.color.width(), self.color.height()]
    }

    /// The class of pixel `(x, y)`.
    pub fn class(&self, x: u32, y: u32) -> ReflectedPointClass {
        ReflectedPointClass::from_u32(self.reference_class.get(x, y))
    }

    /// Pixels on any reflector.
    pub fn reflector_mask(&self) -> PixelMask {
        let [w, h] = self.size();
        PixelMask::from_fn(w, h, |x, y| self.reflector_id.get(x, y) != 0)
    }

    /// Pixels of the given class.
    pub fn class_mask(&self, class: ReflectedPointClass) -> PixelMask {
        let [w, h] = self.size();
        PixelMask::from_fn(w, h, |x, y| self.class(x, y) == class)
    }

    /// Reflector pixels whose reflected point is on screen (what a screen-space method can get).
    pub fn on_screen_mask(&self) -> PixelMask {
        self.class_mask(ReflectedPointClass::OnScreen)
    }

    /// Reflector pixels whose reflected point is not on screen (off screen, hidden, background).
    pub fn off_screen_mask(&self) -> PixelMask {
        let [w, h] = self.size();
        PixelMask::from_fn(w, h, |x, y| {
            matches!(self.class(x, y), ReflectedPointClass::OffScreen | ReflectedPointClass::Background)
        })
    }
}
