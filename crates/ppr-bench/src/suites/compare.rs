//! The comparison (issue 6): scenes × cameras × resolutions × techniques, each timed per
//! pass and measured against the exact reflection.

use std::collections::BTreeSet;
use std::sync::Arc;

use indicatif::{ProgressBar, ProgressStyle};
use ppr_runtime::PlanParams;
use ppr_testbed::gbuffer_targets::Target;
use ppr_testbed::readback::read_rgba_f32;
use ppr_testbed::technique::REFLECTION_FORMAT;
use ppr_testbed::{FrameImages, GlossyParams, GpuContext, LevelRenderer, ReflectionInputs, clear_target};

use crate::bounce_reference::DeeperReferences;
use crate::config::{BenchConfig, Resolution};
use crate::error::BenchError;
use crate::error_causes::{CauseFrame, CauseRow, CauseRunner, classify};
use crate::frame_loop::FrameLoop;
use crate::quality::{Quality, ReferenceFrame};
use crate::quality_pool::QualityPool;
use crate::report::image_sheet::{
    SheetRow, crop_window, visualize_reference, visualize_scene, visualize_technique,
};
use crate::run_result::RunResult;
use crate::scene::{BenchScene, SceneOptions, SceneSpec};
use crate::technique::{BenchFrame, ReflectionOutput};
use crate::technique_spec::{TechniqueContext, TechniqueSpec, build_technique};

/// What the comparison runs.
#[derive(Clone, Debug, PartialEq)]
pub struct CompareConfig {
    /// Scene names or paths (see [`SceneSpec::parse`]).
    pub scenes: Vec<String>,
    /// Camera names to keep (all when empty).
    pub cameras: Vec<String>,
    /// At most this many cameras per scene.
    pub max_cameras: usize,
    /// Render sizes.
    pub resolutions: Vec<Resolution>,
    /// Techniques and settings.
    pub techniques: Vec<TechniqueSpec>,
    /// Quality is measured only at sizes of at most this many pixels (FLIP on the CPU is
    /// slow; 8K is skipped by default).
    pub quality_max_pixels: u64,
    /// Size of the image sheet's crops (the first camera of each scene).
    pub sheet_resolution: Resolution,
    /// Size of the accuracy-against-time plot.
    pub pareto_resolution: Resolution,
    /// The reference every row is scored against.
    pub reference: ReferenceKind,
    /// Views per rough reflector plane of the glossy reference.
    pub glossy_samples: u32,
}

/// The reference the comparison scores against.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum ReferenceKind {
    /// Every reflector as a perfect mirror (the mirrored re-render per plane).
    Mirror,
    /// The exact glossy reference on reflectors with roughness > 0 (the testbed's
    /// `GlossyParams`), the mirror reference on the others.
    #[default]
    Glossy,
}

/// The level renderer's settings for `scene` under `cc`'s reference, and a note saying
/// what the rows of the scene are scored against.
fn reference_settings(scene: &BenchScene, cc: &CompareConfig) -> (ppr_testbed::RenderSettings, String) {
    let mut settings = scene.render_settings();
    let set = &scene.reflectors.reflectors;
    let rough = set.iter().filter(|r| r.enabled && r.roughness > 0.0).count();
    let note = match cc.reference {
        ReferenceKind::Glossy if rough > 0 && cc.glossy_samples > 0 => {
            settings.glossy = GlossyParams { samples: cc.glossy_samples, ..GlossyParams::bench() };
            format!(
                "{}: scored against the exact glossy reference on its {rough} of {} reflectors with roughness > 0 \
                 ({} views per rough plane; `exact` is timed with them), the mirror reference on the others",
                scene.name,
                set.len(),
                cc.glossy_samples
            )
        }
        ReferenceKind::Glossy => {
            format!("{}: no reflector has roughness > 0: scored against the mirror reference", scene.name)
        }
        ReferenceKind::Mirror => format!(
            "{}: scored against the mirror reference (--reference mirror; {rough} reflectors have roughness > 0)",
            scene.name
        ),
    };
    (settings, note)
}

/// Everything the comparison found.
pub struct CompareOutcome {
    pub adapter: String,
    pub results: Vec<RunResult>,
    pub sheets: Vec<SheetRow>,
    /// Per scene: what was noticed while loading, and scenes that were skipped.
    pub notes: Vec<String>,
    /// Full PPR's error by cause, per camera and size where quality was measured
    /// (`error_causes`; computed on untimed frames after each camera's timed runs).
    pub causes: Vec<CauseRow>,
}

/// Runs the comparison on `gpu`.
///
/// # Errors
/// A technique cannot be built, or a readback fails. Scenes that cannot be loaded are
/// skipped with a note.
pub fn run_compare(
    gpu: &GpuContext,
    cfg: &BenchConfig,
    cc: &CompareConfig,
    after_scene: &mut dyn FnMut(&CompareOutcome) -> Result<(), BenchError>,
) -> Result<CompareOutcome, BenchError> {
    let (device, queue) = (&gpu.device, &gpu.queue);
    let mut notes = Vec::new();
    let options = SceneOptions { max_cameras: cc.max_cameras, ..SceneOptions::default() };
    let mut scenes = Vec::new();
    for text in &cc.scenes {
        let spec = SceneSpec::parse(text, &cfg.repo_root, &cfg.scenes_dir)?;
        match BenchScene::load_ranked(&spec, &options, gpu) {
            Ok(mut scene) => {
                scene.keep_cameras(&cc.cameras);
                for n in &scene.notes {
                    notes.push(format!("{}: {n}", scene.name));
                }
                scenes.push(scene);
            }
            Err(e) => notes.push(format!("{}: skipped, cannot load: {e}", spec.name)),
        }
    }
    let total: usize =
        scenes.iter().map(|s| s.cameras.len()).sum::<usize>() * cc.resolutions.len() * cc.techniques.len();
    let bar = ProgressBar::new(total as u64);
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let frames = FrameLoop::new(device, cfg);
    let mut outcome = CompareOutcome {
        adapter: gpu.describe(),
        results: Vec::new(),
        sheets: Vec::new(),
        notes,
        causes: Vec::new(),
    };

    for scene in &scenes {
        // Metrics wait until the scene's timing is done: CPU threads busy with FLIP delay
        // the frame loop's submissions, the GPU idles between frames and clocks down, and
        // the timestamps of the runs beside them come out up to 2.5x slower (seen on the H100).
        let mut pending = Vec::new();
        let results = &mut outcome.results;
        let sheets = &mut outcome.sheets;
        let mut level = LevelRenderer::new(device, queue, &scene.level, &scene.reflectors);
        let (settings, note) = reference_settings(scene, cc);
        level.settings = settings;
        outcome.notes.push(note);
        let ctx = TechniqueContext {
            device,
            queue,
            level: &scene.level,
            reflectors: &scene.reflectors,
            render: scene.render_settings(),
            plan_params: PlanParams::default(),
        };
        let mut techniques = Vec::new();
        let cc_len = cc.techniques.len();
        let mut cause_runners = Vec::new();
        for spec in &cc.techniques {
            techniques.push(build_technique(spec, &ctx)?);
            if let Some(r) = CauseRunner::new(device, queue, &scene.reflectors, spec, ctx.plan_params)? {
                cause_runners.push((spec.label(), r));
            }
        }
        // Rows that feed PPR its previous frame are scored against the reference of as many
        // bounces; every other row against the one-bounce reference.
        let depths: BTreeSet<u32> = techniques.iter().map(|t| t.reference_bounces()).collect();
        let deeper_rows: Vec<String> = techniques
            .iter()
            .filter(|t| t.reference_bounces() > 1)
            .map(|t| format!("`{}` against the {}-bounce reference", t.label(), t.reference_bounces()))
            .collect();
        if !deeper_rows.is_empty() {
            outcome.notes.push(format!(
                "{}: {}; every other row against the one-bounce reference (mirrors in a reflection \
                 show their own colour); scores against different references are not comparable",
                scene.name,
                deeper_rows.join(", ")
            ));
        }
        for (cam_index, cam) in scene.cameras.iter().enumerate() {
            for &res in &cc.resolutions {
                let size = res.size();
                level.prepare(device, queue, &cam.camera, size);
                let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("bench scene frame"),
                });
                level.encode_gbuffer(&mut encoder);
                level.encode_reference(&mut encoder);
                queue.submit([encoder.finish()]);
                let images = if res.pixels() <= cc.quality_max_pixels {
                    if let Some(stats) = level.glossy_stats(device, queue) {
                        let s = stats?;
                        outcome.notes.push(format!(
                            "{} {} {res}: glossy reference over {} px, effective sample size mean {:.1}, \
                             10th percentile {:.1}, min {:.1} (of {} views per rough plane)",
                            scene.name,
                            cam.name,
                            s.pixels,
                            s.mean_ess,
                            s.p10_ess,
                            s.min_ess,
                            cc.glossy_samples
                        ));
                    }
                    Some(FrameImages::read(device, queue, &level)?)
                } else {
                    None
                };
                // The breakdown keeps the G-buffer and the reference's reflected points.
                let (reference, images) = match images {
                    Some(i) if !cause_runners.is_empty() => {
                        (Some(Arc::new(ReferenceFrame::new(i.clone()))), Some(i))
                    }
                    Some(i) => (Some(Arc::new(ReferenceFrame::new(i))), None),
                    None => (None, None),
                };
                let deeper = match &reference {
                    Some(_) => DeeperReferences::render(
                        (device, queue),
                        &mut level,
                        &cam.camera,
                        size,
                        &depths,
                        &format!("{} {} {res}", scene.name, cam.name),
                        &mut outcome.notes,
                    )?,
                    None => DeeperReferences::default(),
                };
                let sheet_here = cam_index == 0 && res == cc.sheet_resolution;
                let mut sheet = match (&reference, sheet_here) {
                    (Some(r), true) => {
                        let window = crop_window(&r.on_screen);
                        Some(SheetRow {
                            scene: scene.name.clone(),
                            camera: cam.name.clone(),
                            resolution: res,
                            window,
                            columns: vec![
                                ("scene".into(), visualize_scene(r, window, cfg.tone_map)),
                                ("exact reflection".into(), visualize_reference(r, window, cfg.tone_map)),
                            ],
                        })
                    }
                    _ => None,
                };
                let output = output_target(device, size);
                let message = format!("{} {} {res}", scene.name, cam.name);
                log(&bar, &message);
                bar.set_message(message);
                for technique in techniques.iter_mut() {
                    clear_output(device, queue, &output);
                    let frame = BenchFrame {
                        level: &level,
                        reflection: ReflectionInputs::from_gbuffer(level.gbuffer(), &output.view),
                    };
                    let run = frames.run(device, queue, technique.as_mut(), &frame, &cam.camera, size);
                    let id = results.len();
                    let mut quality = None;
                    if let Some(r) = &deeper.pick(technique.reference_bounces(), reference.as_ref()) {
                        match technique.output() {
                            ReflectionOutput::Reference => quality = Some(Quality::exact(r)),
                            ReflectionOutput::OutputTexture => {
                                let image = read_rgba_f32(device, queue, &output.texture)?;
                                if let Some(s) = sheet.as_mut() {
                                    s.columns.push((
                                        technique.label(),
                                        visualize_technique(r, &image, s.window, cfg.tone_map),
                                    ));
                                }
                                pending.push((id, Arc::clone(r), image));
                            }
                        }
                    }
                    results.push(RunResult {
                        scene: scene.name.clone(),
                        camera: cam.name.clone(),
                        resolution: res,
                        technique: technique.label(),
                        family: technique.family(),
                        timings: run.timings,
                        timing_source: run.source,
                        quality,
                        plan: run.plan,
                    });
                    bar.inc(1);
                }
                // A second round of every fast technique, the faster of the two runs kept: on
                // the H200 the first technique after a camera's reference, read-backs and
                // metrics still ran up to 3x slower after its warm-up (every pass alike, in the
                // 2026-12-03 runs), and the techniques after it did not.
                for (offset, technique) in techniques.iter_mut().enumerate() {
                    let id = results.len() - cc_len + offset;
                    let first = results[id].timings.total().map_or(f64::INFINITY, |s| s.median);
                    if first > crate::frame_loop::SLOW_FRAME_MS {
                        continue;
                    }
                    let frame = BenchFrame {
                        level: &level,
                        reflection: ReflectionInputs::from_gbuffer(level.gbuffer(), &output.view),
                    };
                    let again = frames.run(device, queue, technique.as_mut(), &frame, &cam.camera, size);
                    if again.median_ms() < first {
                        results[id].timings = again.timings;
                    }
                }
                if let Some(s) = sheet {
                    sheets.push(s);
                }
                // Untimed, after this camera's timed runs: the breakdown's renders and CPU work
                // never sit between timed frames.
                if let Some(images) = &images {
                    let frame = CauseFrame {
                        images,
                        camera: &cam.camera,
                        reflectors: &scene.reflectors,
                        tone_map: cfg.tone_map,
                    };
                    for (label, runner) in &mut cause_runners {
                        let variants = runner.render(device, queue, &level, &cam.camera, size)?;
                        outcome.causes.push(CauseRow {
                            scene: scene.name.clone(),
                            camera: cam.name.clone(),
                            resolution: res,
                            technique: label.clone(),
                            breakdown: classify(&frame, &variants)?,
                        });
                    }
                }
            }
        }
        bar.set_message(format!("{}: waiting for the quality metrics", scene.name));
        let mut pool = QualityPool::new(QualityPool::default_limit());
        for (id, reference, image) in pending {
            pool.submit(id, reference, image, cfg.tone_map);
        }
        for (id, q) in pool.finish() {
            match q {
                Ok(q) => outcome.results[id].quality = Some(q),
                Err(e) => outcome
                    .notes
                    .push(format!("quality of run {id} ({}): {e}", outcome.results[id].technique)),
            }
        }
        after_scene(&outcome)?;
    }
    bar.finish_with_message("done");
    Ok(outcome)
}

/// Prints a line above the bar, or on stderr when the bar is hidden (not a terminal).
pub fn log(bar: &ProgressBar, line: &str) {
    if bar.is_hidden() {
        eprintln!("{line}");
    } else {
        bar.println(line);
    }
}

fn output_target(device: &wgpu::Device, size: [u32; 2]) -> Target {
    let usage = wgpu::TextureUsages::STORAGE_BINDING
        | wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::COPY_SRC
        | wgpu::TextureUsages::RENDER_ATTACHMENT;
    Target::new(device, "bench technique output", size, REFLECTION_FORMAT, usage)
}

/// Clears the output to "no reflection" so that one technique never sees another's pixels.
fn clear_output(device: &wgpu::Device, queue: &wgpu::Queue, output: &Target) {
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("bench clear output") });
    clear_target(&mut encoder, &output.view, "bench clear output");
    queue.submit([encoder.finish()]);
}
