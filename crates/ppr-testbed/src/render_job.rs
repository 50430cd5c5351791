//! What `ppr-render` does: render a level with a reflection technique and with the exact
//! reference, write the images, and measure the technique against the reference.

use std::path::{Path, PathBuf};
use std::time::Instant;

use image::Rgba32FImage;
use ppr_format::ReflectorSet;
use ppr_runtime::Camera;

use crate::TestbedError;
use crate::camera_spec::{ProjectionChoice, pick_camera};
use crate::composite::{CompositeInputs, CompositeParams, CompositePass};
use crate::frame_images::FrameImages;
use crate::gbuffer_targets::Target;
use crate::gpu::GpuContext;
use crate::image_io::{ToneMap, difference_image, write_exr, write_png, write_rgb8};
use crate::level::Level;
use crate::metrics::{ImageComparison, compare};
use crate::pixel_mask::PixelMask;
use crate::readback::read_rgba_f32;
use crate::renderer::{FrameSummary, LevelRenderer, RenderSettings};
use crate::technique::{REFLECTION_FORMAT, ReflectionInputs, ReflectionTechnique, format_timings};

/// Everything `ppr-render` was asked to do.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderJob {
    /// The glTF level.
    pub level: PathBuf,
    /// Its reflector set (`*.ppr.json`).
    pub reflectors: PathBuf,
    /// A camera name, `"eye=...;target=...;fov=..."`, or `None` for the level's first camera.
    pub camera: Option<String>,
    /// Width and height in pixels.
    pub size: [u32; 2],
    /// Depth convention and far plane.
    pub projection: ProjectionChoice,
    /// Path of the composited frame (`frame.png`); the other files are named after it.
    pub output: PathBuf,
    /// How reflections are mixed into the frames.
    pub composite: CompositeParams,
    /// Tone mapping of the PNG files and the metrics.
    pub tone_map: ToneMap,
    /// Lighting, reflector mask and reference tolerances.
    pub render: RenderSettings,
    /// Render even when the set's `source.hash` is not the level file's (the set was
    /// extracted from other bytes): a warning in the report instead of an error.
    pub accept_level_mismatch: bool,
}

/// The files a job writes, named after its output path `frame.png`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OutputFiles {
    /// `frame.png`: composited with the technique's reflection (no reflection without one).
    pub frame: PathBuf,
    /// `frame.reflection.png`: the technique's raw reflection buffer.
    pub reflection_png: PathBuf,
    /// `frame.reflection.exr`: the same, raw float.
    pub reflection_exr: PathBuf,
    /// `frame.reference.png`: composited with the exact reflection.
    pub reference: PathBuf,
    /// `frame.reference.exr`: the exact reflection buffer, raw float.
    pub reference_exr: PathBuf,
    /// `frame.diff.png`: technique vs reference over reflector pixels.
    pub diff: PathBuf,
}

impl OutputFiles {
    /// The names for output path `frame.png` (`frame.reflection.png`, ...).
    pub fn for_output(output: &Path) -> Self {
        let stem = output.with_extension("");
        let named = |suffix: &str| {
            let mut s = stem.clone().into_os_string();
            s.push(suffix);
            PathBuf::from(s)
        };
        Self {
            frame: output.to_owned(),
            reflection_png: named(".reflection.png"),
            reflection_exr: named(".reflection.exr"),
            reference: named(".reference.png"),
            reference_exr: named(".reference.exr"),
            diff: named(".diff.png"),
        }
    }
}

/// What a job found.
#[derive(Clone, Debug)]
pub struct RenderReport {
    /// The adapter, as [`GpuContext::describe`] says.
    pub adapter: String,
    /// The camera used.
    pub camera: Camera,
    /// What the reference rendered.
    pub frame: FrameSummary,
    /// The technique's name and plan, if one ran.
    pub technique: Option<(String, String)>,
    /// The technique's GPU time per pass (name, milliseconds), if measured.
    pub timings: Option<Vec<(String, f64)>>,
    /// Technique vs reference over reflector pixels whose reflected point is on screen.
    pub on_screen: Option<ImageComparison>,
    /// Technique vs reference over the other reflector pixels (off screen, hidden, background).
    pub off_screen: Option<ImageComparison>,
    /// Share of on-screen reflector pixels where the technique found no reflection (alpha 0; PPR's alpha is a confidence, > 0
    /// wherever one was found).
    pub on_screen_holes: Option<f64>,
    /// Reflector pixels, and those whose reflected point is on screen.
    pub reflector_pixels: (usize, usize),
    /// Files written.
    pub files: Vec<PathBuf>,
    /// Wall-clock seconds of the whole job (loading included).
    pub seconds: f64,
    /// What the job accepted but the user should know (a set extracted from other bytes).
    pub warnings: Vec<String>,
}

impl std::fmt::Display for RenderReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for w in &self.warnings {
            writeln!(f, "warning: {w}")?;
        }
        writeln!(f, "adapter: {}", self.adapter)?;
        writeln!(
            f,
            "reference: {} of {} reflector planes rendered; {} reflector pixels, {} with the reflected point on screen",
            self.frame.rendered_planes.len(),
            self.frame.planes,
            self.reflector_pixels.0,
            self.reflector_pixels.1
        )?;
        match &self.technique {
            Some((name, plan)) => writeln!(f, "{name}: {plan}")?,
            None => writeln!(f, "no reflection technique ran: frame.png has no reflections")?,
        }
        if let Some(t) = &self.timings {
            writeln!(f, "GPU timings: {}", format_timings(t))?;
        }
        if let Some(c) = &self.on_screen {
            writeln!(f, "on-screen reflector pixels:  {c}")?;
        }
        if let Some(h) = self.on_screen_holes {
            writeln!(f, "on-screen pixels without a reflection: {:.2}%", h * 100.0)?;
        }
        if let Some(c) = &self.off_screen {
            writeln!(f, "off-screen reflector pixels: {c}")?;
        }
        for file in &self.files {
            writeln!(f, "wrote {}", file.display())?;
        }
        write!(f, "done in {:.2} s", self.seconds)
    }
}

/// Runs `job` on `gpu`, with `technique` producing the reflection under test (or none).
///
/// # Errors
/// Loading the level, the set or the camera, a set extracted from other bytes than the
/// level's ([`TestbedError::SourceMismatch`], unless `job.accept_level_mismatch`), reading
/// back, or writing an image.
pub fn run(
    job: &RenderJob,
    gpu: &GpuContext,
    technique: Option<&mut dyn ReflectionTechnique>,
) -> Result<RenderReport, TestbedError> {
    let start = Instant::now();
    let level = Level::load_gltf(&job.level)?;
    let reflectors = ReflectorSet::load(&job.reflectors)?;
    let mut warnings = Vec::new();
    match reflectors.check_source(&job.reflectors, &job.level, &level.source_hash) {
        Ok(()) => {}
        Err(mismatch) if job.accept_level_mismatch => warnings.push(format!("{mismatch} (accepted)")),
        Err(mismatch) => return Err(mismatch.into()),
    }
    let camera = pick_camera(&level, job.camera.as_deref(), job.projection)?;
    let mut report = run_level(job, &level, &reflectors, &camera, gpu, technique)?;
    report.warnings = warnings;
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// Like [`run`] with the level, the set and the camera already in memory (`job.level`,
/// `job.reflectors`, `job.camera` and `job.projection` are not read).
///
/// # Errors
/// Reading back or writing an image.
pub fn run_level(
    job: &RenderJob,
    level: &Level,
    reflectors: &ReflectorSet,
    camera: &Camera,
    gpu: &GpuContext,
    technique: Option<&mut dyn ReflectionTechnique>,
) -> Result<RenderReport, TestbedError> {
    let start = Instant::now();
    let camera = *camera;
    let (device, queue) = (&gpu.device, &gpu.queue);
    let size = [job.size[0].max(1), job.size[1].max(1)];

    let mut renderer = LevelRenderer::new(device, queue, level, reflectors);
    renderer.settings = job.render;
    let frame = renderer.prepare(device, queue, &camera, size).clone();
    let usage = wgpu::TextureUsages::STORAGE_BINDING
        | wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::COPY_SRC
        | wgpu::TextureUsages::COPY_DST;
    // New textures are zero-initialised by wgpu: no reflection (alpha 0) until written.
    let reflection = Target::new(device, "technique reflection output", size, REFLECTION_FORMAT, usage);
    let mut technique = technique;
    let plan = technique.as_mut().map(|t| (t.name(), t.prepare(device, queue, &camera, size)));
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("ppr-render") });
    renderer.encode_gbuffer(&mut encoder);
    if let Some(t) = technique.as_mut() {
        let g = renderer.gbuffer();
        t.encode(&mut encoder, &ReflectionInputs::from_gbuffer(g, &reflection.view));
    }
    renderer.encode_reference(&mut encoder);
    queue.submit([encoder.finish()]);
    let timings = technique.as_mut().and_then(|t| t.timings(device));

    let compositor = CompositePass::new(device);
    let composite =
        |reflection_view: &wgpu::TextureView, label: &str| -> Result<Rgba32FImage, TestbedError> {
            let out = CompositePass::output_target(device, size, label);
            let g = renderer.gbuffer();
            let inputs = CompositeInputs {
                scene_color: &g.color.view,
                reflection: reflection_view,
                reflector_id: &g.reflector_id.view,
                output: &out.view,
            };
            compositor.run(device, queue, &inputs, &job.composite);
            read_rgba_f32(device, queue, &out.texture)
        };
    let with_reference = composite(&renderer.reference().color.view, "composite with reference")?;
    let with_technique = composite(&reflection.view, "composite with technique")?;
    let images = FrameImages::read(device, queue, &renderer)?;
    let raw = read_rgba_f32(device, queue, &reflection.texture)?;

    let files = OutputFiles::for_output(&job.output);
    let mut written = Vec::new();
    let mut write = |path: &PathBuf, result: Result<(), TestbedError>| -> Result<(), TestbedError> {
        result?;
        written.push(path.clone());
        Ok(())
    };
    let frame_image = if technique.is_some() { &with_technique } else { &images.color };
    write(&files.frame, write_png(&files.frame, frame_image, job.tone_map))?;
    write(&files.reference, write_png(&files.reference, &with_reference, job.tone_map))?;
    write(&files.reference_exr, write_exr(&files.reference_exr, &images.reference))?;
    let reflectors_mask = images.reflector_mask();
    let on_screen = images.on_screen_mask();
    let reflector_pixels = (reflectors_mask.count(), on_screen.count());
    let mut report = RenderReport {
        adapter: gpu.describe(),
        camera,
        frame,
        technique: plan,
        timings,
        on_screen: None,
        off_screen: None,
        on_screen_holes: None,
        reflector_pixels,
        files: Vec::new(),
        seconds: 0.0,
        warnings: Vec::new(),
    };
    if technique.is_some() {
        write(&files.reflection_png, write_png(&files.reflection_png, &raw, job.tone_map))?;
        write(&files.reflection_exr, write_exr(&files.reflection_exr, &raw))?;
        let diff = difference_image(&raw, &images.reference, &reflectors_mask, 4.0, job.tone_map)?;
        write(&files.diff, write_rgb8(&files.diff, &diff))?;
        report.on_screen = Some(compare(&images.reference, &raw, &on_screen, job.tone_map)?);
        report.off_screen = Some(compare(&images.reference, &raw, &images.off_screen_mask(), job.tone_map)?);
        report.on_screen_holes = Some(hole_share(&raw, &on_screen));
    }
    report.files = written;
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// Share of the masked pixels whose reflection alpha is 0 (no reflection; 0 for an empty mask).
pub fn hole_share(reflection: &Rgba32FImage, mask: &PixelMask) -> f64 {
    let total = mask.count();
    if total == 0 {
        return 0.0;
    }
    let holes = reflection.enumerate_pixels().filter(|(x, y, p)| mask.get(*x, *y) && p.0[3] <= 0.0).count();
    holes as f64 / total as f64
}
