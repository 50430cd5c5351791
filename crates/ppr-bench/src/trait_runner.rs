//! Any testbed [`ReflectionTechnique`] (the baselines) as a bench technique: its own
//! per-pass timings, the full G-buffer inputs.

use ppr_runtime::Camera;
use ppr_testbed::ReflectionTechnique;
use ppr_testbed::encoder_timer::EncoderTimer;

use crate::technique::{BenchFrame, BenchTechnique, Family};
use crate::timing::PassTime;

/// A boxed testbed technique with the bench's label and family.
pub struct TraitRunner {
    label: String,
    family: Family,
    inner: Box<dyn ReflectionTechnique>,
    reference_bounces: u32,
    /// With `timing=frame`: two encoder timestamps around everything the technique records.
    span: Option<EncoderTimer>,
}

impl TraitRunner {
    pub fn new(label: impl Into<String>, family: Family, inner: Box<dyn ReflectionTechnique>) -> Self {
        Self { label: label.into(), family, inner, reference_bounces: 1, span: None }
    }

    /// Timed as a whole frame, between two encoder timestamps around everything it records
    /// (as `ppr:timing=frame`), where the device has encoder timestamps; by its passes
    /// elsewhere. The technique then records none of its own pass timestamps, so that the
    /// span holds its work alone (as PPR's does: `DebugOptions::frame_span`).
    pub fn with_frame_timing(mut self, device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        self.span = EncoderTimer::new(device, queue);
        if self.span.is_some() {
            self.inner.stop_pass_timing();
        }
        self
    }

    /// Scored against the reference of `bounces` bounces (1 by default).
    pub fn with_reference_bounces(mut self, bounces: u32) -> Self {
        self.reference_bounces = bounces.max(1);
        self
    }
}

impl BenchTechnique for TraitRunner {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn family(&self) -> Family {
        self.family
    }

    fn reference_bounces(&self) -> u32 {
        self.reference_bounces
    }

    fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        camera: &Camera,
        size: [u32; 2],
    ) -> String {
        format!("{}: {}", self.inner.name(), self.inner.prepare(device, queue, camera, size))
    }

    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, frame: &BenchFrame<'_>) {
        if let Some(t) = &self.span {
            t.begin(encoder);
        }
        self.inner.encode(encoder, &frame.reflection);
        if let Some(t) = &self.span {
            t.end(encoder);
        }
    }

    fn read_timings(&mut self, device: &wgpu::Device) -> Option<Vec<PassTime>> {
        if let Some(t) = &self.span {
            return t.read_ms(device).map(|ms| vec![PassTime::new("frame", ms)]);
        }
        let passes: Vec<PassTime> =
            self.inner.timings(device)?.into_iter().map(|(name, ms)| PassTime::new(name, ms)).collect();
        (!passes.is_empty()).then_some(passes)
    }
}
