//! Every call `bevy_ppr` makes into `ppr-runtime`, in one file (the runtime's root API only).

use std::sync::Arc;

use ppr_format::{FormatError, ReflectorSet, ValidatedSet};
use ppr_runtime::{
    Camera, CameraError, Choice, DepthMode, FrameInputs, PassTimings, ReflectionRenderer, ReflectionSettings,
    RendererDesc,
};

/// One view's runtime: its renderer, the set it was given and what the last plan ran.
pub(crate) struct ViewRuntime {
    renderer: ReflectionRenderer,
    set: Option<Arc<ReflectorSet>>,
}

/// What the composite needs to know of a frame's plan.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PlanSummary {
    /// No reflector is visible: no pass runs and the output is not written.
    pub empty: bool,
    /// Only the tiles with a visible reflector are written: the output needs a clear.
    pub indirect: bool,
}

impl ViewRuntime {
    /// Builds the runtime's pipelines on Bevy's device; timestamps when it has them.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        let mut renderer = ReflectionRenderer::new(device, queue, &RendererDesc { timestamps: true });
        // No layer output is given: glass is skipped and water reflects in the main output.
        renderer.plan_params.layers = Choice::Off;
        Self { renderer, set: None }
    }

    /// Hands the runtime `set` when it is not the one it has (a reload is a new `Arc`).
    ///
    /// # Errors
    /// The runtime's check of the set; it then keeps the set it had.
    pub fn use_set(&mut self, set: &Arc<ReflectorSet>) -> Result<(), FormatError> {
        if self.set.as_ref().is_some_and(|s| Arc::ptr_eq(s, set)) {
            return Ok(());
        }
        self.set = Some(Arc::clone(set));
        self.renderer.set_reflectors(&ValidatedSet::new(ReflectorSet::clone(set))?);
        Ok(())
    }

    /// Plans the frame for a camera given by Bevy's matrices (reversed Z, as Bevy draws).
    ///
    /// # Errors
    /// [`CameraError::NotRigid`] when the camera's transform scales or shears.
    pub fn prepare(
        &mut self,
        world_from_view: glam::DMat4,
        clip_from_view: glam::Mat4,
        settings: ReflectionSettings,
        size: [u32; 2],
    ) -> Result<PlanSummary, CameraError> {
        let camera = Camera::from_matrices(world_from_view.inverse(), clip_from_view, DepthMode::Reversed)?;
        self.renderer.settings = settings;
        let plan = self.renderer.prepare(&camera, size);
        Ok(PlanSummary { empty: plan.is_empty(), indirect: plan.indirect })
    }

    /// Records the runtime's passes: `color` and `depth` (depth-only view) in, `output` out.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        color: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        output: &wgpu::TextureView,
    ) {
        self.renderer.encode(encoder, &FrameInputs::new(color, depth, output));
    }

    /// The GPU time of each pass of the last submitted frame, `(name, ms)`; waits for the
    /// GPU, so call it now and then.
    pub fn read_timings(&self) -> Option<Vec<(&'static str, f64)>> {
        let timings: PassTimings = self.renderer.read_timings()?;
        let mut passes: Vec<_> =
            timings.passes().iter().filter_map(|&(name, ms)| Some((name, ms?))).collect();
        passes.push(("total", timings.total_ms()));
        Some(passes)
    }
}

/// The output texture's format (`Rgba16Float`, alpha the confidence).
pub(crate) const OUTPUT_FORMAT: wgpu::TextureFormat = ppr_runtime::OUTPUT_FORMAT;
