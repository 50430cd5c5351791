//! The game's renderer with PPR in it: what to copy.
//!
//! Per frame:
//!
//! 1. the game renders its scene: the forward pass writes linear HDR colour
//!    (`Rgba16Float`), a reflection weight and depth (`Depth32Float`);
//! 2. PPR, call 1 of 2: `ReflectionRenderer::prepare(&camera, [w, h])` plans the frame on
//!    the CPU (culling, which passes run) and uploads what the GPU needs;
//! 3. PPR, call 2 of 2: `ReflectionRenderer::encode(&mut encoder, &FrameInputs { color,
//!    depth, output })` records the compute passes after the scene, in the same encoder;
//! 4. the game composites: `mix(scene, reflection.rgb, weight × reflection.a)`, tone map,
//!    onto the swapchain, then its UI (here: the text overlay).
//!
//! PPR never sees the meshes, the materials or the swapchain: only colour, depth and its
//! output texture. With [`WalkthroughRenderer::feed_previous_frame`] its colour is the
//! previous frame's composite instead of step 1's ([`crate::previous_frame`]).

use std::sync::Arc;

use ppr_format::{FormatError, ReflectorSet, ValidatedSet};
use ppr_runtime::{Camera, Choice, DepthMode, FrameInputs, FramePlan, ReflectionRenderer, RendererDesc};
use ppr_scene_gpu::LevelMeshes;

use crate::forward_pass::{FORWARD_SURFACES, ForwardPass, SceneLight};
use crate::frame_targets::FrameTargets;
use crate::fullscreen_pipeline::begin_output_pass;
use crate::gltf_level::LevelData;
use crate::previous_frame::PreviousFrame;
use crate::screen_passes::{ScreenInputs, ScreenPasses};
use crate::view_mode::ViewMode;

/// The level, its passes and PPR on one device.
pub struct WalkthroughRenderer {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    pub(crate) meshes: LevelMeshes,
    pub(crate) forward: ForwardPass,
    /// PPR: settings (holes, filtering, anti-bleeding) and plan parameters are public.
    pub ppr: ReflectionRenderer,
    /// The sun of the forward pass.
    pub light: SceneLight,
    /// The (left eye's, with `render_stereo`) frame targets.
    pub(crate) targets: Option<FrameTargets>,
    /// The right eye's targets and each eye's composited image (`stereo_frame.rs`).
    pub(crate) stereo: Option<crate::stereo_frame::StereoTargets>,
    /// PPR reads the previous frame's composite as its colour (one more bounce per frame
    /// in a mirror seen in a mirror); the first frame after switching on reads the scene.
    pub feed_previous_frame: bool,
    pub(crate) previous: Option<PreviousFrame>,
}

impl WalkthroughRenderer {
    /// Uploads the level, builds the passes and hands PPR the reflectors (an empty set
    /// when there is none yet: PPR then plans empty frames and dispatches nothing).
    ///
    /// # Errors
    /// The runtime refuses a set that breaks an invariant of the format.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        level: &LevelData,
        reflectors: Option<&ValidatedSet>,
        depth: DepthMode,
    ) -> Result<Self, FormatError> {
        let forward = ForwardPass::new(device, depth);
        let meshes = LevelMeshes::new(device, queue, &forward.layouts, level, &FORWARD_SURFACES);
        let mut ppr = ReflectionRenderer::new(device, queue, &RendererDesc { timestamps: true });
        // Glass panels and water planes as separate layers need `FrameInputs::layer_output`
        // and a composite that knows their surfaces; this walkthrough keeps to the main
        // buffer: water is reflected there and glass panels are skipped.
        ppr.plan_params.layers = Choice::Off;
        match reflectors {
            Some(set) => ppr.set_reflectors(set),
            None => ppr.set_reflectors(&ValidatedSet::new(ReflectorSet::new(""))?),
        }
        Ok(Self {
            device: device.clone(),
            queue: queue.clone(),
            meshes,
            forward,
            ppr,
            light: SceneLight::default(),
            targets: None,
            stereo: None,
            feed_previous_frame: false,
            previous: None,
        })
    }

    /// Takes a new reflector set (hot reload): cheap, nothing is recompiled.
    ///
    /// The set was validated when it was read (`ValidatedSet`), so this cannot fail.
    pub fn set_reflectors(&mut self, reflectors: &ValidatedSet) {
        self.ppr.set_reflectors(reflectors);
    }

    /// The targets of the last frame (scene colour, weight, depth, PPR output).
    pub fn targets(&self) -> Option<&FrameTargets> {
        self.targets.as_ref()
    }

    /// Renders one frame seen by `camera` at `size` and records it onto each output (the
    /// swapchain image, and a screenshot target when one is asked for), then submits.
    /// Returns the frame plan.
    ///
    /// # Panics
    /// If `camera`'s depth convention is not the one the renderer was built for.
    pub fn render(
        &mut self,
        camera: &Camera,
        size: [u32; 2],
        mode: ViewMode,
        outputs: &[(&ScreenPasses, &wgpu::TextureView)],
    ) -> Arc<FramePlan> {
        assert_eq!(camera.projection.depth, self.forward.depth_mode(), "one depth convention per renderer");
        let size = [size[0].max(1), size[1].max(1)];
        if self.targets.as_ref().is_none_or(|t| t.size != size) {
            self.targets = Some(FrameTargets::new(&self.device, size));
        }
        if !self.feed_previous_frame || self.previous.as_ref().is_some_and(|p| p.size() != size) {
            self.previous = None;
        }
        if self.feed_previous_frame && self.previous.is_none() {
            self.previous = Some(PreviousFrame::new(&self.device, &self.queue, size));
        }
        let targets = self.targets.as_ref().expect("allocated above");

        // 1. The game's scene: camera-relative draws, lit colour, reflection weight, depth.
        self.meshes.update_camera(&self.queue, camera.position);
        self.forward.prepare(&self.queue, camera, size, &self.light);

        // 2. PPR, call 1 of 2: plan the frame on the CPU and upload (before the encoder).
        //    The intermediate-buffer view needs the whole buffer cleared: no indirect dispatch.
        self.ppr.plan_params.indirect =
            if mode == ViewMode::Intermediate { Choice::Off } else { Choice::Auto };
        let plan = self.ppr.prepare(camera, size);

        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("walkthrough frame") });
        self.forward.encode(&mut encoder, targets, &self.meshes, camera.projection.far_depth());

        // With indirect dispatch PPR writes only the tiles that show a visible reflector;
        // clear its output so no other pixel keeps an old frame's reflection (a reflector
        // just disabled in the inspector, say). A full dispatch writes every pixel.
        if plan.indirect {
            let _ = begin_output_pass(
                &mut encoder,
                "walkthrough clear ppr output",
                &targets.reflection.view,
                wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
            );
        }

        // 3. PPR, call 2 of 2: record clear, projection and reflection after the scene.
        //    Nothing is recorded when the plan is empty (then `reflection` is stale: the
        //    composite is told so).
        let color =
            self.previous.as_ref().and_then(PreviousFrame::color_input).unwrap_or(&targets.color.view);
        self.ppr
            .encode(&mut encoder, &FrameInputs::new(color, &targets.depth.view, &targets.reflection.view));
        if let Some(previous) = &mut self.previous {
            previous.encode(&mut encoder, targets, !plan.is_empty());
        }

        // 4. The game's composite and UI onto each output.
        let inputs = ScreenInputs { targets, ppr: &self.ppr, plan: &plan, mode };
        for (passes, output) in outputs {
            passes.encode(&self.queue, &mut encoder, &inputs, output);
        }
        self.queue.submit([encoder.finish()]);
        plan
    }
}
