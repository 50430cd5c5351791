//! The GPU buffers a technique fills once per frame: the frame uniform, its settings
//! uniform and the reflector planes.

use crate::gpu_types::{BaselineFrame, GpuReflectorPlane};

/// A storage buffer of reflector planes that grows to fit (never empty: WGSL runtime
/// arrays need at least one element).
pub struct PlaneBuffer {
    label: String,
    buffer: wgpu::Buffer,
    capacity: usize,
}

impl PlaneBuffer {
    /// A buffer with room for one plane.
    pub fn new(device: &wgpu::Device, label: &str) -> Self {
        Self { label: label.to_owned(), buffer: Self::allocate(device, label, 1), capacity: 1 }
    }

    fn allocate(device: &wgpu::Device, label: &str, capacity: usize) -> wgpu::Buffer {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: (capacity * size_of::<GpuReflectorPlane>()) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// Uploads `planes`, reallocating when they do not fit; returns whether the buffer
    /// was replaced (bind groups over it must be rebuilt).
    pub fn write(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        planes: &[GpuReflectorPlane],
    ) -> bool {
        let grew = planes.len() > self.capacity;
        if grew {
            self.capacity = planes.len().next_power_of_two();
            self.buffer = Self::allocate(device, &self.label, self.capacity);
        }
        if !planes.is_empty() {
            queue.write_buffer(&self.buffer, 0, bytemuck::cast_slice(planes));
        }
        grew
    }

    /// The buffer.
    pub fn buffer(&self) -> &wgpu::Buffer {
        &self.buffer
    }
}

/// The frame uniform and a technique's settings uniform.
pub struct FrameUniforms {
    /// [`BaselineFrame`].
    pub frame: wgpu::Buffer,
    /// The technique's settings uniform.
    pub params: wgpu::Buffer,
}

impl FrameUniforms {
    /// Buffers for a settings uniform of `params_size` bytes.
    pub fn new(device: &wgpu::Device, label: &str, params_size: usize) -> Self {
        let uniform = |name: &str, size: usize| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(&format!("{label} {name}")),
                size: size.max(16) as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        Self { frame: uniform("frame", size_of::<BaselineFrame>()), params: uniform("params", params_size) }
    }

    /// Uploads the frame and the settings.
    pub fn write<P: bytemuck::Pod>(&self, queue: &wgpu::Queue, frame: &BaselineFrame, params: &P) {
        queue.write_buffer(&self.frame, 0, bytemuck::bytes_of(frame));
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(params));
    }
}
