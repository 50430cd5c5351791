//! Reading textures back to the CPU: the screenshot (`Rgba8UnormSrgb`) and, for tests, the
//! scene colour and PPR's output (`Rgba16Float`).

use anyhow::{Context, Result, anyhow, bail};
use image::{GrayImage, Rgba32FImage, RgbaImage};

/// The texture's bytes, rows without wgpu's 256-byte padding.
///
/// # Errors
/// When mapping fails (e.g. the device was lost).
pub fn read_texture_bytes(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<u8>> {
    let format = texture.format();
    let texel =
        u64::from(format.block_copy_size(None).ok_or_else(|| anyhow!("{format:?} cannot be copied"))?);
    let (width, height) = (texture.width(), texture.height());
    let row = texel * u64::from(width);
    let padded = row.next_multiple_of(u64::from(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT));
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("walkthrough readback"),
        size: padded * u64::from(height),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("walkthrough readback") });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(u32::try_from(padded)?),
                rows_per_image: Some(height),
            },
        },
        texture.size(),
    );
    queue.submit([encoder.finish()]);
    let slice = buffer.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).context("waiting for the readback")?;
    rx.recv().context("readback callback dropped")?.context("mapping the readback buffer")?;
    let mut bytes = Vec::with_capacity((row * u64::from(height)) as usize);
    {
        let mapped = slice.get_mapped_range().map_err(|e| anyhow!("readback: {e:?}"))?;
        for y in 0..height as usize {
            let start = y * padded as usize;
            bytes.extend_from_slice(&mapped[start..start + row as usize]);
        }
    }
    buffer.unmap();
    Ok(bytes)
}

/// An `Rgba8Unorm(Srgb)` texture as an image (values as stored: sRGB-encoded for sRGB formats).
///
/// # Errors
/// Another format, or the readback failed.
pub fn read_rgba8(device: &wgpu::Device, queue: &wgpu::Queue, texture: &wgpu::Texture) -> Result<RgbaImage> {
    if !matches!(texture.format(), wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Rgba8UnormSrgb) {
        bail!("read_rgba8: {:?} is not RGBA8", texture.format());
    }
    let bytes = read_texture_bytes(device, queue, texture)?;
    RgbaImage::from_raw(texture.width(), texture.height(), bytes).context("readback size")
}

/// An `R8Unorm` texture as a grey image.
///
/// # Errors
/// Another format, or the readback failed.
pub fn read_r8(device: &wgpu::Device, queue: &wgpu::Queue, texture: &wgpu::Texture) -> Result<GrayImage> {
    if texture.format() != wgpu::TextureFormat::R8Unorm {
        bail!("read_r8: {:?} is not R8Unorm", texture.format());
    }
    let bytes = read_texture_bytes(device, queue, texture)?;
    GrayImage::from_raw(texture.width(), texture.height(), bytes).context("readback size")
}

/// An `Rgba16Float` texture as a float image.
///
/// # Errors
/// Another format, or the readback failed.
pub fn read_rgba16f(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Rgba32FImage> {
    if texture.format() != wgpu::TextureFormat::Rgba16Float {
        bail!("read_rgba16f: {:?} is not Rgba16Float", texture.format());
    }
    let bytes = read_texture_bytes(device, queue, texture)?;
    let floats: Vec<f32> =
        bytes.chunks_exact(2).map(|b| half::f16::from_le_bytes([b[0], b[1]]).to_f32()).collect();
    Rgba32FImage::from_raw(texture.width(), texture.height(), floats).context("readback size")
}
