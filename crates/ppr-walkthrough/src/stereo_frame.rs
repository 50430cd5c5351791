//! A headset's two eyes side by side (`--stereo`): each eye's scene drawn at half the
//! width, PPR for both from the one renderer (`prepare_stereo` plans both eyes, one
//! `encode_stereo` records both), each eye composited into an image of its own and copied
//! into its half of the output.
//!
//! What a VR renderer does the same way, but into the two layers of its eye textures.
//! The previous-frame feed is not used in stereo; the intermediate-buffer view shows the
//! right eye's buffer in both halves (the eyes share the runtime's buffers).

use std::sync::Arc;

use glam::Vec3;
use ppr_runtime::{Camera, Choice, FrameInputs, FramePlan};

use crate::frame_targets::{FrameTargets, Target};
use crate::fullscreen_pipeline::begin_output_pass;
use crate::screen_passes::{ScreenInputs, ScreenPasses};
use crate::view_mode::ViewMode;
use crate::walkthrough_renderer::WalkthroughRenderer;

/// Half the distance between the eyes, metres.
pub const HALF_IPD: f64 = 0.032;

/// The right eye's frame targets and the eyes' composited images (one pair per output
/// format).
pub struct StereoTargets {
    eye_size: [u32; 2],
    right: FrameTargets,
    images: Vec<(wgpu::TextureFormat, [Target; 2])>,
}

/// The left and right eyes of `head`: offset along its right vector, looking the same way.
pub fn eyes(head: &Camera) -> [Camera; 2] {
    let right = (head.rotation * Vec3::X).as_dvec3();
    [-HALF_IPD, HALF_IPD].map(|d| Camera { position: head.position + right * d, ..*head })
}

/// Each eye's size in an output of `size`: half the width (at least a pixel).
pub fn eye_size([w, h]: [u32; 2]) -> [u32; 2] {
    [(w / 2).max(1), h.max(1)]
}

impl WalkthroughRenderer {
    /// Renders both eyes of `head` side by side onto each output (`size` is the output's:
    /// each eye gets half its width), then submits. Returns the eyes' plans.
    ///
    /// Outputs need `COPY_DST` (each eye's composite is copied into its half).
    ///
    /// # Panics
    /// If `head`'s depth convention is not the one the renderer was built for.
    pub fn render_stereo(
        &mut self,
        head: &Camera,
        size: [u32; 2],
        mode: ViewMode,
        outputs: &[(&ScreenPasses, &wgpu::TextureView)],
    ) -> [Arc<FramePlan>; 2] {
        assert_eq!(head.projection.depth, self.forward.depth_mode(), "one depth convention per renderer");
        let eye_size = eye_size(size);
        let eyes = eyes(head);
        if self.targets.as_ref().is_none_or(|t| t.size != eye_size) {
            self.targets = Some(FrameTargets::new(&self.device, eye_size));
        }
        if self.stereo.as_ref().is_none_or(|s| s.eye_size != eye_size) {
            let right = FrameTargets::new(&self.device, eye_size);
            self.stereo = Some(StereoTargets { eye_size, right, images: Vec::new() });
        }
        self.previous = None;

        // 1. Each eye's scene, a submit each: the draws' camera-relative uniforms are
        //    written through the queue, so each eye's must land before its pass.
        for (k, eye) in eyes.iter().enumerate() {
            self.meshes.update_camera(&self.queue, eye.position);
            self.forward.prepare(&self.queue, eye, eye_size, &self.light);
            let targets = if k == 0 { self.targets.as_ref() } else { self.stereo.as_ref().map(|s| &s.right) };
            let mut encoder = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("walkthrough eye scene"),
            });
            self.forward.encode(
                &mut encoder,
                targets.expect("allocated above"),
                &self.meshes,
                eye.projection.far_depth(),
            );
            self.queue.submit([encoder.finish()]);
        }

        // 2. PPR for both eyes: one plan each, one encode for both.
        self.ppr.plan_params.indirect =
            if mode == ViewMode::Intermediate { Choice::Off } else { Choice::Auto };
        let plans = self.ppr.prepare_stereo([&eyes[0], &eyes[1]], eye_size);
        let stereo = self.stereo.as_mut().expect("allocated above");
        let targets = [self.targets.as_ref().expect("allocated above"), &stereo.right];
        let mut encoder = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("walkthrough stereo frame"),
        });
        for (t, plan) in targets.iter().zip(&plans) {
            if plan.indirect {
                let _ = begin_output_pass(
                    &mut encoder,
                    "walkthrough clear ppr output",
                    &t.reflection.view,
                    wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                );
            }
        }
        let inputs = targets.map(|t| FrameInputs::new(&t.color.view, &t.depth.view, &t.reflection.view));
        self.ppr.encode_stereo(&mut encoder, [&inputs[0], &inputs[1]]);

        // 3. Each eye composited into its own image, copied into its half of the output.
        for (passes, output) in outputs {
            let texture = output.texture();
            let format = texture.format();
            if !stereo.images.iter().any(|(f, _)| *f == format) {
                let image = |label| {
                    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
                    Target::new(&self.device, label, eye_size, format, usage)
                };
                stereo.images.push((format, [image("walkthrough left eye"), image("walkthrough right eye")]));
            }
            let images = &stereo.images.iter().find(|(f, _)| *f == format).expect("made above").1;
            for k in 0..2 {
                let inputs = ScreenInputs { targets: targets[k], ppr: &self.ppr, plan: &plans[k], mode };
                passes.encode(&self.queue, &mut encoder, &inputs, &images[k].view);
                encoder.copy_texture_to_texture(
                    images[k].texture.as_image_copy(),
                    wgpu::TexelCopyTextureInfo {
                        texture,
                        mip_level: 0,
                        origin: wgpu::Origin3d { x: k as u32 * eye_size[0], y: 0, z: 0 },
                        aspect: wgpu::TextureAspect::All,
                    },
                    wgpu::Extent3d {
                        width: eye_size[0].min(texture.width().saturating_sub(k as u32 * eye_size[0])),
                        height: eye_size[1].min(texture.height()),
                        depth_or_array_layers: 1,
                    },
                );
            }
        }
        self.queue.submit([encoder.finish()]);
        plans
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn the_eyes_are_64_mm_apart_and_each_gets_half_the_width() {
        let head = Camera::look_at(DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0), Vec3::Y, Default::default());
        let [l, r] = eyes(&head);
        // Looking down +x, the right vector is +z.
        assert!((r.position - l.position - DVec3::new(0.0, 0.0, 0.064)).length() < 1e-6, "{l:?} {r:?}");
        assert_eq!(eye_size([1280, 720]), [640, 720]);
        assert_eq!(eye_size([1, 1]), [1, 1]);
    }
}
