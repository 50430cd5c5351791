//! One run's findings: a technique on one scene, camera and size.

use crate::config::Resolution;
use crate::quality::Quality;
use crate::technique::Family;
use crate::timing::{TimingSeries, TimingSource};

/// What one run measured.
#[derive(Clone, Debug)]
pub struct RunResult {
    pub scene: String,
    pub camera: String,
    pub resolution: Resolution,
    /// Technique label with its setting.
    pub technique: String,
    pub family: Family,
    pub timings: TimingSeries,
    pub timing_source: TimingSource,
    /// `None` when quality was not measured at this size (see the report).
    pub quality: Option<Quality>,
    /// The technique's plan of the last frame.
    pub plan: String,
}

impl RunResult {
    /// Median GPU time of the whole technique, ms (NaN without frames).
    pub fn total_ms(&self) -> f64 {
        self.timings.total().map_or(f64::NAN, |s| s.median)
    }
}
