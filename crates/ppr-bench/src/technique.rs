//! What the bench runs: a technique that reads the frame's colour and depth, writes a
//! reflection, and says how long each of its passes took.

use ppr_runtime::Camera;
use ppr_testbed::{LevelRenderer, ReflectionInputs};

use crate::timing::PassTime;

/// Which family a technique belongs to (plot colours and the report's grouping).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Family {
    /// Pixel-projected reflections (`ppr-runtime`).
    Ppr,
    /// Ray-marched screen-space reflections (baselines).
    Ssr,
    /// Screen-space planar reflections with a projection hash buffer (baseline).
    Sspr,
    /// The scene rendered again from the mirrored camera per reflector plane.
    Exact,
}

impl Family {
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Ppr => "PPR",
            Self::Ssr => "SSR",
            Self::Sspr => "SSPR",
            Self::Exact => "exact",
        }
    }
}

/// Where the technique's reflection ends up after a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReflectionOutput {
    /// In the output texture of [`BenchFrame::reflection`].
    OutputTexture,
    /// It *is* the exact reference (the level renderer's reference targets): quality is
    /// exact by definition.
    Reference,
}

/// What a frame gives a technique.
pub struct BenchFrame<'a> {
    /// The level renderer, prepared for this frame's camera and size (its G-buffer holds
    /// the frame; techniques that re-render the scene use it).
    pub level: &'a LevelRenderer,
    /// Colour, depth and the output texture.
    pub reflection: ReflectionInputs<'a>,
}

/// A technique with a setting, as the bench drives it.
pub trait BenchTechnique {
    /// Label of the technique and its setting, unique within a run (`"ppr"`,
    /// `"ssr-low stride=64"`).
    fn label(&self) -> String;

    /// Its family.
    fn family(&self) -> Family;

    /// The bounces of the reference it is scored against (PPR fed its previous frame N
    /// times: N; everything else: 1).
    fn reference_bounces(&self) -> u32 {
        1
    }

    /// Where the reflection goes.
    fn output(&self) -> ReflectionOutput {
        ReflectionOutput::OutputTexture
    }

    /// Uploads what the frame seen by `camera` at `size` needs (called every frame, as a
    /// game would); returns a description of the frame's plan.
    fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        camera: &Camera,
        size: [u32; 2],
    ) -> String;

    /// Records the technique's passes.
    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, frame: &BenchFrame<'_>);

    /// Waits for the submitted frame and returns the GPU time of each pass, or `None`
    /// when the device has no (usable) timestamps.
    fn read_timings(&mut self, device: &wgpu::Device) -> Option<Vec<PassTime>>;
}
