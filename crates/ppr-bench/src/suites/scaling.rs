//! Scaling (issue 5): GPU time per pass against shape count on generated levels, without
//! tile culling, with flat tile lists and with super-tile lists, and the plan's thresholds
//! (tile culling and super-tiles from how many shapes, indirect dispatch up to which
//! screen coverage).

use ppr_format::ReflectorSet;
use ppr_runtime::{Choice, PlanParams, ReflectionSettings};
use ppr_testbed::gbuffer_targets::Target;
use ppr_testbed::technique::REFLECTION_FORMAT;
use ppr_testbed::{GpuContext, LevelRenderer, ReflectionInputs};

use crate::config::{BenchConfig, Resolution};
use crate::error::BenchError;
use crate::frame_loop::{FrameLoop, faster_of_two_rounds_in, lightest_first};
use crate::ppr_runner::PprRunner;
use crate::scaling::coverage_level::coverage_level;
use crate::scaling::level_family::{GeneratedLevel, LevelFamily, generate};
use crate::technique::BenchFrame;
use crate::timing::{TimingSeries, TimingSource};

/// What the scaling suite runs.
#[derive(Clone, Debug, PartialEq)]
pub struct ScalingConfig {
    pub families: Vec<LevelFamily>,
    /// Shape counts of the main measurement.
    pub counts: Vec<usize>,
    /// Shape counts of the tile-culling threshold sweep.
    pub threshold_counts: Vec<usize>,
    /// Screen coverages of the indirect-dispatch threshold sweep.
    pub coverages: Vec<f64>,
    pub resolution: Resolution,
}

/// One measurement: a level, a plan choice, its times.
#[derive(Clone, Debug)]
pub struct ScalingRow {
    /// `stairway`, `tiled-floor`, `facade` or `coverage`.
    pub family: String,
    /// Reflectors in the level.
    pub shapes: usize,
    /// What was forced: `culling off`, `culling on` (flat tile lists), `super-tiles`,
    /// `indirect on`, ...
    pub variant: String,
    /// Visible shapes, as the plan saw them.
    pub visible: usize,
    /// Projection tests (visible shapes, merged plane groups and parallel trees counting one).
    pub tested: usize,
    /// Share of the screen the plan's screen rectangles cover.
    pub coverage: f32,
    /// Passes the plan ran.
    pub passes: String,
    pub timings: TimingSeries,
    pub source: TimingSource,
}

impl ScalingRow {
    /// Median of one pass (NaN when it did not run).
    pub fn pass_ms(&self, name: &str) -> f64 {
        self.timings.pass(name).map_or(f64::NAN, |s| s.median)
    }

    pub fn total_ms(&self) -> f64 {
        self.timings.total().map_or(f64::NAN, |s| s.median)
    }
}

/// Everything the scaling suite found.
pub struct ScalingOutcome {
    pub adapter: String,
    pub resolution: Resolution,
    /// Families × counts × culling off / on / super-tiles.
    pub rows: Vec<ScalingRow>,
    /// The tile-culling threshold sweep.
    pub threshold_rows: Vec<ScalingRow>,
    /// The indirect-dispatch sweep.
    pub coverage_rows: Vec<ScalingRow>,
}

struct Measurer<'a> {
    gpu: &'a GpuContext,
    frames: FrameLoop,
    size: [u32; 2],
}

impl Measurer<'_> {
    /// Times `variants` on `g`, the first round lightest first by `earlier`, the same
    /// family's rows at the previous count (the variants without one last, in order).
    fn run(
        &self,
        g: &GeneratedLevel,
        variants: &[(&str, PlanParams)],
        earlier: &[ScalingRow],
    ) -> Result<Vec<ScalingRow>, BenchError> {
        let (device, queue) = (&self.gpu.device, &self.gpu.queue);
        // The G-buffer needs no reflector mask: PPR reads colour and depth only.
        let mut level = LevelRenderer::new(device, queue, &g.level, &ReflectorSet::new(""));
        level.prepare(device, queue, &g.camera, self.size);
        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("scaling gbuffer") });
        level.encode_gbuffer(&mut encoder);
        queue.submit([encoder.finish()]);
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let output = Target::new(device, "scaling output", self.size, REFLECTION_FORMAT, usage);
        let frame = BenchFrame {
            level: &level,
            reflection: ReflectionInputs::new(
                &level.gbuffer().color.view,
                &level.gbuffer().depth.view,
                &output.view,
            ),
        };
        let mut runners = Vec::new();
        for (_, params) in variants {
            let mut runner =
                PprRunner::new(device, queue, &g.reflectors, "ppr", ReflectionSettings::ALL, *params)?;
            // The report's projection columns need the projection's own time.
            runner.time_projection_apart();
            runners.push(runner);
        }
        // The first round lightest first, so that the heavy variants' frames (up to 50 ms at
        // 10 000 shapes without culling) cannot leave the GPU slow for the light ones; the
        // reverse round skips the heaviest and meets the rest at other times.
        let expected: Vec<f64> = variants
            .iter()
            .map(|(name, _)| {
                earlier.iter().find(|r| r.variant == *name).map_or(f64::NAN, ScalingRow::total_ms)
            })
            .collect();
        let runs = faster_of_two_rounds_in(&lightest_first(&expected), |i| {
            Ok::<_, BenchError>(self.frames.run(device, queue, &mut runners[i], &frame, &g.camera, self.size))
        })?;
        let mut rows = Vec::new();
        for (((variant, _), ppr), run) in variants.iter().zip(&mut runners).zip(runs) {
            let plan = ppr.renderer().plan().cloned();
            eprintln!(
                "scaling: {} {} shapes, {variant}: {:.3} ms",
                g.family.as_str(),
                g.reflectors.reflectors.len(),
                run.median_ms()
            );
            rows.push(ScalingRow {
                family: g.family.as_str().into(),
                shapes: g.reflectors.reflectors.len(),
                variant: (*variant).into(),
                visible: plan.as_ref().map_or(0, |p| p.visible.len()),
                tested: plan.as_ref().map_or(0, |p| p.tested.len()),
                coverage: plan.as_ref().map_or(0.0, |p| p.coverage),
                passes: plan.as_ref().map_or(String::new(), |p| p.passes().join(" → ")),
                timings: run.timings,
                source: run.source,
            });
        }
        Ok(rows)
    }
}

/// Culling forced, every visible shape tested alone (no merged plane groups or trees).
fn culling(tile_culling: Choice, super_tiles: Choice) -> PlanParams {
    PlanParams {
        tile_culling,
        super_tiles,
        plane_groups: Choice::Off,
        parallel_trees: Choice::Off,
        ..PlanParams::default()
    }
}

/// Variant names of the culling sweeps.
pub const CULLING_OFF: &str = "culling off";
/// Tile culling with tile lists built from every visible shape.
pub const CULLING_ON: &str = "culling on";
/// Tile culling with tile lists built from super-tile lists.
pub const SUPER_TILES: &str = "super-tiles";
/// Coplanar shapes merged into plane groups (forced on, no parallel trees), culling as the
/// plan picks it.
pub const PLANE_GROUPS: &str = "plane groups";
/// Parallel families walked as trees (forced on), plane groups and culling as the plan
/// picks them.
pub const PARALLEL_TREES: &str = "parallel trees";
/// Parallel trees forced on, walked without their offset index (what the index buys).
pub const TREES_NO_INDEX: &str = "trees, no offset index";
/// The plan's own choices with the projection's subgroup culling off (what it buys).
pub const NO_SUBGROUPS: &str = "no subgroup culling";
/// The plan's own choices with the projection's subgroup culling forced on (where its
/// threshold comes from).
pub const SUBGROUPS_ON: &str = "subgroup culling on";

/// Runs the suite.
///
/// # Errors
/// None today; kept for readbacks to come.
pub fn run_scaling(
    gpu: &GpuContext,
    cfg: &BenchConfig,
    sc: &ScalingConfig,
) -> Result<ScalingOutcome, BenchError> {
    let m = Measurer { gpu, frames: FrameLoop::new(&gpu.device, cfg), size: sc.resolution.size() };
    let on_off = [
        (CULLING_OFF, culling(Choice::Off, Choice::Off)),
        (CULLING_ON, culling(Choice::On, Choice::Off)),
        (SUPER_TILES, culling(Choice::On, Choice::On)),
        (
            PLANE_GROUPS,
            PlanParams { plane_groups: Choice::On, parallel_trees: Choice::Off, ..PlanParams::default() },
        ),
        (PARALLEL_TREES, PlanParams { parallel_trees: Choice::On, ..PlanParams::default() }),
        (
            TREES_NO_INDEX,
            PlanParams { parallel_trees: Choice::On, tree_index: Choice::Off, ..PlanParams::default() },
        ),
        (NO_SUBGROUPS, PlanParams { subgroup_cull: Choice::Off, ..PlanParams::default() }),
        (SUBGROUPS_ON, PlanParams { subgroup_cull: Choice::On, ..PlanParams::default() }),
    ];
    let mut rows = Vec::new();
    for &family in &sc.families {
        let mut earlier = Vec::new();
        for &n in &sc.counts {
            let level = m.run(&generate(family, n), &on_off, &earlier)?;
            earlier.clone_from(&level);
            rows.extend(level);
        }
    }
    let mut threshold_rows = Vec::new();
    for &family in &sc.families {
        let mut earlier = Vec::new();
        for &n in &sc.threshold_counts {
            // Counts already measured in the main sweep are reused.
            let mut level: Vec<ScalingRow> =
                rows.iter().filter(|r| r.family == family.as_str() && r.shapes == n).cloned().collect();
            if level.is_empty() {
                level = m.run(&generate(family, n), &on_off, &earlier)?;
            }
            earlier.clone_from(&level);
            threshold_rows.extend(level);
        }
    }
    let mut coverage_rows = Vec::new();
    let indirect = |c| PlanParams { indirect: c, ..PlanParams::default() };
    for &c in &sc.coverages {
        let mut r = m.run(
            &coverage_level(c),
            &[("indirect off", indirect(Choice::Off)), ("indirect on", indirect(Choice::On))],
            &[],
        )?;
        for row in &mut r {
            row.family = "coverage".into();
        }
        coverage_rows.extend(r);
    }
    Ok(ScalingOutcome {
        adapter: gpu.describe(),
        resolution: sc.resolution,
        rows,
        threshold_rows,
        coverage_rows,
    })
}

/// The smallest shape count from which `faster` is never slower than `slower` (total
/// time), for one family's sweep; `None` if it does not win at the largest count.
pub fn crossover(rows: &[ScalingRow], family: &str, faster: &str, slower: &str) -> Option<usize> {
    let mut counts: Vec<usize> = rows.iter().filter(|r| r.family == family).map(|r| r.shapes).collect();
    counts.sort_unstable();
    counts.dedup();
    let wins = |n: usize| {
        let t = |v: &str| {
            rows.iter()
                .find(|r| r.family == family && r.shapes == n && r.variant == v)
                .map(ScalingRow::total_ms)
        };
        matches!((t(faster), t(slower)), (Some(on), Some(off)) if on <= off)
    };
    let mut crossover = None;
    for &n in counts.iter().rev() {
        if wins(n) {
            crossover = Some(n);
        } else {
            break;
        }
    }
    crossover
}

/// The largest measured coverage up to which indirect dispatch is never slower (total).
pub fn indirect_crossover(rows: &[ScalingRow]) -> Option<f32> {
    let mut covs: Vec<f32> = rows.iter().map(|r| r.coverage).collect();
    covs.sort_by(f32::total_cmp);
    covs.dedup();
    let mut best = None;
    for c in covs {
        let t = |v: &str| rows.iter().find(|r| r.coverage == c && r.variant == v).map(ScalingRow::total_ms);
        match (t("indirect on"), t("indirect off")) {
            (Some(on), Some(off)) if on <= off => best = Some(c),
            _ => break,
        }
    }
    best
}
