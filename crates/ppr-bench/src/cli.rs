//! The command line: subcommands per suite, shared options, and the entry point the binary
//! and the tests call.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use ppr_testbed::GpuContext;

use crate::config::{BenchConfig, Resolution};
use crate::error::BenchError;
use crate::goals::{GoalFiles, judge_files};
use crate::report::compare_report::write_compare_report;
use crate::report::pipeline_stats_report::write_pipeline_stats_report;
use crate::report::runtime_report::write_runtime_report;
use crate::report::scaling_report::write_scaling_report;
use crate::report::trade_report::write_trade_report;
use crate::scaling::level_family::LevelFamily;
use crate::suites::compare::{CompareConfig, CompareOutcome, ReferenceKind, run_compare};
use crate::suites::extract_trade::{TradeConfig, run_extract_trade};
use crate::suites::pipeline_stats::{PipelineStatsConfig, run_pipeline_stats};
use crate::suites::runtime::{RuntimeConfig, run_runtime};
use crate::suites::scaling::{ScalingConfig, run_scaling};
use crate::technique_spec::TechniqueSpec;

const EXAMPLES: &str = "\
Examples:
  # CI smoke run: demo level, one camera, 64x36, every technique, a few frames
  ppr-bench compare --quick --out target/bench-quick

  # The full comparison (issue 6) on the demo level and the shared scenes
  ppr-bench compare --scene demo --scene kitchen --scene small --out docs/perf

  # PPR alone at 4K on the kitchen, tile culling forced off
  ppr-bench compare --scene kitchen --resolution 4k --technique ppr:culling=off

  # Runtime passes against their bandwidth floor (issue 4), scaling with shape count
  # (issue 5) and the extractor's trade (issue 6), each into its own folder
  ppr-bench runtime --out docs/perf
  ppr-bench scaling --out docs/perf
  ppr-bench extract-trade --out docs/perf

  # What the driver compiled each runtime pipeline to (registers, shared/local memory,
  # spills, instructions), on the GPU's Vulkan driver
  WGPU_BACKEND=vulkan ppr-bench pipeline-stats --out docs/perf

Scenes: demo (assets/demo_room.glb), kitchen, small, collision-world, pool, mine (from
--scenes-dir), the generated closed mirror rooms mirror-room, mirror-room-<boxes> and
mirror-corridor, the scaling suite's generated levels <family>-<count> (stairway-10000,
tiled-floor-1000, facade-100, rooms-1000: one camera), or a path to a .glb/.gltf (append
:all-planar for levels with one material).
Run on a GPU with WGPU_BACKEND=vulkan; without one, wgpu's GL backend on llvmpipe works
(only --quick is practical there).";

/// Benchmarks of pixel-projected reflections: accuracy against time, runtime passes against
/// the bandwidth floor, scaling with shape count, the extractor's trade.
#[derive(Parser, Debug)]
#[command(name = "ppr-bench", version, about, after_help = EXAMPLES)]
pub struct Cli {
    #[command(subcommand)]
    pub suite: Suite,
}

/// One suite per question.
#[derive(Subcommand, Debug)]
pub enum Suite {
    /// Scenes x cameras x resolutions x techniques: GPU time per pass, PSNR/FLIP against the
    /// exact reflection, Pareto plots, image sheet (comparison.md, comparison.csv).
    Compare(CompareArgs),
    /// Each PPR pass on the demo level and the kitchen against its bandwidth floor, with the
    /// copy bandwidth measured in the same run (runtime.md, runtime.csv).
    Runtime(RuntimeArgs),
    /// Generated levels with 1 to 10 000 reflectors, without tile culling, with flat tile
    /// lists and with super-tile lists, and the plan's
    /// two thresholds (scaling.md, scaling.csv, scaling.png).
    Scaling(ScalingArgs),
    /// Extraction settings per scene: rectangles against coverage and their GPU cost
    /// (extract_trade.md, extract_trade.csv, one plot per scene).
    ExtractTrade(TradeArgs),
    /// What the GPU driver compiled each runtime compute pipeline to: registers per thread,
    /// shared and local memory, spills, instruction counts, as the driver names them
    /// (pipeline_stats.md, pipeline_stats.csv). Use it to read the occupancy of the hot
    /// kernels (projection, reflection) and to check what a shader change did to them.
    ///
    /// Renders one frame of each camera of each scene with the runtime's default settings,
    /// its pipeline log on; converts every distinct pipeline's WGSL to SPIR-V as wgpu's Vulkan
    /// backend does, and compiles it on a Vulkan device of its own with
    /// VK_KHR_pipeline_executable_properties (the first that has it, a GPU before a CPU
    /// implementation). Needs the Vulkan loader and a driver with that extension (NVIDIA's,
    /// AMD's, Intel's, Mesa's RADV and ANV; not Mesa 22's lavapipe); run with
    /// WGPU_BACKEND=vulkan so that the frames choose the variants (subgroups) the GPU's wgpu
    /// device gets.
    PipelineStats(PipelineStatsArgs),
    /// Issue 13's goals judged from CSV files the other suites wrote (no GPU): whole frames
    /// at 4K, the projection against its floor, PPR against the cheapest low-quality SSR,
    /// the generated levels against shape count, collision-world. Prints a markdown report
    /// (and writes it with --out) saying which goals the files meet and by how much the
    /// others are missed.
    ///
    /// The runtime files should hold the `frame span` and `reflection own pass` profile rows
    /// (`runtime --projection-profile --profile-row "frame span" --profile-row "reflection
    /// own pass"`) and, for the scaling goals, the generated levels (`runtime --scene
    /// stairway-1 --scene stairway-1000 --scene stairway-10000 …`). Example:
    ///
    ///   ppr-bench goals --runtime results/profile --runtime results/generated
    ///     --compare results/compare --compare results/collision
    ///     --baseline-compare docs/perf/comparison_34_h100.csv --out goals.md
    #[command(verbatim_doc_comment)]
    Goals(GoalsArgs),
}

/// Options of `goals`.
#[derive(Args, Debug, Clone)]
pub struct GoalsArgs {
    /// A `runtime.csv`, or a `runtime --out` folder holding one (repeat).
    #[arg(long = "runtime", value_name = "CSV_OR_DIR")]
    pub runtime: Vec<PathBuf>,
    /// A `comparison.csv`, or a `compare --out` folder holding one (repeat).
    #[arg(long = "compare", value_name = "CSV_OR_DIR")]
    pub compare: Vec<PathBuf>,
    /// A compare run of the code whose on-screen PSNR full PPR must not fall below (without
    /// it the PSNR goal is not judged).
    #[arg(long = "baseline-compare", value_name = "CSV_OR_DIR")]
    pub baseline_compare: Option<PathBuf>,
    /// How many dB below the baseline's PSNR still count as no lower.
    #[arg(long, default_value_t = 0.02)]
    pub psnr_tolerance_db: f64,
    /// Also write the report to this file.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

/// Options of `pipeline-stats`.
#[derive(Args, Debug, Clone)]
pub struct PipelineStatsArgs {
    #[command(flatten)]
    pub paths: PathArgs,
    /// Scene to render (repeat; default: demo and kitchen, as `runtime`).
    #[arg(long = "scene")]
    pub scenes: Vec<String>,
    /// Render size of the frames (the plan, and so the variants, may depend on it).
    #[arg(long, default_value = "3840x2160")]
    pub resolution: Resolution,
    /// Most cameras per scene.
    #[arg(long, default_value_t = 3)]
    pub max_cameras: usize,
    /// Also compile the projection's ablations and options one at a time (the default
    /// frame's variant with each part left out or turned off): which part takes the
    /// registers and the shared memory.
    #[arg(long)]
    pub projection_variants: bool,
}

/// Options of `runtime`.
#[derive(Args, Debug, Clone)]
pub struct RuntimeArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Scene to run (repeat; default: demo and kitchen).
    #[arg(long = "scene")]
    pub scenes: Vec<String>,
    /// Render size (repeat; default: 1080p and 4k).
    #[arg(long = "resolution")]
    pub resolutions: Vec<Resolution>,
    /// Most cameras per scene.
    #[arg(long, default_value_t = 3)]
    pub max_cameras: usize,
    /// MiB in each buffer of the copy kernel that measures the bandwidth.
    #[arg(long, default_value_t = 256)]
    pub copy_mib: u64,
    /// Also run every scene with the glass/water layers and normal maps off (rows
    /// `<scene> (features off)`): what those features cost when a level has them; and with
    /// every reflector marked as normal-mapped (rows `<scene> (normal maps)`): what the
    /// normal-map variant of the reflection pass costs.
    #[arg(long)]
    pub features_off: bool,
    /// Also run every scene with each projection tuning and ablation (rows
    /// `<scene> [<tuning>]`): where the projection pass's time goes, part by part (and,
    /// rows `[reflection: …]`, the reflection pass's).
    #[arg(long)]
    pub projection_profile: bool,
    /// With `--projection-profile`: run only the profile rows of this name (repeat; e.g.
    /// `--profile-row "tests only" --profile-row "reflection: mirrors"`); an unknown
    /// name is an error that lists them. Default: every row.
    #[arg(long = "profile-row", value_name = "NAME")]
    pub profile_rows: Vec<String>,
    /// With `--projection-profile`: leave out the profile rows of this name (repeat), e.g.
    /// rows already timed in an earlier call; an unknown name is an error that lists them.
    #[arg(long = "skip-profile-row", value_name = "NAME")]
    pub skip_profile_rows: Vec<String>,
    /// Also time full-screen `Rgba16Float` writes (compute storage texture in several
    /// layouts, storage buffer, fragment pass) at each resolution: the floor of the
    /// reflection and upsample passes' output write.
    #[arg(long)]
    pub write_probe: bool,
    /// Also time a frame's upload before its first pass: small copies from host memory
    /// into device buffers (one per buffer, several into one, or one of everything), then
    /// a dispatch that reads them, between two encoder timestamps.
    #[arg(long)]
    pub upload_probe: bool,
    /// Also run every scene with every reflector at roughness 0.2, glossy on and off (rows
    /// `<scene> (roughness 0.2, glossy)` and `(…, glossy off)`): what the glossy blur costs.
    #[arg(long)]
    pub glossy: bool,
    /// Also time a stereo frame (one renderer, `prepare_stereo` + `encode_stereo`) against
    /// two mono frames, on each scene's first camera, at these per-eye sizes (repeat, e.g.
    /// `--stereo 2064x2208 --stereo 1920x1080`).
    #[arg(long = "stereo", value_parser = parse_size)]
    pub stereo: Vec<[u32; 2]>,
}

/// `goals`: judges the files, prints the report, writes it where asked.
fn run_goals(a: &GoalsArgs) -> Result<Vec<PathBuf>, BenchError> {
    let judgement = judge_files(&GoalFiles {
        runtime: a.runtime.clone(),
        compare: a.compare.clone(),
        baseline: a.baseline_compare.clone(),
        psnr_tolerance_db: a.psnr_tolerance_db,
    })?;
    print!("{}", judgement.markdown);
    match &a.out {
        Some(path) => {
            // Through a temporary file and a rename: a failed write leaves no half report.
            ppr_format::write_atomically(path, judgement.markdown.as_bytes())
                .map_err(|e| BenchError::io(path, e))?;
            Ok(vec![path.clone()])
        }
        None => Ok(Vec::new()),
    }
}

/// `WIDTHxHEIGHT`.
fn parse_size(text: &str) -> Result<[u32; 2], String> {
    let (w, h) = text.split_once('x').ok_or_else(|| format!("`{text}` is not WIDTHxHEIGHT"))?;
    let parse = |v: &str| {
        v.trim().parse::<u32>().map_err(|e| format!("`{text}`: {e}")).and_then(|n| {
            if (1..=16384).contains(&n) { Ok(n) } else { Err(format!("`{text}`: {n} is outside 1..=16384")) }
        })
    };
    Ok([parse(w)?, parse(h)?])
}

/// Options of `scaling`.
#[derive(Args, Debug, Clone)]
pub struct ScalingArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Shape counts (comma-separated).
    #[arg(long, value_delimiter = ',', default_value = "1,10,100,1000,10000")]
    pub counts: Vec<usize>,
    /// Shape counts of the tile-culling threshold sweep (comma-separated).
    #[arg(long, value_delimiter = ',', default_value = "1,2,4,8,16,32,64,128,256")]
    pub threshold_counts: Vec<usize>,
    /// Screen coverages of the indirect-dispatch sweep (comma-separated).
    #[arg(long, value_delimiter = ',', default_value = "0.05,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1.0")]
    pub coverages: Vec<f64>,
    /// Level families (repeat; default: stairway, tiled-floor, facade, rooms).
    #[arg(long = "family")]
    pub families: Vec<String>,
    /// Render size.
    #[arg(long, default_value = "3840x2160")]
    pub resolution: Resolution,
}

/// Options of `extract-trade`.
#[derive(Args, Debug, Clone)]
pub struct TradeArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Scene to run (repeat; default: demo, kitchen, small, collision-world).
    #[arg(long = "scene")]
    pub scenes: Vec<String>,
    /// Render size.
    #[arg(long, default_value = "3840x2160")]
    pub resolution: Resolution,
    /// Most cameras per scene.
    #[arg(long, default_value_t = 3)]
    pub max_cameras: usize,
}

/// Where a suite reads and writes (every suite takes them).
#[derive(Args, Debug, Clone)]
pub struct PathArgs {
    /// Folder for the reports (created if missing).
    #[arg(long, default_value = "target/bench")]
    pub out: PathBuf,
    /// Repository root (holds assets/demo_room.glb).
    #[arg(long, default_value = ".")]
    pub repo_root: PathBuf,
    /// Folder of the shared scenes.
    #[arg(long, default_value = "../shared/scenes")]
    pub scenes_dir: PathBuf,
}

impl PathArgs {
    /// The full-size configuration of these folders.
    fn config(&self) -> BenchConfig {
        BenchConfig::full(self.out.clone(), self.repo_root.clone(), self.scenes_dir.clone())
    }
}

/// Options every suite takes.
#[derive(Args, Debug, Clone)]
pub struct CommonArgs {
    #[command(flatten)]
    pub paths: PathArgs,
    /// Timed frames per run (after the warm-up).
    #[arg(long, default_value_t = 30)]
    pub frames: usize,
    /// Warm-up frames per run.
    #[arg(long, default_value_t = 5)]
    pub warmup: usize,
    /// Timed frames of runs whose first timed frame takes more than 50 ms.
    #[arg(long, default_value_t = 10)]
    pub slow_frames: usize,
    /// MiB written to a scratch buffer before each frame to evict the GPU caches (0: none).
    #[arg(long, default_value_t = 256)]
    pub flush_mib: u64,
    /// Small and fast, for CI: the demo level, one camera, 64x36, 1 warm-up and 3 timed frames.
    #[arg(long)]
    pub quick: bool,
}

/// Options of `compare`.
#[derive(Args, Debug, Clone)]
pub struct CompareArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Scene to run (repeat; default: demo, kitchen, small, collision-world).
    #[arg(long = "scene")]
    pub scenes: Vec<String>,
    /// Camera name to keep (repeat; default: every camera of the scene, up to --max-cameras).
    #[arg(long = "camera")]
    pub cameras: Vec<String>,
    /// Most cameras per scene.
    #[arg(long, default_value_t = 3)]
    pub max_cameras: usize,
    /// Render size, WIDTHxHEIGHT or 1080p/1440p/4k/8k (repeat; default: all four).
    #[arg(long = "resolution")]
    pub resolutions: Vec<Resolution>,
    /// Technique and setting, `name` or `name:key=value,...` (repeat; default: every PPR
    /// setting, exact, and the baselines with several SSR step counts and thicknesses).
    /// Names: ppr-raw, ppr-holes, ppr-filter, ppr (culling=, indirect=, trees=, blockers=
    /// on|off|auto; fade= border fade as a fraction of the shorter side, 0..0.5;
    /// replace-far= on|off, the seed's 6-px rule;
    /// tier= full|half|quarter, the resolution the passes run at), exact,
    /// ppr:glossy=off (every reflector blurred as a mirror), ppr:timing=frame (the whole
    /// frame between two encoder timestamps instead of the sum of its passes' own, which
    /// leaves out the barriers between them and the upload's copies; the SSR and SSPR
    /// baselines take timing=frame too, and then record none of their own pass timestamps
    /// inside the span, as PPR records none), ppr:upsample=shared|per-pixel (the reduced tiers'
    /// upsample reads each workgroup's reduced samples once into workgroup memory, or each
    /// pixel its own, the default; the same image; or store-only|depth-only|no-own-depth,
    /// probes of its time, not its image), ssr-brute (thickness=),
    /// ssr-low (stride=, refine=, thickness=), ssr-glossy (ssr-low's march and keys, then a
    /// blur of radius spread × roughness² × hit distance: spread= default 4, max-radius= in
    /// pixels default 32, taps= default 24), ssr-hiz (iterations=, thickness=), sspr,
    /// sspr-stretch, planar.
    #[arg(long = "technique")]
    pub techniques: Vec<TechniqueSpec>,
    /// Measure quality only up to this many megapixels (FLIP runs on the CPU; the default
    /// skips 8K).
    #[arg(long, default_value_t = 8.3)]
    pub quality_max_mpix: f64,
    /// Size of the Pareto plots and of the cost ratios.
    #[arg(long, default_value = "3840x2160")]
    pub pareto_resolution: Resolution,
    /// Size of the image sheet's crops.
    #[arg(long, default_value = "1920x1080")]
    pub sheet_resolution: Resolution,
    /// What every row is scored against: `glossy` (the exact glossy reference on scenes
    /// whose reflectors have roughness > 0: views from eye points around the mirrored camera,
    /// self-normalised importance sampling of the GGX lobe; the mirror reference elsewhere)
    /// or `mirror` (every reflector as a perfect mirror).
    #[arg(long, value_enum, default_value_t = ReferenceKind::Glossy)]
    pub reference: ReferenceKind,
    /// Views per rough reflector plane of the glossy reference (default 256; 64 with --quick).
    #[arg(long)]
    pub glossy_samples: Option<u32>,
}

/// The size of `--quick` runs.
const TINY: Resolution = Resolution { width: 64, height: 36 };

/// The given list, or the quick or full default.
fn pick<T: Clone, D: Clone + Into<T>>(
    given: &[T],
    quick: bool,
    quick_default: &[D],
    full_default: &[D],
) -> Vec<T> {
    if !given.is_empty() {
        return given.to_vec();
    }
    let d = if quick { quick_default } else { full_default };
    d.iter().cloned().map(Into::into).collect()
}

fn bench_config(common: &CommonArgs, command_line: &str) -> BenchConfig {
    let mut cfg = common.paths.config();
    cfg.frames.timed = common.frames.max(1);
    cfg.frames.warmup = common.warmup;
    cfg.frames.slow_timed = common.slow_frames.min(cfg.frames.timed);
    cfg.flush_bytes = common.flush_mib << 20;
    cfg.command_line = command_line.to_owned();
    if common.quick { cfg.into_quick() } else { cfg }
}

fn compare_config(args: &CompareArgs, quick: bool) -> CompareConfig {
    let scenes = match (args.scenes.is_empty(), quick) {
        (false, _) => args.scenes.clone(),
        (true, true) => vec!["demo".into()],
        (true, false) => ["demo", "kitchen", "small", "collision-world"].map(String::from).to_vec(),
    };
    let resolutions = match (args.resolutions.is_empty(), quick) {
        (false, _) => args.resolutions.clone(),
        (true, true) => vec![TINY],
        (true, false) => Resolution::STANDARD.to_vec(),
    };
    let techniques =
        if args.techniques.is_empty() { TechniqueSpec::defaults() } else { args.techniques.clone() };
    CompareConfig {
        scenes,
        cameras: if quick && args.cameras.is_empty() {
            vec!["cam_mirror".into()]
        } else {
            args.cameras.clone()
        },
        max_cameras: args.max_cameras,
        resolutions: resolutions.clone(),
        techniques,
        quality_max_pixels: (args.quality_max_mpix * 1e6) as u64,
        sheet_resolution: if quick { resolutions[0] } else { args.sheet_resolution },
        reference: args.reference,
        glossy_samples: args.glossy_samples.unwrap_or(if quick { 64 } else { 256 }),
        pareto_resolution: if quick { resolutions[0] } else { args.pareto_resolution },
    }
}

/// Parses `args` (the first is the program name) and runs the suite; returns the files
/// written.
///
/// # Errors
/// Bad arguments (clap's message), no GPU adapter, or a failing suite.
pub fn run_cli<I, T>(args: I) -> Result<Vec<PathBuf>, BenchError>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let args: Vec<std::ffi::OsString> = args.into_iter().map(Into::into).collect();
    let command_line = args.iter().map(|a| a.to_string_lossy().into_owned()).collect::<Vec<_>>().join(" ");
    let cli = Cli::try_parse_from(&args).map_err(|e| BenchError::Spec(e.to_string()))?;
    // `goals` reads files only: answered before a GPU is asked for.
    let gpu = match &cli.suite {
        Suite::Goals(a) => return run_goals(a),
        _ => GpuContext::new_headless()?,
    };
    eprintln!("adapter: {}", gpu.describe());
    match &cli.suite {
        Suite::Compare(a) => {
            let cfg = bench_config(&a.common, &command_line);
            let cc = compare_config(a, cfg.quick);
            // The report is rewritten after every scene, so a run cut short keeps what it did.
            let mut write = |o: &CompareOutcome| {
                write_compare_report(
                    &cfg.out_dir,
                    o,
                    &command_line,
                    cc.pareto_resolution,
                    cc.quality_max_pixels,
                )
                .map(|_| ())
            };
            let outcome = run_compare(&gpu, &cfg, &cc, &mut write)?;
            write_compare_report(
                &cfg.out_dir,
                &outcome,
                &command_line,
                cc.pareto_resolution,
                cc.quality_max_pixels,
            )
        }
        Suite::Runtime(a) => {
            let cfg = bench_config(&a.common, &command_line);
            let rc = RuntimeConfig {
                scenes: pick(&a.scenes, cfg.quick, &["demo"], &["demo", "kitchen"]),
                resolutions: pick(&a.resolutions, cfg.quick, &[TINY], &[Resolution::HD, Resolution::UHD]),
                max_cameras: if cfg.quick { 1 } else { a.max_cameras },
                copy_bytes: if cfg.quick { 1 << 20 } else { a.copy_mib << 20 },
                features_off: a.features_off,
                projection_profile: a.projection_profile,
                profile_rows: a.profile_rows.clone(),
                skip_profile_rows: a.skip_profile_rows.clone(),
                write_probe: a.write_probe,
                upload_probe: a.upload_probe,
                glossy: a.glossy,
                stereo_sizes: a.stereo.clone(),
            };
            let outcome = run_runtime(&gpu, &cfg, &rc)?;
            write_runtime_report(&cfg.out_dir, &outcome, &command_line)
        }
        Suite::Scaling(a) => {
            let cfg = bench_config(&a.common, &command_line);
            let families = if a.families.is_empty() {
                LevelFamily::ALL.to_vec()
            } else {
                a.families
                    .iter()
                    .map(|f| {
                        LevelFamily::ALL.into_iter().find(|k| k.as_str() == f).ok_or_else(|| {
                            BenchError::Spec(format!(
                                "unknown family `{f}` (stairway, tiled-floor, facade, rooms)"
                            ))
                        })
                    })
                    .collect::<Result<_, _>>()?
            };
            let sc = ScalingConfig {
                families,
                counts: if cfg.quick { vec![1, 10] } else { a.counts.clone() },
                threshold_counts: if cfg.quick { vec![1, 2] } else { a.threshold_counts.clone() },
                coverages: if cfg.quick { vec![0.2, 1.0] } else { a.coverages.clone() },
                resolution: if cfg.quick { TINY } else { a.resolution },
            };
            let outcome = run_scaling(&gpu, &cfg, &sc)?;
            write_scaling_report(&cfg.out_dir, &outcome, &command_line)
        }
        Suite::ExtractTrade(a) => {
            let cfg = bench_config(&a.common, &command_line);
            let tc = TradeConfig {
                scenes: pick(
                    &a.scenes,
                    cfg.quick,
                    &["demo"],
                    &["demo", "kitchen", "small", "collision-world"],
                ),
                resolution: if cfg.quick { TINY } else { a.resolution },
                max_cameras: if cfg.quick { 1 } else { a.max_cameras },
            };
            let (rows, notes) = run_extract_trade(&gpu, &cfg, &tc)?;
            write_trade_report(&cfg.out_dir, &rows, &notes, &gpu.describe(), tc.resolution, &command_line)
        }
        Suite::Goals(_) => unreachable!("`goals` returned before the GPU was made"),
        Suite::PipelineStats(a) => {
            let mut cfg = a.paths.config();
            cfg.command_line = command_line.clone();
            let pc = PipelineStatsConfig {
                scenes: pick(&a.scenes, false, &["demo"], &["demo", "kitchen"]),
                resolution: a.resolution,
                max_cameras: a.max_cameras,
                projection_variants: a.projection_variants,
            };
            let outcome = run_pipeline_stats(&gpu, &cfg, &pc)?;
            write_pipeline_stats_report(&cfg.out_dir, &outcome, &command_line)
        }
    }
}
