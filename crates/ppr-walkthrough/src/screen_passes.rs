//! The passes that draw onto an output image of one format: composite (or the
//! intermediate-buffer view) and the text overlay. The window has one set for its surface
//! format; screenshots have one for `Rgba8UnormSrgb`.

use ppr_runtime::{FramePlan, ReflectionRenderer};

use crate::composite_pass::{CompositeMode, CompositePass};
use crate::frame_targets::FrameTargets;
use crate::intermediate_view::IntermediateView;
use crate::overlay_pass::OverlayPass;
use crate::view_mode::ViewMode;

/// Composite, intermediate view and overlay for one output format.
pub struct ScreenPasses {
    composite: CompositePass,
    intermediate: IntermediateView,
    pub overlay: OverlayPass,
}

/// What the screen passes read besides the frame targets.
pub struct ScreenInputs<'a> {
    pub targets: &'a FrameTargets,
    pub ppr: &'a ReflectionRenderer,
    pub plan: &'a FramePlan,
    pub mode: ViewMode,
}

impl ScreenPasses {
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, format: wgpu::TextureFormat) -> Self {
        Self {
            composite: CompositePass::new(device, queue, format),
            intermediate: IntermediateView::new(device, queue, format),
            overlay: OverlayPass::new(device, format),
        }
    }

    /// Records the frame onto `output` (the size of the frame targets).
    pub fn encode(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &ScreenInputs<'_>,
        output: &wgpu::TextureView,
    ) {
        let size = inputs.targets.size;
        let intermediate = inputs.ppr.intermediate_buffer().filter(|_| !inputs.plan.is_empty());
        match (inputs.mode.composite_mode(), intermediate) {
            (Some(mode), _) => {
                self.composite.encode(encoder, inputs.targets, output, mode, !inputs.plan.is_empty());
            }
            (None, Some(buffer)) => {
                self.intermediate.encode(encoder, buffer, size, &inputs.plan.encoding, output);
            }
            // Nothing was projected this frame (the buffer was not even cleared): no offsets.
            (None, None) => {
                self.composite.encode(encoder, inputs.targets, output, CompositeMode::ReflectionBuffer, false)
            }
        }
        self.overlay.encode(queue, encoder, output, size);
    }
}
