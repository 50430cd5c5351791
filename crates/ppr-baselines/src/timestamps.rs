//! GPU timestamps around a technique's passes, resolved into a buffer and read back on
//! request as `(pass name, milliseconds)`.

use crate::error::BaselineError;

/// A query set with a begin and an end timestamp per pass slot, and the buffers to read it.
pub struct PassTimer {
    query_set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    slots: u32,
    period_ns: f32,
}

impl PassTimer {
    /// A timer with `slots` pass slots, or `None` when the device was created without
    /// `TIMESTAMP_QUERY`.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, label: &str, slots: u32) -> Option<Self> {
        if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            return None;
        }
        let slots = slots.max(1);
        let count = 2 * slots;
        let size = u64::from(count) * 8;
        Some(Self {
            query_set: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some(&format!("{label} timestamps")),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(&format!("{label} timestamps resolve")),
                size,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            readback: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(&format!("{label} timestamps readback")),
                size,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            slots,
            period_ns: queue.get_timestamp_period(),
        })
    }

    /// Timestamp writes at the beginning and end of a pass in slot `slot`.
    ///
    /// # Panics
    /// If `slot` is out of range.
    pub fn pass(&self, slot: u32) -> wgpu::ComputePassTimestampWrites<'_> {
        assert!(slot < self.slots, "timestamp slot {slot} out of range ({})", self.slots);
        wgpu::ComputePassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: Some(2 * slot),
            end_of_pass_write_index: Some(2 * slot + 1),
        }
    }

    /// Timestamp write at the end of an empty marker pass: `begin` true writes slot
    /// `slot`'s begin, false its end. Two markers bracket work recorded in between that
    /// has no pass of its own to time (render passes recorded by other code); on every
    /// backend wgpu writes pass timestamps once the preceding work is done.
    ///
    /// # Panics
    /// If `slot` is out of range.
    pub fn marker(&self, slot: u32, begin: bool) -> wgpu::ComputePassTimestampWrites<'_> {
        assert!(slot < self.slots, "timestamp slot {slot} out of range ({})", self.slots);
        wgpu::ComputePassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: None,
            end_of_pass_write_index: Some(2 * slot + u32::from(!begin)),
        }
    }

    /// Records the resolve and the copy to the readback buffer (after the passes).
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.query_set, 0..2 * self.slots, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, self.resolve.size());
    }

    /// Waits for the submitted frame and reads the time of each named slot that ran:
    /// `ran[i]` is `Some(name)` when slot `i` was recorded. A slot whose end is before its
    /// begin (llvmpipe's GL timer queries) is left out.
    ///
    /// # Errors
    /// [`BaselineError::Readback`] when the map or the wait fails.
    pub fn read(
        &self,
        device: &wgpu::Device,
        ran: &[Option<&str>],
    ) -> Result<Vec<(String, f64)>, BaselineError> {
        let slice = self.readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            // The receiver waits below; a send error only means it gave up already.
            let _ = tx.send(r);
        });
        let err = |reason: String| BaselineError::Readback { what: "timestamps".into(), reason };
        device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| err(e.to_string()))?;
        rx.recv().map_err(|e| err(e.to_string()))?.map_err(|e| err(e.to_string()))?;
        let ticks: Vec<u64> = {
            let view = slice.get_mapped_range().map_err(|e| err(e.to_string()))?;
            view.chunks_exact(8)
                .map(|c| u64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
                .collect()
        };
        self.readback.unmap();
        let period_ms = f64::from(self.period_ns) * 1e-6;
        Ok(ran
            .iter()
            .enumerate()
            .take(self.slots as usize)
            .filter_map(|(i, name)| {
                let (begin, end) = (ticks[2 * i], ticks[2 * i + 1]);
                let name = (*name)?;
                (end >= begin).then(|| (name.to_owned(), (end - begin) as f64 * period_ms))
            })
            .collect())
    }
}
