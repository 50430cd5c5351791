//! The breakdown of one frame of a bench scene, untimed (for tests and small-size looks on
//! the software adapter), beside full PPR's score as `compare` computes it.

use ppr_runtime::{Camera, PlanParams};
use ppr_testbed::image_io::ToneMap;
use ppr_testbed::{FrameImages, GpuContext, LevelRenderer};

use crate::error::BenchError;
use crate::error_causes::{CauseFrame, CauseRunner, ErrorBreakdown, PprVariants, classify};
use crate::quality::{Quality, ReferenceFrame};
use crate::scene::BenchScene;
use crate::technique_spec::TechniqueSpec;

/// One frame's breakdown and what it was computed from.
pub struct FrameBreakdown {
    /// The G-buffer and the exact reference.
    pub images: FrameImages,
    /// The PPR renders.
    pub variants: PprVariants,
    /// The breakdown (clamp tone map, `compare`'s default).
    pub breakdown: ErrorBreakdown,
    /// Full PPR's score ([`Quality::measure`] of `variants.full`).
    pub quality: Quality,
}

/// Renders `scene` from `camera` at `size` and breaks down the error of `spec` (full PPR,
/// `ppr` with any settings) over `plan_params`.
///
/// # Errors
/// `spec` is not full PPR, or a readback fails.
pub fn frame_breakdown(
    gpu: &GpuContext,
    scene: &BenchScene,
    camera: &Camera,
    size: [u32; 2],
    spec: &TechniqueSpec,
    plan_params: &PlanParams,
) -> Result<FrameBreakdown, BenchError> {
    let (device, queue) = (&gpu.device, &gpu.queue);
    let mut runner = CauseRunner::new(device, queue, &scene.reflectors, spec, *plan_params)?
        .ok_or_else(|| BenchError::Spec(format!("`{spec}` is not full PPR: no error breakdown")))?;
    let mut level = LevelRenderer::new(device, queue, &scene.level, &scene.reflectors);
    level.settings = scene.render_settings();
    level.render(device, queue, camera, size);
    let images = FrameImages::read(device, queue, &level)?;
    let variants = runner.render(device, queue, &level, camera, size)?;
    let frame =
        CauseFrame { images: &images, camera, reflectors: &scene.reflectors, tone_map: ToneMap::Clamp };
    let breakdown = classify(&frame, &variants)?;
    let reference = ReferenceFrame::new(images.clone());
    let quality = Quality::measure(&reference, &variants.full, ToneMap::Clamp)?;
    Ok(FrameBreakdown { images, variants, breakdown, quality })
}
