//! PPR from `ppr-runtime` (through the testbed's [`PprTechnique`]) as a bench technique.

use ppr_format::ReflectorSet;
use ppr_runtime::{Camera, PlanParams, ReflectionRenderer, ReflectionSettings};
use ppr_testbed::{PprTechnique, ReflectionTechnique};

use crate::error::BenchError;
use crate::technique::{BenchFrame, BenchTechnique, Family};
use crate::timing::PassTime;

/// PPR with one set of reflection-pass steps and plan parameters.
pub struct PprRunner {
    label: String,
    technique: PprTechnique,
    /// Scored against this reference instead of the one of its bounces.
    reference_bounces: Option<u32>,
    /// For reading back what the hidden-shape pass skipped.
    queue: wgpu::Queue,
    /// Whether this prepared camera's skipped tests were logged.
    hidden_logged: bool,
}

impl PprRunner {
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        reflectors: &ReflectorSet,
        label: impl Into<String>,
        settings: ReflectionSettings,
        plan_params: PlanParams,
    ) -> Result<Self, BenchError> {
        let mut technique = PprTechnique::new(device, queue, reflectors, settings)?;
        technique.renderer().plan_params = plan_params;
        Ok(Self {
            label: label.into(),
            technique,
            reference_bounces: None,
            queue: queue.clone(),
            hidden_logged: false,
        })
    }

    /// Frames of the same camera per bench frame, each fed the previous one's composite
    /// ([`PprTechnique::set_bounces`]); the timings are the last frame's passes and the
    /// copy that feeds it, what a game pays per frame.
    pub fn set_bounces(&mut self, bounces: u32) {
        self.technique.set_bounces(bounces);
    }

    /// Scored against the reference of `bounces` bounces (default: as many as it feeds back).
    pub fn set_reference_bounces(&mut self, bounces: u32) {
        self.reference_bounces = Some(bounces.max(1));
    }

    /// Logs, once per prepared camera, how many tests the hidden-shape pass skipped (the
    /// bench's logs keep what the reports do not).
    fn log_hidden_shapes(&mut self, device: &wgpu::Device) {
        let renderer = self.technique.renderer();
        let Some(plan) = renderer.plan().cloned().filter(|p| p.hidden_culling) else {
            return;
        };
        let Some(buffer) = renderer.seen_tests_buffer() else {
            return;
        };
        if let Ok(seen) = crate::buffer_readback::read_buffer_u32(device, &self.queue, buffer) {
            let skipped = plan
                .hidden_regions
                .iter()
                .zip(&seen)
                .filter(|&(r, &s)| *r != ppr_runtime::HiddenRegion::KEEP && s == 0)
                .count();
            eprintln!("{}: hidden shapes: {skipped} of {} tests skipped", self.label, plan.tested.len());
        }
    }

    /// The runtime renderer (plan, intermediate buffer, active tiles).
    pub fn renderer(&mut self) -> &mut ReflectionRenderer {
        self.technique.renderer()
    }
}

impl BenchTechnique for PprRunner {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn family(&self) -> Family {
        Family::Ppr
    }

    fn reference_bounces(&self) -> u32 {
        self.reference_bounces.unwrap_or_else(|| self.technique.bounces())
    }

    fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        camera: &Camera,
        size: [u32; 2],
    ) -> String {
        self.hidden_logged = false;
        self.technique.prepare(device, queue, camera, size)
    }

    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, frame: &BenchFrame<'_>) {
        self.technique.encode(encoder, &frame.reflection);
    }

    fn read_timings(&mut self, device: &wgpu::Device) -> Option<Vec<PassTime>> {
        if !std::mem::replace(&mut self.hidden_logged, true) {
            self.log_hidden_shapes(device);
        }
        let passes: Vec<PassTime> =
            self.technique.timings(device)?.into_iter().map(|(name, ms)| PassTime::new(name, ms)).collect();
        (!passes.is_empty()).then_some(passes)
    }
}
