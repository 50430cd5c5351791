//! GPU timestamps around each pass, resolved into a buffer and read back on request.

/// GPU time of each pass of one frame, milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PassTimings {
    pub clear_ms: f64,
    pub projection_ms: f64,
    pub reflection_ms: f64,
}

impl PassTimings {
    /// Sum of the passes.
    pub fn total_ms(&self) -> f64 {
        self.clear_ms + self.projection_ms + self.reflection_ms
    }
}

/// Number of passes timed (clear, projection, reflection).
pub const TIMED_PASSES: u32 = 3;

/// A query set with a begin and an end timestamp per pass, and the buffers to read it.
pub struct PassTimer {
    query_set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    period_ns: f32,
}

impl PassTimer {
    /// A timer, or `None` when the device was created without `TIMESTAMP_QUERY`.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Option<Self> {
        if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            return None;
        }
        let count = 2 * TIMED_PASSES;
        let size = u64::from(count) * 8;
        Some(Self {
            query_set: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("ppr timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ppr timestamps resolve"),
                size,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            readback: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ppr timestamps readback"),
                size,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            period_ns: queue.get_timestamp_period(),
        })
    }

    /// Timestamp writes for pass `index` (0 clear, 1 projection, 2 reflection).
    pub fn writes(&self, index: u32) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: Some(2 * index),
            end_of_pass_write_index: Some(2 * index + 1),
        }
    }

    /// Records the resolve and the copy to the readback buffer (after the passes).
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.query_set, 0..2 * TIMED_PASSES, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, self.resolve.size());
    }

    /// Waits for the submitted frame and reads its timings.
    pub fn read(&self, device: &wgpu::Device) -> Option<PassTimings> {
        let slice = self.readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        device.poll(wgpu::PollType::wait_indefinitely()).ok()?;
        rx.recv().ok()?.ok()?;
        let ticks: Vec<u64> = {
            let view = slice.get_mapped_range().ok()?;
            view.chunks_exact(8).map(|c| u64::from_le_bytes(c.try_into().expect("8 bytes"))).collect()
        };
        self.readback.unmap();
        let ms =
            |i: usize| ticks[2 * i + 1].wrapping_sub(ticks[2 * i]) as f64 * f64::from(self.period_ns) * 1e-6;
        Some(PassTimings { clear_ms: ms(0), projection_ms: ms(1), reflection_ms: ms(2) })
    }
}
