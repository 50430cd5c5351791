//! The previous frame's composited image as PPR's colour input (a mirror seen in a mirror
//! then shows its own reflection: one more bounce per frame). A frame composites its
//! reflection over the scene colour, then copies the result into the texture the next
//! frame's PPR reads; the copy is what a game pays, timed here with encoder timestamps.

use crate::composite::{COMPOSITE_FORMAT, CompositeInputs, CompositeParams, CompositePass};
use crate::encoder_timer::EncoderTimer;
use crate::gbuffer_targets::{COLOR_FORMAT, Target};

/// Label of the copy's time in a technique's timings.
pub const PREVIOUS_FRAME_COPY: &str = "previous-frame copy";

/// What one frame's feed reads.
pub struct FeedInputs<'a> {
    /// This frame's scene colour (the composite's fallback).
    pub scene_color: &'a wgpu::TextureView,
    /// This frame's reflection (colour, confidence in alpha).
    pub reflection: &'a wgpu::TextureView,
    /// The reflector id: only reflector pixels get the reflection.
    pub reflector_id: &'a wgpu::TextureView,
}

/// The composited frame and its copy, the next frame's colour input.
pub struct PreviousFrameFeed {
    composite: CompositePass,
    params: CompositeParams,
    targets: Option<FeedTargets>,
    timer: Option<EncoderTimer>,
}

struct FeedTargets {
    size: [u32; 2],
    composited: Target,
    previous: Target,
}

impl PreviousFrameFeed {
    /// A feed that composites with `params` (the testbed's composite by default).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, params: CompositeParams) -> Self {
        Self {
            composite: CompositePass::new(device),
            params,
            targets: None,
            timer: EncoderTimer::new(device, queue),
        }
    }

    /// The previous frame's composited image (`Rgba16Float`, texture binding), once
    /// [`Self::encode`] has run at `size`.
    pub fn previous(&self, size: [u32; 2]) -> Option<&wgpu::TextureView> {
        self.targets.as_ref().filter(|t| t.size == size).map(|t| &t.previous.view)
    }

    /// Records the composite of `inputs` at `size` and its copy into the next frame's
    /// colour input (timed when `timed`: only the last copy of a submission can be read).
    pub fn encode(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &FeedInputs<'_>,
        size: [u32; 2],
        timed: bool,
    ) {
        if self.targets.as_ref().is_none_or(|t| t.size != size) {
            let previous = Target::new(
                device,
                "previous composited frame",
                size,
                COLOR_FORMAT,
                wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            );
            let composited = Target::new(
                device,
                "composited frame",
                size,
                COMPOSITE_FORMAT,
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            );
            self.targets = Some(FeedTargets { size, composited, previous });
        }
        let t = self.targets.as_ref().expect("created above");
        let composite = CompositeInputs {
            scene_color: inputs.scene_color,
            reflection: inputs.reflection,
            reflector_id: inputs.reflector_id,
            output: &t.composited.view,
        };
        let bind_group = self.composite.bind_group(device, &composite, &self.params);
        self.composite.encode(encoder, &bind_group, &t.composited.view);
        let timer = self.timer.as_ref().filter(|_| timed);
        if let Some(timer) = timer {
            timer.begin(encoder);
        }
        encoder.copy_texture_to_texture(
            t.composited.texture.as_image_copy(),
            t.previous.texture.as_image_copy(),
            t.composited.texture.size(),
        );
        if let Some(timer) = timer {
            timer.end(encoder);
        }
    }

    /// Waits for the submitted frame and returns the last timed copy's milliseconds
    /// (`None` without encoder timestamps, or when the adapter's timer went backwards).
    pub fn read_copy_ms(&self, device: &wgpu::Device) -> Option<f64> {
        self.timer.as_ref()?.read_ms(device)
    }
}
