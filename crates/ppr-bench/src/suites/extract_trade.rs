//! The extractor's side of the trade (issue 6): per scene, how many rectangles each
//! extraction setting makes against how well they cover the reflective area, and what
//! each setting costs at run time (projection and reflection GPU time).

use ppr_extract::{ExtractParams, extract};
use ppr_format::{ReflectorKind, ReflectorSet};
use ppr_level::load_level;
use ppr_runtime::{PlanParams, ReflectionSettings};
use ppr_testbed::gbuffer_targets::Target;
use ppr_testbed::technique::REFLECTION_FORMAT;
use ppr_testbed::{GpuContext, LevelRenderer, ReflectionInputs};

use crate::config::{BenchConfig, Resolution};
use crate::error::BenchError;
use crate::frame_loop::FrameLoop;
use crate::ppr_runner::PprRunner;
use crate::scene::{BenchScene, SceneOptions, SceneSpec};
use crate::stats::median;
use crate::technique::BenchFrame;

/// What the trade suite runs.
#[derive(Clone, Debug, PartialEq)]
pub struct TradeConfig {
    pub scenes: Vec<String>,
    pub resolution: Resolution,
    pub max_cameras: usize,
}

/// One extraction setting on one scene.
#[derive(Clone, Debug)]
pub struct TradeRow {
    pub scene: String,
    pub setting: String,
    /// Split threshold, most rectangles per region, angle (°) and distance (m) tolerances.
    pub params: (f64, usize, f64, f64),
    pub rectangles: usize,
    /// Reflective area over rectangle area, area-weighted over the set.
    pub coverage: f64,
    /// Summed rectangle area, m².
    pub rect_area: f64,
    /// Mean over the cameras of the visible shapes.
    pub visible: f64,
    /// Medians over the cameras of each camera's median, ms.
    pub projection_ms: f64,
    pub reflection_ms: f64,
    pub total_ms: f64,
}

/// The settings swept: split threshold and rectangles per region, then tolerances.
pub fn trade_settings(base: &ExtractParams) -> Vec<(String, ExtractParams)> {
    let split = |gain: f64, max: usize| ExtractParams {
        split_min_gain: gain,
        max_shapes_per_region: max,
        ..base.clone()
    };
    let tol = |angle: f64, dist: f64| ExtractParams {
        angle_tolerance_deg: angle,
        distance_tolerance_m: dist,
        ..base.clone()
    };
    vec![
        ("no split".into(), split(1.0, 1)),
        ("split gain 0.5, ≤4".into(), split(0.5, 4)),
        ("split gain 0.2, ≤8".into(), split(0.2, 8)),
        ("default (gain 0.1, ≤8)".into(), base.clone()),
        ("split gain 0.03, ≤16".into(), split(0.03, 16)),
        ("split gain 0.01, ≤32".into(), split(0.01, 32)),
        ("tight tolerances (0.25°, 1 mm)".into(), tol(0.25, 0.001)),
        ("loose tolerances (4°, 20 mm)".into(), tol(4.0, 0.02)),
    ]
}

/// Runs the suite.
///
/// # Errors
/// A scene name is not understood.
pub fn run_extract_trade(
    gpu: &GpuContext,
    cfg: &BenchConfig,
    tc: &TradeConfig,
) -> Result<(Vec<TradeRow>, Vec<String>), BenchError> {
    let (device, queue) = (&gpu.device, &gpu.queue);
    let frames = FrameLoop::new(device, cfg);
    let size = tc.resolution.size();
    let mut rows = Vec::new();
    let mut notes = Vec::new();
    for text in &tc.scenes {
        let spec = SceneSpec::parse(text, &cfg.repo_root, &cfg.scenes_dir)?;
        let options = SceneOptions { max_cameras: tc.max_cameras, ..SceneOptions::default() };
        let (scene, source) = match (BenchScene::load_ranked(&spec, &options, gpu), load_level(&spec.path)) {
            (Ok(s), Ok(l)) => (s, l),
            (Err(e), _) => {
                notes.push(format!("{}: skipped, cannot load: {e}", spec.name));
                continue;
            }
            (_, Err(e)) => {
                notes.push(format!("{}: skipped, cannot extract: {e}", spec.name));
                continue;
            }
        };
        notes.push(format!(
            "{}: cameras {}",
            scene.name,
            scene.cameras.iter().map(|c| c.name.as_str()).collect::<Vec<_>>().join(", ")
        ));
        let mut level = LevelRenderer::new(device, queue, &scene.level, &ReflectorSet::new(""));
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let output = Target::new(device, "trade output", size, REFLECTION_FORMAT, usage);
        for (name, params) in trade_settings(&spec.preset.params()) {
            let mut set = extract(&source, &params, &|_, _| {}).set;
            for r in &mut set.reflectors {
                if r.kind == ReflectorKind::Transparent {
                    r.kind = ReflectorKind::Opaque;
                }
            }
            let rect_area: f64 = set.reflectors.iter().map(|r| r.area()).sum();
            let reflective: f64 = set.reflectors.iter().map(|r| r.area() * r.coverage).sum();
            let mut ppr =
                PprRunner::new(device, queue, &set, "ppr", ReflectionSettings::ALL, PlanParams::default())?;
            // The trade reports the projection's and the reflection's times apart.
            ppr.time_projection_apart();
            let (mut proj, mut refl, mut total, mut visible) =
                (Vec::new(), Vec::new(), Vec::new(), Vec::new());
            for cam in &scene.cameras {
                level.prepare(device, queue, &cam.camera, size);
                let mut encoder = device
                    .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("trade gbuffer") });
                level.encode_gbuffer(&mut encoder);
                queue.submit([encoder.finish()]);
                let frame = BenchFrame {
                    level: &level,
                    reflection: ReflectionInputs::new(
                        &level.gbuffer().color.view,
                        &level.gbuffer().depth.view,
                        &output.view,
                    ),
                };
                let run = frames.run(device, queue, &mut ppr, &frame, &cam.camera, size);
                proj.push(run.timings.pass("projection").map_or(0.0, |s| s.median));
                refl.push(run.timings.pass("reflection").map_or(0.0, |s| s.median));
                total.push(run.timings.total().map_or(0.0, |s| s.median));
                visible.push(ppr.renderer().plan().map_or(0.0, |p| p.visible.len() as f64));
            }
            eprintln!("extract-trade: {} {name}: {} rectangles", scene.name, set.reflectors.len());
            rows.push(TradeRow {
                scene: scene.name.clone(),
                setting: name,
                params: (
                    params.split_min_gain,
                    params.max_shapes_per_region,
                    params.angle_tolerance_deg,
                    params.distance_tolerance_m,
                ),
                rectangles: set.reflectors.len(),
                coverage: if rect_area > 0.0 { reflective / rect_area } else { 0.0 },
                rect_area,
                visible: visible.iter().sum::<f64>() / visible.len().max(1) as f64,
                projection_ms: median(&proj).unwrap_or(f64::NAN),
                reflection_ms: median(&refl).unwrap_or(f64::NAN),
                total_ms: median(&total).unwrap_or(f64::NAN),
            });
        }
    }
    Ok((rows, notes))
}
