//! Runs a technique for many frames and collects its pass times: warm-up frames first (back
//! to back, at least [`WARMUP_SECONDS`] and until their GPU time settles), then timed frames, each after a write over a large
//! scratch buffer that evicts the GPU's caches (as the rest of a game frame would).

use std::time::Instant;

use ppr_runtime::Camera;

pub use crate::config::{FrameCounts, WARMUP_SECONDS};
use crate::technique::{BenchFrame, BenchTechnique};
use crate::timing::{PassTime, TimingSeries, TimingSource};

/// GPU milliseconds above which a run takes [`FrameCounts::slow_timed`] frames.
pub const SLOW_FRAME_MS: f64 = 50.0;

/// Most warm-up frames, whatever their time.
const MAX_WARMUP_FRAMES: usize = 4000;

/// Longest warm-up, seconds: past it a run is timed whether or not its frames have settled.
const MAX_WARMUP_SECONDS: f64 = 1.0;

/// Warm-up frames between two looks at the GPU time.
const WARMUP_BATCH: usize = 8;

/// A warm-up batch whose last frame is within this share of the fastest one before it has
/// settled. On the H200 the first technique after a camera's reference and metrics still ran
/// 1.4–3.6x slower after 0.2 s of warm-up (its clocks ramp up over longer than that).
const SETTLED: f64 = 0.05;

/// A scratch buffer written before every frame so that inputs do not sit in the L2 cache
/// from the previous frame (the H100 has 50 MB of it: a 1080p frame's inputs would fit).
pub struct CacheFlush {
    buffer: Option<wgpu::Buffer>,
}

impl CacheFlush {
    /// A flush of `bytes` (0: none).
    pub fn new(device: &wgpu::Device, bytes: u64) -> Self {
        let buffer = (bytes > 0).then(|| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("bench cache flush"),
                size: bytes.next_multiple_of(4),
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            })
        });
        Self { buffer }
    }

    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) {
        if let Some(b) = &self.buffer {
            encoder.clear_buffer(b, 0, None);
        }
    }
}

/// Whether the warm-up's frame times have stopped falling: a frame within [`SETTLED`] of
/// the fastest one before it.
#[derive(Clone, Copy, Debug)]
struct Settling {
    fastest: f64,
    settled: bool,
}

impl Settling {
    fn new() -> Self {
        Self { fastest: f64::INFINITY, settled: false }
    }

    /// Takes one look at a frame's GPU time. A frame over [`SLOW_FRAME_MS`] settles at once:
    /// its clocks are up after one batch, and seconds of such frames slowed the runs after
    /// them (every pass of a 1 ms frame 2.7x in the eleventh session's scaling run).
    fn observe(&mut self, ms: f64) {
        self.settled = ms > SLOW_FRAME_MS
            || (self.fastest.is_finite() && (ms - self.fastest).abs() <= SETTLED * self.fastest);
        self.fastest = self.fastest.min(ms);
    }
}

/// What a run of frames measured.
pub struct FrameRun {
    pub timings: TimingSeries,
    pub source: TimingSource,
    /// The technique's plan of the last frame.
    pub plan: String,
    /// Per timed frame, the CPU milliseconds of the technique's `prepare` and `encode`
    /// (recording its commands; not the cache flush, not the submit).
    pub cpu_ms: Vec<f64>,
}

impl FrameRun {
    /// The median of the frames' totals (infinite for a run without frames).
    pub fn median_ms(&self) -> f64 {
        self.timings.total().map_or(f64::INFINITY, |s| s.median)
    }

    /// The median of [`Self::cpu_ms`] (NaN for a run without frames).
    pub fn cpu_median_ms(&self) -> f64 {
        let mut v = self.cpu_ms.clone();
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
    }
}

/// How a suite runs frames: the counts and the cache flush before each frame.
pub struct FrameLoop {
    pub counts: FrameCounts,
    pub flush: CacheFlush,
}

impl FrameLoop {
    /// The frame loop of `cfg` on `device` (allocates the flush buffer).
    pub fn new(device: &wgpu::Device, cfg: &crate::config::BenchConfig) -> Self {
        Self { counts: cfg.frames, flush: CacheFlush::new(device, cfg.flush_bytes) }
    }

    /// Runs `technique` on `frame` seen by `camera` at `size`.
    pub fn run(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        technique: &mut dyn BenchTechnique,
        frame: &BenchFrame<'_>,
        camera: &Camera,
        size: [u32; 2],
    ) -> FrameRun {
        run_frames(device, queue, technique, frame, camera, size, self.counts, &self.flush)
    }
}

/// Runs jobs `0..count` (`run(j)` times job `j` once) in two rounds, the second in reverse
/// order, and keeps each job's faster run; a job whose first run took over
/// [`SLOW_FRAME_MS`] a frame runs once. The GPU sometimes sits in a slow state for seconds
/// (the H200 ran a 10 000-shape level's light variants 2.7x slower, every pass alike, right
/// after its 50-60 ms `culling off` frames, and three contiguous stairway rows at
/// 0.96-1.00 ms against 0.73-0.75 for the same code when each was the faster of two runs
/// back to back); in the reverse round each job meets that state at another time.
///
/// # Errors
/// The first error `run` returns.
pub fn faster_of_two_rounds<E>(
    count: usize,
    run: impl FnMut(usize) -> Result<FrameRun, E>,
) -> Result<Vec<FrameRun>, E> {
    faster_of_two_rounds_in(&(0..count).collect::<Vec<_>>(), run)
}

/// [`faster_of_two_rounds`] with the first round in `order` (a permutation of the jobs) and
/// the second in its reverse: given the lightest jobs first, the first round times them
/// before any heavy job could leave the GPU in its slow state (the second round, which
/// skips the heaviest, times the rest after the heavy ones).
///
/// # Errors
/// The first error `run` returns.
///
/// # Panics
/// If `order` is not a permutation of `0..order.len()`.
pub fn faster_of_two_rounds_in<E>(
    order: &[usize],
    mut run: impl FnMut(usize) -> Result<FrameRun, E>,
) -> Result<Vec<FrameRun>, E> {
    let mut seen = vec![false; order.len()];
    for &j in order {
        assert!(!std::mem::replace(&mut seen[j], true), "job {j} twice in {order:?}");
    }
    let mut runs: Vec<Option<FrameRun>> = order.iter().map(|_| None).collect();
    for &j in order.iter().chain(order.iter().rev()) {
        if runs[j].as_ref().is_some_and(|r| r.median_ms() > SLOW_FRAME_MS) {
            continue;
        }
        let new = run(j)?;
        if runs[j].as_ref().is_none_or(|earlier| new.median_ms() < earlier.median_ms()) {
            runs[j] = Some(new);
        }
    }
    Ok(runs.into_iter().map(|r| r.expect("every job ran in the first round")).collect())
}

/// The jobs from lightest to heaviest by `expected` times (a job without one, NaN, after
/// every job with one, in job order; ties in job order).
pub fn lightest_first(expected: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..expected.len()).collect();
    let key = |j: usize| if expected[j].is_nan() { f64::INFINITY } else { expected[j] };
    order.sort_by(|&a, &b| key(a).total_cmp(&key(b)));
    order
}

/// Runs `technique` on `frame` for `counts` frames.
#[allow(clippy::too_many_arguments)] // the loop's inputs, each used once; callers use `FrameLoop`
fn run_frames(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    technique: &mut dyn BenchTechnique,
    frame: &BenchFrame<'_>,
    camera: &Camera,
    size: [u32; 2],
    counts: FrameCounts,
    flush: &CacheFlush,
) -> FrameRun {
    let mut timings = TimingSeries::default();
    let mut source = TimingSource::GpuTimestamps;
    let mut plan = String::new();
    // Warm-up: frames back to back, without waiting, for at least `warmup_seconds`, so that
    // the GPU leaves whatever clock state the previous (CPU-bound) work left it in; then on,
    // batch by batch, until a batch's last frame is within `SETTLED` of the fastest before it
    // (the clocks have stopped ramping up), for at most `MAX_WARMUP_SECONDS`.
    let start = Instant::now();
    let mut warm = 0;
    let mut settling = Settling::new();
    while warm < MAX_WARMUP_FRAMES {
        let elapsed = start.elapsed().as_secs_f64();
        let minimum_done = warm >= counts.warmup.max(1) && elapsed >= counts.warmup_seconds;
        if minimum_done && (settling.settled || counts.warmup_seconds == 0.0 || elapsed >= MAX_WARMUP_SECONDS)
        {
            break;
        }
        plan = technique.prepare(device, queue, camera, size);
        let mut encoder = device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("bench warm-up frame") });
        flush.encode(&mut encoder);
        technique.encode(&mut encoder, frame);
        queue.submit([encoder.finish()]);
        warm += 1;
        if warm % WARMUP_BATCH == 0 {
            // Keep the queue short enough that the time above means GPU time; the batch's
            // last frame says whether the clocks still ramp.
            match technique.read_timings(device) {
                Some(passes) => settling.observe(passes.iter().map(|p| p.ms).sum()),
                None => {
                    let _ = device.poll(wgpu::PollType::wait_indefinitely());
                    settling.settled = true;
                }
            }
        }
    }
    let _ = technique.read_timings(device);
    let mut total = counts.timed;
    let mut i = 0;
    let mut cpu_ms = Vec::with_capacity(total);
    while i < total {
        let prepare_start = Instant::now();
        plan = technique.prepare(device, queue, camera, size);
        let prepared = prepare_start.elapsed();
        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("bench frame") });
        flush.encode(&mut encoder);
        let encode_start = Instant::now();
        technique.encode(&mut encoder, frame);
        cpu_ms.push((prepared + encode_start.elapsed()).as_secs_f64() * 1e3);
        let start = Instant::now();
        queue.submit([encoder.finish()]);
        let passes = technique.read_timings(device);
        let passes = match passes {
            Some(p) => p,
            None => {
                let _ = device.poll(wgpu::PollType::wait_indefinitely());
                source = TimingSource::WallClock;
                vec![PassTime::new("frame (wall clock)", start.elapsed().as_secs_f64() * 1e3)]
            }
        };
        let frame_ms: f64 = passes.iter().map(|p| p.ms).sum();
        if i == 0 && frame_ms > SLOW_FRAME_MS {
            total = counts.slow_timed.clamp(1, counts.timed);
        }
        timings.push_frame(&passes);
        i += 1;
    }
    FrameRun { timings, source, plan: plan.replace('\n', " | "), cpu_ms }
}

#[cfg(test)]
mod tests {
    use super::{FrameRun, Settling, faster_of_two_rounds_in, lightest_first};
    use crate::timing::{PassTime, TimingSeries, TimingSource};

    fn run_of(ms: f64) -> FrameRun {
        let mut timings = TimingSeries::default();
        timings.push_frame(&[PassTime::new("projection", ms)]);
        FrameRun { timings, source: TimingSource::GpuTimestamps, plan: String::new(), cpu_ms: vec![ms] }
    }

    #[test]
    fn two_rounds_go_in_the_order_then_back_and_keep_each_job_s_faster_run() {
        // Job 1 is heavy (over SLOW_FRAME_MS: it runs once); job 0 is faster the second time.
        let times = [vec![0.5, 0.4], vec![60.0], vec![0.2, 0.3]];
        let mut calls = Vec::new();
        let runs = faster_of_two_rounds_in(&[2, 0, 1], |j| {
            let k = calls.iter().filter(|&&c| c == j).count();
            calls.push(j);
            Ok::<_, ()>(run_of(times[j][k]))
        })
        .unwrap();
        assert_eq!(calls, [2, 0, 1, 0, 2]);
        let medians: Vec<f64> = runs.iter().map(FrameRun::median_ms).collect();
        assert_eq!(medians, [0.4, 60.0, 0.2]);
    }

    #[test]
    fn lightest_first_sorts_by_the_expected_times_unknown_last() {
        assert_eq!(lightest_first(&[47.8, 2.1, f64::NAN, 12.9, 2.1]), [1, 4, 3, 0, 2]);
        assert_eq!(lightest_first(&[]), Vec::<usize>::new());
    }

    #[test]
    fn warm_up_settles_once_frame_times_stop_falling() {
        let mut s = Settling::new();
        // Clocks ramping up: every look faster by more than the tolerance.
        for ms in [0.60, 0.45, 0.30, 0.20] {
            s.observe(ms);
            assert!(!s.settled, "settled while still falling, at {ms} ms");
        }
        s.observe(0.204);
        assert!(s.settled, "a frame within 5 % of the fastest has settled");
        // A slow outlier (or clocks dropping again) unsettles it.
        s.observe(0.30);
        assert!(!s.settled);
        s.observe(0.199);
        assert!(s.settled);
        // A heavy frame does not wait for its clocks.
        let mut heavy = Settling::new();
        heavy.observe(60.0);
        assert!(heavy.settled);
    }
}
