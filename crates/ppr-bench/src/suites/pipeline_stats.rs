//! What the GPU driver compiled each runtime compute pipeline to (registers per thread,
//! shared and local memory, spills, instructions): one frame of each camera of each scene
//! with `ppr-runtime`'s pipeline log on, then every distinct logged pipeline compiled again
//! on a Vulkan device of our own that reports its executables' statistics
//! (`crate::pipeline_stats`).

use std::collections::HashSet;

use ppr_runtime::passes::{Ablation, ProjectionPass, ProjectionVariant, TileClassifyPass, UpsamplePass};
use ppr_runtime::pipeline_log::{self, PipelineSource};
use ppr_runtime::{PlanParams, ReflectionSettings};
use ppr_testbed::gbuffer_targets::Target;
use ppr_testbed::technique::REFLECTION_FORMAT;
use ppr_testbed::{GpuContext, LevelRenderer, ReflectionInputs};

use crate::config::{BenchConfig, Resolution};
use crate::error::BenchError;
use crate::pipeline_stats::spirv::{compile_pipeline, spirv_options};
use crate::pipeline_stats::statistic::ExecutableStats;
use crate::pipeline_stats::vulkan::StatsDevice;
use crate::ppr_runner::PprRunner;
use crate::scene::{BenchScene, SceneOptions, SceneSpec};
use crate::technique::{BenchFrame, BenchTechnique};

/// What the suite renders before it compiles.
#[derive(Clone, Debug, PartialEq)]
pub struct PipelineStatsConfig {
    pub scenes: Vec<String>,
    pub resolution: Resolution,
    pub max_cameras: usize,
    /// Also compile the projection's variants of [`projection_variants`] (its ablations and
    /// options: which part of the pass takes the registers and the shared memory), the
    /// classification without layers and every upsample variant.
    pub projection_variants: bool,
}

/// The projection's default frame variant on the demo level (fused block lists, layers,
/// source boxes, uniform tests, depth occlusion first), each ablation of it, and it with
/// one option turned off at a time; then the same for a frame without tile culling (the
/// kitchen's close views), and the first with the block-list pass's lists.
pub fn projection_variants() -> Vec<ProjectionVariant> {
    let fused = ProjectionVariant {
        tile_culling: true,
        fused_lists: true,
        depth_occlusion: true,
        layers: true,
        source_boxes: true,
        uniform_tests: true,
        occlusion_first: true,
        ..ProjectionVariant::default()
    };
    let plain = ProjectionVariant { tile_culling: false, fused_lists: false, layers: false, ..fused };
    let mut out = Vec::new();
    for base in [fused, plain] {
        out.push(base);
        for ablation in [
            Ablation::Empty,
            Ablation::PositionOnly,
            Ablation::TestsOnly,
            Ablation::NoEncode,
            Ablation::NoWrite,
            Ablation::NoAtomic,
        ] {
            out.push(ProjectionVariant { ablation, ..base });
        }
        out.push(ProjectionVariant { depth_occlusion: false, occlusion_first: false, ..base });
        out.push(ProjectionVariant { uniform_tests: false, ..base });
        out.push(ProjectionVariant { layers: false, ..base });
        out.push(ProjectionVariant { source_boxes: false, ..base });
        out.push(ProjectionVariant { occlusion_first: false, ..base });
    }
    // Tile culling with the block-list pass's lists instead of the projection's own.
    out.push(ProjectionVariant { fused_lists: false, ..fused });
    out
}

/// The distinct pipelines the frames created.
#[derive(Clone, Debug, Default)]
pub struct LoggedPipelines {
    /// One per (source, entry point, constants), in creation order.
    pub pipelines: Vec<PipelineSource>,
    /// Frames rendered.
    pub frames: usize,
    /// Scenes skipped, pipelines the log missed.
    pub notes: Vec<String>,
}

/// One pipeline and what the driver made of it.
#[derive(Clone, Debug)]
pub struct PipelineStats {
    pub pipeline: PipelineSource,
    pub executables: Vec<ExecutableStats>,
    /// Invocations per workgroup.
    pub workgroup_threads: u32,
    /// The workgroup memory the code declares (`CompiledPipeline::declared_workgroup_bytes`).
    pub declared_workgroup_bytes: u32,
}

/// Everything the suite found.
#[derive(Clone, Debug)]
pub struct PipelineStatsOutcome {
    /// The wgpu adapter the frames ran on.
    pub adapter: String,
    /// The Vulkan device that compiled the pipelines.
    pub vulkan_device: String,
    pub resolution: Resolution,
    pub frames: usize,
    pub pipelines: Vec<PipelineStats>,
    pub notes: Vec<String>,
}

/// Opens the Vulkan device (first, so that a machine without one fails at once), logs the
/// pipelines of one frame per camera and compiles each.
///
/// # Errors
/// No Vulkan loader or device ([`crate::pipeline_stats::PipelineStatsError`]), or a frame
/// fails. A pipeline that fails to compile is a note.
pub fn run_pipeline_stats(
    gpu: &GpuContext,
    cfg: &BenchConfig,
    pc: &PipelineStatsConfig,
) -> Result<PipelineStatsOutcome, BenchError> {
    let device = StatsDevice::open()?;
    eprintln!("pipeline-stats: Vulkan device {}", device.description);
    let logged = log_pipelines(gpu, cfg, pc)?;
    let options = spirv_options(&device.target, &ppr_runtime::shader::runtime_checks());
    let mut notes = logged.notes;
    let mut pipelines = Vec::new();
    for p in logged.pipelines {
        eprintln!("pipeline-stats: {} ({})", p.label, p.entry_point);
        let stats = compile_pipeline(&p, &options).and_then(|compiled| {
            let executables = device.statistics(&compiled, &p.entry_point)?;
            Ok((compiled, executables))
        });
        match stats {
            Ok((compiled, executables)) => pipelines.push(PipelineStats {
                pipeline: p,
                executables,
                workgroup_threads: compiled.workgroup_threads,
                declared_workgroup_bytes: compiled.declared_workgroup_bytes,
            }),
            Err(e) => {
                eprintln!("pipeline-stats: {e}");
                notes.push(e.to_string());
            }
        }
    }
    Ok(PipelineStatsOutcome {
        adapter: gpu.describe(),
        vulkan_device: device.description.clone(),
        resolution: pc.resolution,
        frames: logged.frames,
        pipelines,
        notes,
    })
}

/// Renders one frame of each camera of each scene with the runtime's default settings,
/// the pipeline log on, and returns the distinct pipelines created meanwhile (the
/// renderer's own, built when it is created, and those its frames asked for).
///
/// The log is process-global: pipelines another thread creates meanwhile are logged too.
///
/// # Errors
/// A scene name is unknown, or a frame fails.
pub fn log_pipelines(
    gpu: &GpuContext,
    cfg: &BenchConfig,
    pc: &PipelineStatsConfig,
) -> Result<LoggedPipelines, BenchError> {
    let (device, queue) = (&gpu.device, &gpu.queue);
    let options = SceneOptions { max_cameras: pc.max_cameras, ..SceneOptions::default() };
    let size = pc.resolution.size();
    let mut out = LoggedPipelines::default();
    let mut logged = Vec::new();
    pipeline_log::start();
    let _ = pipeline_log::take();
    for text in &pc.scenes {
        let spec = SceneSpec::parse(text, &cfg.repo_root, &cfg.scenes_dir)?;
        let scene = match BenchScene::load_ranked(&spec, &options, gpu) {
            Ok(s) => s,
            Err(e) => {
                out.notes.push(format!("{}: skipped, cannot load: {e}", spec.name));
                continue;
            }
        };
        let mut level = LevelRenderer::new(device, queue, &scene.level, &scene.reflectors);
        let (settings, params) = (ReflectionSettings::ALL, PlanParams::default());
        let mut ppr = PprRunner::new(device, queue, &scene.reflectors, "ppr", settings, params)?;
        for cam in &scene.cameras {
            eprintln!("pipeline-stats: {} {} {}", scene.name, cam.name, pc.resolution);
            level.prepare(device, queue, &cam.camera, size);
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("pipeline-stats frame"),
            });
            level.encode_gbuffer(&mut encoder);
            let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
            let output = Target::new(device, "pipeline-stats output", size, REFLECTION_FORMAT, usage);
            let frame = BenchFrame {
                level: &level,
                reflection: ReflectionInputs::from_gbuffer(level.gbuffer(), &output.view),
            };
            ppr.prepare(device, queue, &cam.camera, size);
            ppr.encode(&mut encoder, &frame);
            queue.submit([encoder.finish()]);
            gpu.wait_idle()?;
            out.frames += 1;
        }
        logged.extend(pipeline_log::take());
    }
    if pc.projection_variants {
        let mut pass = ProjectionPass::new(device);
        for v in projection_variants() {
            pass.prepare_variant(device, v);
        }
        // The classification of frames without layers, which the default scenes (whose
        // indirect frames have layers) do not build.
        TileClassifyPass::new(device).prepare_without_layers(device);
        // The reduced tiers' upsample, each pixel's samples read alone (built with every
        // renderer) and each workgroup's once (bench only, built on request).
        UpsamplePass::new(device).prepare_shared(device);
        logged.extend(pipeline_log::take());
    }
    let unknown = pipeline_log::unknown_modules();
    pipeline_log::stop();
    if unknown > 0 {
        out.notes
            .push(format!("{unknown} pipeline(s) not logged: their module was made before the log started"));
    }
    out.pipelines = distinct(logged);
    Ok(out)
}

/// The first of each (source, entry point, constants).
pub fn distinct(pipelines: Vec<PipelineSource>) -> Vec<PipelineSource> {
    let mut seen = HashSet::new();
    pipelines
        .into_iter()
        .filter(|p| {
            let constants: Vec<(String, u64)> =
                p.constants.iter().map(|(n, v)| (n.clone(), v.to_bits())).collect();
            seen.insert((p.source.clone(), p.entry_point.clone(), constants))
        })
        .collect()
}

/// `NAME=value;…` (the CSV's constants column).
pub fn constants_text(p: &PipelineSource) -> String {
    p.constants.iter().map(|(n, v)| format!("{n}={v}")).collect::<Vec<_>>().join(";")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pipeline(label: &str, source: &str, constants: &[(&str, f64)]) -> PipelineSource {
        PipelineSource {
            label: label.into(),
            source: source.into(),
            entry_point: "main".into(),
            constants: constants.iter().map(|&(n, v)| (n.into(), v)).collect(),
        }
    }

    #[test]
    fn distinct_keeps_the_first_of_each_source_entry_and_constants() {
        let list = vec![
            pipeline("a", "s", &[("X", 1.0)]),
            pipeline("b", "s", &[("X", 1.0)]),
            pipeline("c", "s", &[("X", 0.0)]),
            pipeline("d", "t", &[("X", 1.0)]),
        ];
        let labels: Vec<_> = distinct(list).into_iter().map(|p| p.label).collect();
        assert_eq!(labels, ["a", "c", "d"]);
        assert_eq!(constants_text(&pipeline("a", "s", &[("X", 1.0), ("Y", 16.0)])), "X=1;Y=16");
    }
}
