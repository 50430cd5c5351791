//! GPU timestamps around each pass, resolved into a buffer and read back on request.

use crate::wgpu_compat::MappedRange;
use std::fmt;

/// GPU time of each pass of one frame, milliseconds; `None` for a pass that did not run
/// (or whose timestamps the adapter got wrong).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PassTimings {
    pub classify_ms: Option<f64>,
    pub clear_ms: Option<f64>,
    pub projection_ms: Option<f64>,
    pub reflection_ms: Option<f64>,
    pub layers_ms: Option<f64>,
    /// Reduced-resolution tiers: depth and colour to the reduced size.
    pub downsample_ms: Option<f64>,
    /// Reduced-resolution tiers: the reflections back to the full size.
    pub upsample_ms: Option<f64>,
    /// The whole frame from two encoder timestamps: the upload's copies, the passes and the
    /// barriers between them (`DebugOptions::frame_span`; the passes are then not timed one
    /// by one).
    pub frame_ms: Option<f64>,
    /// The projection and the reflection (and the layer reflection beside it) recorded in
    /// one compute pass (the default; then `projection_ms` and `reflection_ms` are `None`).
    pub projection_reflection_ms: Option<f64>,
}

impl PassTimings {
    /// Sum of the passes that ran.
    pub fn total_ms(&self) -> f64 {
        self.passes().iter().filter_map(|(_, t)| *t).sum()
    }

    /// (name, time) of each pass in order.
    pub fn passes(&self) -> [(&'static str, Option<f64>); TIMED_PASSES as usize] {
        [
            ("classify", self.classify_ms),
            ("clear", self.clear_ms),
            ("projection", self.projection_ms),
            ("reflection", self.reflection_ms),
            ("layers", self.layers_ms),
            ("downsample", self.downsample_ms),
            ("upsample", self.upsample_ms),
            ("frame", self.frame_ms),
            ("projection + reflection", self.projection_reflection_ms),
        ]
    }
}

impl fmt::Display for PassTimings {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (name, t) in self.passes() {
            if let Some(t) = t {
                write!(f, "{name} {t:.3} ms, ")?;
            }
        }
        write!(f, "total {:.3} ms", self.total_ms())
    }
}

/// Passes with a timestamp slot: classify, clear, projection, reflection, layers, the
/// reduced tiers' downsample and upsample, the whole frame's span, and the projection and
/// reflection in one compute pass, in [`PassTimings::passes`] order.
pub const TIMED_PASSES: u32 = 9;

/// The slots of the passes timed on their own, in [`PassTimings::passes`] order.
pub const CLASSIFY: u32 = 0;
pub const CLEAR: u32 = 1;
pub const PROJECTION: u32 = 2;
pub const REFLECTION: u32 = 3;
pub const LAYERS: u32 = 4;
pub const DOWNSAMPLE: u32 = 5;
pub const UPSAMPLE: u32 = 6;

/// The slot of the whole frame's span ([`PassTimer::write_span`]).
pub const FRAME_SPAN: u32 = 7;

/// The slot of the projection and the reflection recorded in one compute pass.
pub const PROJECTION_REFLECTION: u32 = 8;

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

    /// Timestamp writes for pass `index` (0 classify, 1 clear, 2 projection, 3 reflection,
    /// 4 layers, 5 downsample, 6 upsample, 8 projection + reflection).
    pub fn writes(&self, index: u32) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: Some(2 * index),
            end_of_pass_write_index: Some(2 * index + 1),
        }
    }

    /// Whether the device can write timestamps between passes ([`Self::write_span`]).
    pub fn spans(device: &wgpu::Device) -> bool {
        device.features().contains(wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS)
    }

    /// Records the frame span's begin (`end` false) or end timestamp into the encoder,
    /// between passes. Needs [`Self::spans`].
    pub fn write_span(&self, encoder: &mut wgpu::CommandEncoder, end: bool) {
        encoder.write_timestamp(&self.query_set, 2 * FRAME_SPAN + u32::from(end));
    }

    /// Records the resolve and the copy to the readback buffer (after the passes).
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.query_set, 0..2 * TIMED_PASSES, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, self.resolve.size());
    }

    /// Waits for the submitted frame and reads its timings; `ran[i]` says whether pass `i`
    /// was recorded.
    pub fn read(&self, device: &wgpu::Device, ran: [bool; TIMED_PASSES as usize]) -> Option<PassTimings> {
        let slice = self.readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        device.poll(wgpu::PollType::wait_indefinitely()).ok()?;
        rx.recv().ok()?.ok()?;
        let ticks: Vec<u64> = {
            let view = slice.get_mapped_range().into_view()?;
            view.chunks_exact(8).map(|c| u64::from_le_bytes(c.try_into().expect("8 bytes"))).collect()
        };
        self.readback.unmap();
        let ms = |i: usize| {
            let (begin, end) = (ticks[2 * i], ticks[2 * i + 1]);
            // Some drivers (llvmpipe's GL timer queries) report an end before the begin.
            (ran[i] && end >= begin).then(|| (end - begin) as f64 * f64::from(self.period_ns) * 1e-6)
        };
        Some(PassTimings {
            classify_ms: ms(0),
            clear_ms: ms(1),
            projection_ms: ms(2),
            reflection_ms: ms(3),
            layers_ms: ms(4),
            downsample_ms: ms(5),
            upsample_ms: ms(6),
            frame_ms: ms(7),
            projection_reflection_ms: ms(8),
        })
    }
}
