//! One frame of a bench scene, untimed: the exact reference and each technique's reflection
//! scored as `compare` scores them (for tests and small-size investigations on the
//! software adapter).

use image::Rgba32FImage;
use ppr_runtime::{Camera, PlanParams};
use ppr_testbed::gbuffer_targets::Target;
use ppr_testbed::image_io::ToneMap;
use ppr_testbed::readback::read_rgba_f32;
use ppr_testbed::technique::REFLECTION_FORMAT;
use ppr_testbed::{FrameImages, GpuContext, LevelRenderer, ReflectionInputs};

use crate::error::BenchError;
use crate::quality::{Quality, ReferenceFrame};
use crate::scene::BenchScene;
use crate::technique::{BenchFrame, ReflectionOutput};
use crate::technique_spec::{TechniqueContext, TechniqueSpec, build_technique};

/// A technique's reflection of one frame and its score.
pub struct TechniqueFrame {
    /// The technique's label.
    pub label: String,
    /// Its output texture as read back (the reference's colour for `exact`).
    pub image: Rgba32FImage,
    /// Its score against the exact reference ([`Quality::measure`]).
    pub quality: Quality,
}

/// The reference of one frame and every technique's reflection of it.
pub struct SceneFrame {
    /// The G-buffer and the exact reference as read back.
    pub images: FrameImages,
    /// The reference and its masks, as `compare` builds them.
    pub reference: ReferenceFrame,
    /// One entry per technique, in the order asked.
    pub techniques: Vec<TechniqueFrame>,
}

/// Renders `scene` from `camera` at `size`, runs each technique once on that frame (PPR with
/// `plan_params`; `compare` uses the default) and scores it with the clamp tone map
/// (`compare`'s default).
///
/// # Errors
/// A technique cannot be built, or a readback fails.
pub fn render_scene_frame(
    gpu: &GpuContext,
    scene: &BenchScene,
    camera: &Camera,
    size: [u32; 2],
    techniques: &[TechniqueSpec],
    plan_params: &PlanParams,
) -> Result<SceneFrame, BenchError> {
    render_scene_frame_bounces(gpu, scene, camera, size, techniques, plan_params, 1)
}

/// As [`render_scene_frame`], every technique scored against the exact reference of
/// `reference_bounces` bounces (`RenderSettings::reference_bounces`).
///
/// # Errors
/// A technique cannot be built, or a readback fails.
pub fn render_scene_frame_bounces(
    gpu: &GpuContext,
    scene: &BenchScene,
    camera: &Camera,
    size: [u32; 2],
    techniques: &[TechniqueSpec],
    plan_params: &PlanParams,
    reference_bounces: u32,
) -> Result<SceneFrame, BenchError> {
    let (device, queue) = (&gpu.device, &gpu.queue);
    let mut level = LevelRenderer::new(device, queue, &scene.level, &scene.reflectors);
    level.settings = scene.render_settings();
    level.settings.reference_bounces = reference_bounces;
    level.render(device, queue, camera, size);
    let images = FrameImages::read(device, queue, &level)?;
    let reference = ReferenceFrame::new(images.clone());
    let ctx = TechniqueContext {
        device,
        queue,
        level: &scene.level,
        reflectors: &scene.reflectors,
        render: scene.render_settings(),
        plan_params: *plan_params,
    };
    let usage = wgpu::TextureUsages::STORAGE_BINDING
        | wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::COPY_SRC
        | wgpu::TextureUsages::COPY_DST;
    let output = Target::new(device, "one-frame technique output", size, REFLECTION_FORMAT, usage);
    let mut out = Vec::new();
    for spec in techniques {
        let mut technique = build_technique(spec, &ctx)?;
        let label = technique.label();
        if technique.output() == ReflectionOutput::Reference {
            out.push(TechniqueFrame {
                label,
                image: reference.reference.clone(),
                quality: Quality::exact(&reference),
            });
            continue;
        }
        // Cleared to "no reflection" so that no technique sees another's pixels.
        let zeros = vec![0u8; (size[0] * size[1]) as usize * 8];
        queue.write_texture(
            output.texture.as_image_copy(),
            &zeros,
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(size[0] * 8), rows_per_image: None },
            output.texture.size(),
        );
        technique.prepare(device, queue, camera, size);
        let frame = BenchFrame {
            level: &level,
            reflection: ReflectionInputs::from_gbuffer(level.gbuffer(), &output.view),
        };
        let mut encoder = device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("one-frame technique") });
        technique.encode(&mut encoder, &frame);
        queue.submit([encoder.finish()]);
        let image = read_rgba_f32(device, queue, &output.texture)?;
        let quality = Quality::measure(&reference, &image, ToneMap::Clamp)?;
        out.push(TechniqueFrame { label, image, quality });
    }
    Ok(SceneFrame { images, reference, techniques: out })
}
