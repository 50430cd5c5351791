//! What every suite shares: where to write, how many frames, which machine-independent
//! choices (cache flush, tone map) apply.

use std::fmt;
use std::path::PathBuf;
use std::str::FromStr;

use ppr_testbed::image_io::ToneMap;

use crate::error::BenchError;

/// How many frames a run takes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameCounts {
    /// Frames run and thrown away first (pipelines, caches, clocks).
    pub warmup: usize,
    /// Frames timed.
    pub timed: usize,
    /// Frames timed instead when the first timed frame took longer than [`crate::frame_loop::SLOW_FRAME_MS`]
    /// (brute-force SSR and the exact re-render at 8K: their medians are steady and far
    /// from PPR's, and a full count would not fit a device lease).
    pub slow_timed: usize,
    /// Warm up for at least this long, frames back to back ([`WARMUP_SECONDS`] for
    /// measurements; 0 for `--quick`).
    pub warmup_seconds: f64,
}

/// Shortest warm-up, seconds of frames submitted back to back. Without it, a short
/// technique timed right after seconds of CPU work (read-backs, metrics) ran 2–2.6× slower
/// on the H100 at 4K, every pass alike (docs/perf/comparison.md).
pub const WARMUP_SECONDS: f64 = 0.2;

/// A render size.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Resolution {
    pub width: u32,
    pub height: u32,
}

impl Resolution {
    pub const HD: Self = Self { width: 1920, height: 1080 };
    pub const QHD: Self = Self { width: 2560, height: 1440 };
    pub const UHD: Self = Self { width: 3840, height: 2160 };
    pub const UHD8K: Self = Self { width: 7680, height: 4320 };
    /// The four resolutions of the comparison.
    pub const STANDARD: [Self; 4] = [Self::HD, Self::QHD, Self::UHD, Self::UHD8K];

    pub fn size(self) -> [u32; 2] {
        [self.width, self.height]
    }

    pub fn pixels(self) -> u64 {
        u64::from(self.width) * u64::from(self.height)
    }
}

impl fmt::Display for Resolution {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}x{}", self.width, self.height)
    }
}

impl FromStr for Resolution {
    type Err = BenchError;

    /// `1920x1080`, or `1080p`, `1440p`, `4k`, `8k`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let named = match s.to_ascii_lowercase().as_str() {
            "1080p" => Some(Self::HD),
            "1440p" => Some(Self::QHD),
            "4k" | "2160p" => Some(Self::UHD),
            "8k" | "4320p" => Some(Self::UHD8K),
            _ => None,
        };
        if let Some(r) = named {
            return Ok(r);
        }
        let bad = || {
            BenchError::Spec(format!(
                "resolution `{s}`: expected WIDTHxHEIGHT (1920x1080) or 1080p/1440p/4k/8k"
            ))
        };
        let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
        let width: u32 = w.trim().parse().map_err(|_| bad())?;
        let height: u32 = h.trim().parse().map_err(|_| bad())?;
        if width == 0 || height == 0 || width > 16384 || height > 16384 {
            return Err(bad());
        }
        Ok(Self { width, height })
    }
}

/// Settings every suite shares.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchConfig {
    /// Where the reports go (created if missing).
    pub out_dir: PathBuf,
    /// The repository root (the demo level is `assets/demo_room.glb` under it).
    pub repo_root: PathBuf,
    /// Folder of the shared scenes (`kitchen/kitchen.gltf`, `small.glb`, ...).
    pub scenes_dir: PathBuf,
    /// Warm-up and timed frames per run.
    pub frames: FrameCounts,
    /// Bytes written to a scratch buffer before every frame to evict caches (0: none).
    pub flush_bytes: u64,
    /// Tone map of the quality metrics and images.
    pub tone_map: ToneMap,
    /// The command line, recorded in every report.
    pub command_line: String,
    /// Small everything, for CI.
    pub quick: bool,
}

impl BenchConfig {
    /// Frames and flush of a full run: 5 warm-up frames and at least 0.2 s of them, 30 timed
    /// (10 for frames over 50 ms), 256 MiB flush.
    pub fn full(out_dir: PathBuf, repo_root: PathBuf, scenes_dir: PathBuf) -> Self {
        Self {
            out_dir,
            repo_root,
            scenes_dir,
            frames: FrameCounts { warmup: 5, timed: 30, slow_timed: 10, warmup_seconds: WARMUP_SECONDS },
            flush_bytes: 256 << 20,
            tone_map: ToneMap::Clamp,
            command_line: String::new(),
            quick: false,
        }
    }

    /// The same with `--quick`'s frames: 1 warm-up, 3 timed, no flush, no timed warm-up.
    pub fn into_quick(mut self) -> Self {
        self.frames = FrameCounts { warmup: 1, timed: 3, slow_timed: 3, warmup_seconds: 0.0 };
        self.flush_bytes = 0;
        self.quick = true;
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resolutions_parse() {
        assert_eq!("1920x1080".parse::<Resolution>().expect("res"), Resolution::HD);
        assert_eq!("4k".parse::<Resolution>().expect("res"), Resolution::UHD);
        assert_eq!("64x36".parse::<Resolution>().expect("res").pixels(), 64 * 36);
        assert!("0x5".parse::<Resolution>().is_err());
        assert!("big".parse::<Resolution>().is_err());
        assert_eq!(Resolution::UHD8K.to_string(), "7680x4320");
    }
}
