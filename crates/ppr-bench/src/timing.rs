//! GPU time of one frame per pass, and the series of frames a run collects.

use std::collections::BTreeMap;

use crate::stats::Summary;

/// GPU (or wall-clock) time of one pass of one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PassTime {
    /// Pass name as the technique reports it (`"projection"`, `"trace"`, ...).
    pub pass: String,
    /// Milliseconds.
    pub ms: f64,
}

impl PassTime {
    pub fn new(pass: impl Into<String>, ms: f64) -> Self {
        Self { pass: pass.into(), ms }
    }
}

/// Where a run's times come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimingSource {
    /// GPU timestamps around each pass.
    GpuTimestamps,
    /// Wall clock from submission to completion (adapters without usable timestamps,
    /// such as llvmpipe): one pseudo-pass `frame`, CPU overhead included.
    WallClock,
}

impl TimingSource {
    pub fn as_str(self) -> &'static str {
        match self {
            Self::GpuTimestamps => "gpu-timestamps",
            Self::WallClock => "wall-clock",
        }
    }
}

/// The per-pass times of many frames of one run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TimingSeries {
    /// Pass names in the order they first appeared.
    order: Vec<String>,
    /// Samples per pass name.
    samples: BTreeMap<String, Vec<f64>>,
    /// Sum of the passes of each frame.
    totals: Vec<f64>,
}

impl TimingSeries {
    /// Adds one frame's passes.
    pub fn push_frame(&mut self, passes: &[PassTime]) {
        for p in passes {
            if !self.samples.contains_key(&p.pass) {
                self.order.push(p.pass.clone());
            }
            self.samples.entry(p.pass.clone()).or_default().push(p.ms);
        }
        self.totals.push(passes.iter().map(|p| p.ms).sum());
    }

    /// Frames recorded.
    pub fn frames(&self) -> usize {
        self.totals.len()
    }

    /// Median and p95 of each pass, in order of first appearance.
    pub fn passes(&self) -> Vec<(String, Summary)> {
        self.order
            .iter()
            .filter_map(|name| Summary::of(&self.samples[name]).map(|s| (name.clone(), s)))
            .collect()
    }

    /// Median and p95 of the per-frame total.
    pub fn total(&self) -> Option<Summary> {
        Summary::of(&self.totals)
    }

    /// The summary of one pass by name.
    pub fn pass(&self, name: &str) -> Option<Summary> {
        self.samples.get(name).and_then(|s| Summary::of(s))
    }
}

pub use ppr_testbed::encoder_timer::EncoderTimer;

/// Maps a `MAP_READ` buffer, waits, and returns its contents as little-endian u64s.
pub fn read_u64s(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Option<Vec<u64>> {
    let bytes = read_bytes(device, buffer)?;
    Some(bytes.chunks_exact(8).map(|c| u64::from_le_bytes(c.try_into().expect("8 bytes"))).collect())
}

/// Maps a `MAP_READ` buffer, waits, and returns its bytes.
pub fn read_bytes(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Option<Vec<u8>> {
    let slice = buffer.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).ok()?;
    rx.recv().ok()?.ok()?;
    let bytes = slice.get_mapped_range().ok()?.to_vec();
    buffer.unmap();
    Some(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_keeps_pass_order_and_sums_frames() {
        let mut s = TimingSeries::default();
        for k in 0..5 {
            let k = f64::from(k);
            s.push_frame(&[PassTime::new("clear", 0.1), PassTime::new("projection", 1.0 + k)]);
        }
        let names: Vec<String> = s.passes().into_iter().map(|(n, _)| n).collect();
        assert_eq!(names, ["clear", "projection"]);
        assert_eq!(s.frames(), 5);
        assert_eq!(s.pass("projection").map(|p| p.median), Some(3.0));
        let total = s.total().expect("total");
        assert!((total.median - 3.1).abs() < 1e-12 && (total.p95 - 5.1).abs() < 1e-12);
    }
}
