//! Frame timing for the fly camera (seconds since the last frame) and the on-screen frame
//! rate (mean over the last half second).

use std::time::{Duration, Instant};

/// How long the frame rate is averaged over.
pub const AVERAGE_OVER: Duration = Duration::from_millis(500);

/// Ticks once per frame.
#[derive(Clone, Copy, Debug)]
pub struct FrameClock {
    last: Instant,
    window_start: Instant,
    window_frames: u32,
    mean_ms: Option<f64>,
}

impl FrameClock {
    pub fn new(now: Instant) -> Self {
        Self { last: now, window_start: now, window_frames: 0, mean_ms: None }
    }

    /// A frame starts at `now`: returns the seconds since the previous one (at most 0.25,
    /// so a stall does not throw the camera across the level).
    pub fn tick(&mut self, now: Instant) -> f64 {
        let dt = now.saturating_duration_since(self.last).as_secs_f64().min(0.25);
        self.last = now;
        self.window_frames += 1;
        let elapsed = now.saturating_duration_since(self.window_start);
        if elapsed >= AVERAGE_OVER {
            self.mean_ms = Some(elapsed.as_secs_f64() * 1e3 / f64::from(self.window_frames));
            self.window_start = now;
            self.window_frames = 0;
        }
        dt
    }

    /// Mean frame time over the last completed half second, milliseconds.
    pub fn mean_ms(&self) -> Option<f64> {
        self.mean_ms
    }

    /// Forgets the time spent away (minimised, recreating the device).
    pub fn resume(&mut self, now: Instant) {
        *self = Self { mean_ms: self.mean_ms, ..Self::new(now) };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn averages_over_half_a_second_and_caps_the_step() {
        let t0 = Instant::now();
        let mut clock = FrameClock::new(t0);
        for k in 1..=30 {
            let dt = clock.tick(t0 + Duration::from_millis(20 * k));
            assert!((dt - 0.02).abs() < 1e-9);
        }
        assert!((clock.mean_ms().expect("a half second passed") - 20.0).abs() < 1e-9);
        assert_eq!(clock.tick(t0 + Duration::from_secs(10)), 0.25);
    }
}
