//! The viewport's GPU side: the testbed's `LevelRenderer` (G-buffer, exact reference)
//! and `PprTechnique` (the runtime's `ReflectionRenderer`) on eframe's wgpu device,
//! composited and read back into an image egui shows.

use egui::ColorImage;
use ppr_format::ReflectorSet;
use ppr_runtime::{Camera, PassTimings};
use ppr_testbed::composite::{CompositeInputs, CompositeParams, CompositePass};
use ppr_testbed::gbuffer_targets::Target;
use ppr_testbed::image_io::{ToneMap, difference_image, to_srgb8};
use ppr_testbed::metrics::{ImageComparison, compare};
use ppr_testbed::readback::read_rgba_f32;
use ppr_testbed::render_job::hole_share;
use ppr_testbed::technique::{REFLECTION_FORMAT, ReflectionInputs, ReflectionTechnique};
use ppr_testbed::{FrameImages, Level, LevelRenderer, PprTechnique, clear_target};

use crate::error::InspectorError;
use crate::preview::{PreviewMode, PreviewSettings};

/// How the difference image scales errors (as `ppr-render` does).
const DIFFERENCE_SCALE: f32 = 4.0;

/// PPR against the reference, over on-screen reflector pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreviewQuality {
    /// PSNR, MAE and FLIP.
    pub comparison: ImageComparison,
    /// Share of those pixels where PPR found no reflection.
    pub holes: f64,
}

/// One rendered viewport image with what the frame did.
#[derive(Clone)]
pub struct PreviewFrame {
    /// The image, sRGB.
    pub image: ColorImage,
    /// The runtime's frame plan (its `Display`).
    pub plan: String,
    /// GPU time per pass, when the device measures it.
    pub timings: Option<PassTimings>,
    /// Which timed passes ran (in [`PassTimings::passes`] order): a pass that ran without
    /// a time had timestamps the adapter got wrong.
    pub passes_recorded: [bool; ppr_runtime::timestamps::TIMED_PASSES as usize],
    /// Whether the device has timestamps at all.
    pub timestamps: bool,
    /// Quality against the reference (difference mode only).
    pub quality: Option<PreviewQuality>,
}

struct SizedTargets {
    size: [u32; 2],
    reflection: Target,
    output: Target,
}

/// A level on the GPU, ready to render previews of any reflector set.
pub struct ViewportRenderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    level: LevelRenderer,
    ppr: PprTechnique,
    composite: CompositePass,
    targets: Option<SizedTargets>,
}

impl ViewportRenderer {
    /// Uploads `level` and builds every pass.
    ///
    /// # Errors
    /// [`InspectorError::InvalidLevel`] when the level breaks the testbed's invariants.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        level: &Level,
        level_path: &std::path::Path,
        set: &ReflectorSet,
    ) -> Result<Self, InspectorError> {
        level
            .validate()
            .map_err(|reason| InspectorError::InvalidLevel { path: level_path.to_owned(), reason })?;
        within_error_scope(device, || {
            Ok(Self {
                device: device.clone(),
                queue: queue.clone(),
                level: LevelRenderer::new(device, queue, level, set),
                ppr: PprTechnique::new(device, queue, set, ppr_runtime::ReflectionSettings::ALL)?,
                composite: CompositePass::new(device),
                targets: None,
            })
        })
    }

    /// Replaces the reflector set (after an edit).
    ///
    /// # Errors
    /// [`InspectorError::Gpu`] when the device refuses the new buffers.
    pub fn set_reflectors(&mut self, set: &ReflectorSet) -> Result<(), InspectorError> {
        let device = self.device.clone();
        within_error_scope(&device, || {
            // The runtime checks the set first: nothing changes if it refuses it.
            let valid = ppr_format::ValidatedSet::new(set.clone())?;
            self.ppr.renderer().set_reflectors(&valid);
            self.level.set_reflectors(&self.device, set);
            Ok(())
        })
    }

    fn targets(&mut self, size: [u32; 2]) -> &SizedTargets {
        if self.targets.as_ref().is_none_or(|t| t.size != size) {
            let usage = wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC;
            let reflection =
                Target::new(&self.device, "inspector reflection", size, REFLECTION_FORMAT, usage);
            let output = CompositePass::output_target(&self.device, size, "inspector composite");
            self.targets = Some(SizedTargets { size, reflection, output });
        }
        self.targets.as_ref().expect("allocated above")
    }

    /// Renders the frame `camera` sees at `size` as `settings` asks, and reads it back.
    ///
    /// # Errors
    /// A read-back or image error from the testbed.
    pub fn render(
        &mut self,
        camera: &Camera,
        size: [u32; 2],
        settings: &PreviewSettings,
    ) -> Result<PreviewFrame, InspectorError> {
        let device = self.device.clone();
        within_error_scope(&device, || self.render_frame(camera, size, settings))
    }

    fn render_frame(
        &mut self,
        camera: &Camera,
        size: [u32; 2],
        settings: &PreviewSettings,
    ) -> Result<PreviewFrame, InspectorError> {
        let size = [size[0].max(1), size[1].max(1)];
        let (device, queue) = (self.device.clone(), self.queue.clone());
        self.targets(size);
        self.level.prepare(&device, &queue, camera, size);
        self.ppr.renderer().settings = settings.reflection;
        let plan = self.ppr.prepare(&device, &queue, camera, size);
        let targets = self.targets.as_ref().expect("allocated above");

        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("inspector frame") });
        clear_target(&mut encoder, &targets.reflection.view, "inspector reflection clear");
        self.level.encode_gbuffer(&mut encoder);
        {
            let inputs = ReflectionInputs::from_gbuffer(self.level.gbuffer(), &targets.reflection.view);
            self.ppr.encode(&mut encoder, &inputs);
        }
        if settings.mode.needs_reference() {
            self.level.encode_reference(&mut encoder);
        }
        queue.submit([encoder.finish()]);
        let timestamps = self.ppr.renderer().has_timestamps();
        let timings = self.ppr.renderer().read_timings();
        let passes_recorded = self.ppr.renderer().passes_recorded();

        let tone_map = ToneMap::default();
        let params = CompositeParams { reflectivity: settings.reflectivity };
        let g = self.level.gbuffer();
        let composite = |reflection: &wgpu::TextureView| {
            let inputs = CompositeInputs {
                scene_color: &g.color.view,
                reflection,
                reflector_id: &g.reflector_id.view,
                output: &targets.output.view,
            };
            self.composite.run(&device, &queue, &inputs, &params);
            read_rgba_f32(&device, &queue, &targets.output.texture)
        };
        let mut quality = None;
        let rgb = match settings.mode {
            PreviewMode::Scene => to_srgb8(&read_rgba_f32(&device, &queue, &g.color.texture)?, tone_map),
            PreviewMode::Ppr => to_srgb8(&composite(&targets.reflection.view)?, tone_map),
            PreviewMode::Reference => to_srgb8(&composite(&self.level.reference().color.view)?, tone_map),
            PreviewMode::Difference => {
                let images = FrameImages::read(&device, &queue, &self.level)?;
                let raw = read_rgba_f32(&device, &queue, &targets.reflection.texture)?;
                let on_screen = images.on_screen_mask();
                quality = Some(PreviewQuality {
                    comparison: compare(&images.reference, &raw, &on_screen, tone_map)?,
                    holes: hole_share(&raw, &on_screen),
                });
                difference_image(
                    &raw,
                    &images.reference,
                    &images.reflector_mask(),
                    DIFFERENCE_SCALE,
                    tone_map,
                )?
            }
        };
        let image = ColorImage::from_rgb([size[0] as usize, size[1] as usize], rgb.as_raw());
        Ok(PreviewFrame { image, plan, timings, passes_recorded, timestamps, quality })
    }
}

/// Runs `work` with the device's validation and out-of-memory errors caught: they become
/// [`InspectorError::Gpu`] instead of wgpu's default panic.
fn within_error_scope<T>(
    device: &wgpu::Device,
    work: impl FnOnce() -> Result<T, InspectorError>,
) -> Result<T, InspectorError> {
    let memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let result = work();
    let validation = pollster::block_on(validation.pop());
    let memory = pollster::block_on(memory.pop());
    match (validation.or(memory), result) {
        (Some(e), _) => Err(InspectorError::Gpu(e.to_string())),
        (None, result) => result,
    }
}
