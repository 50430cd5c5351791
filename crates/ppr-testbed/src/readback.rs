//! Reading textures back from the GPU into CPU images (rows padded to 256 bytes on the GPU).

use image::Rgba32FImage;

use crate::TestbedError;
use crate::depth_copy::{DEPTH_BITS_FORMAT, DepthCopyPass};
use crate::gbuffer_targets::Target;
use crate::gpu::wait_idle;

/// A single-channel `u32` image (reflector ids, reference classes), rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct U32Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` values.
    pub data: Vec<u32>,
}

impl U32Image {
    /// The value at pixel `(x, y)`.
    ///
    /// # Panics
    /// If the pixel is outside the image.
    pub fn get(&self, x: u32, y: u32) -> u32 {
        assert!(x < self.width && y < self.height, "pixel ({x}, {y}) outside {}x{}", self.width, self.height);
        self.data[(y * self.width + x) as usize]
    }
}

/// Copies a whole 2D texture (mip 0, layer 0) into tightly packed bytes.
///
/// # Errors
/// [`TestbedError::UnsupportedFormat`] for formats without a fixed texel size, and
/// [`TestbedError::Readback`] if mapping fails.
pub fn read_texture_bytes(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<u8>, TestbedError> {
    let format = texture.format();
    let what = || texture_name(texture);
    let aspect = if format.is_depth_stencil_format() {
        wgpu::TextureAspect::DepthOnly
    } else {
        wgpu::TextureAspect::All
    };
    let texel = format
        .block_copy_size(Some(aspect))
        .ok_or_else(|| TestbedError::UnsupportedFormat { what: what(), format })?;
    let (w, h) = (texture.width(), texture.height());
    let row = w * texel;
    let padded = row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback buffer"),
        size: u64::from(padded) * u64::from(h),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback") });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo { texture, mip_level: 0, origin: wgpu::Origin3d::ZERO, aspect },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(h),
            },
        },
        wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
    );
    queue.submit([encoder.finish()]);
    let (sender, receiver) = std::sync::mpsc::channel();
    buffer.map_async(wgpu::MapMode::Read, .., move |r| {
        // The receiver waits below; a send error only means it gave up already.
        let _ = sender.send(r);
    });
    wait_idle(device)?;
    receiver
        .recv()
        .map_err(|e| TestbedError::Readback { what: what(), reason: e.to_string() })?
        .map_err(|e| TestbedError::Readback { what: what(), reason: e.to_string() })?;
    let view = buffer
        .get_mapped_range(..)
        .map_err(|e| TestbedError::Readback { what: what(), reason: e.to_string() })?;
    let mut out = Vec::with_capacity((row * h) as usize);
    for y in 0..h as usize {
        let start = y * padded as usize;
        out.extend_from_slice(&view[start..start + row as usize]);
    }
    drop(view);
    buffer.unmap();
    Ok(out)
}

/// Reads a colour texture as linear RGBA `f32` (from `Rgba16Float`, `Rgba32Float`,
/// `R32Float`, `Rgba8Unorm` or `Rgba8UnormSrgb`, the latter decoded to linear).
///
/// # Errors
/// [`TestbedError::UnsupportedFormat`] for other formats, or a readback error.
pub fn read_rgba_f32(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Rgba32FImage, TestbedError> {
    let bytes = read_texture_bytes(device, queue, texture)?;
    let (w, h) = (texture.width(), texture.height());
    let data: Vec<f32> = match texture.format() {
        wgpu::TextureFormat::Rgba16Float => {
            bytes.chunks_exact(2).map(|c| half::f16::from_le_bytes([c[0], c[1]]).to_f32()).collect()
        }
        wgpu::TextureFormat::Rgba32Float => {
            bytes.chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect()
        }
        wgpu::TextureFormat::R32Float | wgpu::TextureFormat::Depth32Float => bytes
            .chunks_exact(4)
            .flat_map(|c| {
                let v = f32::from_le_bytes([c[0], c[1], c[2], c[3]]);
                [v, v, v, 1.0]
            })
            .collect(),
        wgpu::TextureFormat::Rgba8Unorm => bytes.iter().map(|&b| f32::from(b) / 255.0).collect(),
        wgpu::TextureFormat::Rgba8UnormSrgb => bytes
            .chunks_exact(4)
            .flat_map(|c| {
                let [r, g, b, a] = [c[0], c[1], c[2], c[3]].map(|v| f32::from(v) / 255.0);
                [srgb_to_linear(r), srgb_to_linear(g), srgb_to_linear(b), a]
            })
            .collect(),
        format => return Err(TestbedError::UnsupportedFormat { what: texture_name(texture), format }),
    };
    Rgba32FImage::from_raw(w, h, data).ok_or_else(|| TestbedError::Readback {
        what: texture_name(texture),
        reason: "pixel count does not match the size".into(),
    })
}

/// Reads an `R32Uint` texture.
///
/// # Errors
/// [`TestbedError::UnsupportedFormat`] for other formats, or a readback error.
pub fn read_u32(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<U32Image, TestbedError> {
    if texture.format() != wgpu::TextureFormat::R32Uint {
        return Err(TestbedError::UnsupportedFormat {
            what: texture_name(texture),
            format: texture.format(),
        });
    }
    let bytes = read_texture_bytes(device, queue, texture)?;
    let data = bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    Ok(U32Image { width: texture.width(), height: texture.height(), data })
}

/// Reads a `Depth32Float` texture (which needs `TEXTURE_BINDING` usage) as one `f32` per
/// pixel, through [`DepthCopyPass`] (built for this call), since GL cannot copy depth to
/// buffers.
///
/// # Errors
/// [`TestbedError::UnsupportedFormat`] for other formats, or a readback error.
pub fn read_depth(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<f32>, TestbedError> {
    if texture.format() != wgpu::TextureFormat::Depth32Float {
        return Err(TestbedError::UnsupportedFormat {
            what: texture_name(texture),
            format: texture.format(),
        });
    }
    let pass = DepthCopyPass::new(device);
    let view = texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some("depth readback view"),
        aspect: wgpu::TextureAspect::DepthOnly,
        ..Default::default()
    });
    let size = [texture.width(), texture.height()];
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
    let bits = Target::new(device, "depth readback bits", size, DEPTH_BITS_FORMAT, usage);
    let bind_group = pass.bind_group(device, &view);
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("depth readback") });
    pass.encode(&mut encoder, &bind_group, &bits);
    queue.submit([encoder.finish()]);
    let bytes = read_texture_bytes(device, queue, &bits.texture)?;
    Ok(bytes.chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect())
}

/// The sRGB transfer function's inverse (sRGB-encoded value to linear).
pub fn srgb_to_linear(v: f32) -> f32 {
    if v <= 0.04045 { v / 12.92 } else { ((v + 0.055) / 1.055).powf(2.4) }
}

fn texture_name(texture: &wgpu::Texture) -> String {
    format!("{}x{} {:?} texture", texture.width(), texture.height(), texture.format())
}
