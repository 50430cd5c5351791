//! The exact planar reflection (the scene rendered again from the mirrored camera of every
//! visible reflector plane, the testbed's `MirrorReference`) timed as a technique: the
//! accuracy ceiling of the comparison and what it costs.

use ppr_format::ReflectorSet;
use ppr_runtime::Camera;
use ppr_testbed::{Level, LevelRenderer, RenderSettings};

use crate::technique::{BenchFrame, BenchTechnique, Family, ReflectionOutput};
use crate::timing::{EncoderTimer, PassTime};

/// Times the level renderer's reference passes with encoder timestamps.
pub struct ExactReference {
    timer: Option<EncoderTimer>,
    /// With more than one bounce: its own level renderer at that depth (the bench's level
    /// renders one bounce), its G-buffer drawn untimed before the timed reference.
    deeper: Option<(LevelRenderer, u32)>,
}

impl ExactReference {
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        Self { timer: EncoderTimer::new(device, queue), deeper: None }
    }

    /// The reference of `bounces` bounces (`exact:bounces=N`): its time and, as its quality,
    /// exact against the N-bounce reference.
    pub fn with_bounces(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: (&Level, &ReflectorSet),
        render: RenderSettings,
        bounces: u32,
    ) -> Self {
        let mut reference = Self::new(device, queue);
        if bounces > 1 {
            let mut level = LevelRenderer::new(device, queue, scene.0, scene.1);
            level.settings = RenderSettings { reference_bounces: bounces, ..render };
            reference.deeper = Some((level, bounces));
        }
        reference
    }
}

/// Label of the exact reference in reports.
pub const EXACT_LABEL: &str = "exact";

impl BenchTechnique for ExactReference {
    fn label(&self) -> String {
        match &self.deeper {
            Some((_, n)) => format!("{EXACT_LABEL} bounces={n}"),
            None => EXACT_LABEL.into(),
        }
    }

    fn reference_bounces(&self) -> u32 {
        self.deeper.as_ref().map_or(1, |(_, n)| *n)
    }

    fn family(&self) -> Family {
        Family::Exact
    }

    fn output(&self) -> ReflectionOutput {
        ReflectionOutput::Reference
    }

    fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        camera: &Camera,
        size: [u32; 2],
    ) -> String {
        match &mut self.deeper {
            Some((level, n)) => {
                let s = level.prepare(device, queue, camera, size);
                format!(
                    "{n} bounces: {} first-bounce views, {} more ({} over the cap skipped)",
                    s.rendered_planes.len(),
                    s.bounce_views,
                    s.bounce_views_skipped
                )
            }
            None => "mirrored re-render per visible plane (prepared with the level)".into(),
        }
    }

    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, frame: &BenchFrame<'_>) {
        if let Some((level, _)) = &self.deeper {
            level.encode_gbuffer(encoder);
        }
        if let Some(t) = &self.timer {
            t.begin(encoder);
        }
        match &self.deeper {
            Some((level, _)) => level.encode_reference(encoder),
            None => frame.level.encode_reference(encoder),
        }
        if let Some(t) = &self.timer {
            t.end(encoder);
        }
    }

    fn read_timings(&mut self, device: &wgpu::Device) -> Option<Vec<PassTime>> {
        let ms = self.timer.as_ref()?.read_ms(device)?;
        Some(vec![PassTime::new("mirrored views + resolve", ms)])
    }
}
