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
        Ok(Self { label: label.into(), technique, reference_bounces: None })
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

    /// Records the reflection in a compute pass of its own on every frame, so that the
    /// projection is timed apart (for the suites that report it alone: `scaling`,
    /// `extract-trade`). The runtime's default records them in one pass on frames without
    /// layers, about 0.006 ms faster (`DebugOptions::reflection_own_pass`).
    pub fn time_projection_apart(&mut self) {
        self.technique.renderer().debug.reflection_own_pass = true;
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
        self.technique.prepare(device, queue, camera, size)
    }

    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, frame: &BenchFrame<'_>) {
        self.technique.encode(encoder, &frame.reflection);
    }

    fn read_timings(&mut self, device: &wgpu::Device) -> Option<Vec<PassTime>> {
        let passes: Vec<PassTime> =
            self.technique.timings(device)?.into_iter().map(|(name, ms)| PassTime::new(name, ms)).collect();
        (!passes.is_empty()).then_some(passes)
    }
}
