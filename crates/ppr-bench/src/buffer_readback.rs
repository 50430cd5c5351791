//! Reading a GPU buffer (with `COPY_SRC`) back as u32 words.

use crate::error::BenchError;
use crate::timing::read_bytes;

/// Copies `buffer` into a mappable buffer, waits, and returns its words.
///
/// # Errors
/// [`BenchError::Gpu`] if mapping fails.
pub fn read_buffer_u32(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    buffer: &wgpu::Buffer,
) -> Result<Vec<u32>, BenchError> {
    let size = buffer.size();
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("bench buffer readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("bench buffer readback") });
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
    queue.submit([encoder.finish()]);
    let bytes = read_bytes(device, &staging)
        .ok_or_else(|| BenchError::Gpu("mapping a readback buffer failed".into()))?;
    Ok(bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect())
}
