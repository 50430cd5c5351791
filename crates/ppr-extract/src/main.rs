//! The `ppr-extract` command: parses arguments, then loads, extracts, writes and prints the
//! summary through the library.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use anyhow::Context as _;
use clap::Parser;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use ppr_extract::edits_file::{keep_previous, reapply_edits, save_edits};
use ppr_extract::manual_edits::{EditedSet, ManualEdits};
use ppr_extract::{CandidateRule, ExtractParams, Stage, extract, load_level, summary::summary_table};
use ppr_format::edits::edits_path;

/// Exit status: success.
const EXIT_OK: u8 = 0;
/// Exit status: bad command line.
const EXIT_USAGE: u8 = 1;
/// Exit status: the input could not be read or is not valid glTF.
const EXIT_INPUT: u8 = 2;
/// Exit status: the output could not be written.
const EXIT_OUTPUT: u8 = 3;
/// Exit status: the extracted set failed validation (a bug).
const EXIT_INTERNAL: u8 = 4;

/// Extractions still running after this long show a progress bar (on a terminal).
const PROGRESS_AFTER: Duration = Duration::from_secs(1);

const AFTER_HELP: &str = "\
CANDIDATES:
  A triangle is a candidate when its node's, else its mesh's, else its material's glTF
  extras say {\"ppr\": {\"reflector\": true}}; never when they say false. Otherwise, by
  material: roughness <= 0.3, or metallic >= 0.8 with roughness <= 0.5, or transmission
  > 0, or clear coat >= 0.5 with clear-coat roughness <= 0.3, or a material, mesh or node
  name containing mirror, glass, water, puddle, chrome or polished. With --all-planar
  every triangle is a candidate (for levels with one material for everything) and
  every reflector a mirror (roughness 0, whatever the material says).
  Kind: extras {\"ppr\": {\"kind\": \"opaque|transparent|water\"}} wins; else a name
  containing \"water\" gives water; else transmission > 0 or a name containing \"glass\"
  or \"window\" gives transparent; else opaque.

EXAMPLES:
  ppr-extract level.glb                      writes level.ppr.json beside it
  ppr-extract level.gltf -o out/level.ppr.json
  ppr-extract collision-world.glb --all-planar --min-area 0.5
  ppr-extract level.glb --angle-tolerance 2 --distance-tolerance 0.002 --reach 5
  ppr-extract level_in_cm.glb --unit 0.01      tolerances stay in metres

UNITS:
  Lengths are metres and areas m² (glTF's unit), never fractions of the level's size: the
  same room gives the same rectangles alone or inside a large level. Defaults (measured
  on the shared scenes, docs/perf/extract.md): vertices within 5 mm of their plane (the
  reflection moves by at most 1 cm), gaps up to 5 mm bridged, regions under 0.01 m²
  dropped, touching regions within 2° merged when the reflection error at 1 m stays
  under 8 cm, occluders looked for anywhere in front of a reflector, at most 64 per list,
  at most 128 rectangles in any 10 m cube (the density budget: what a view that sees a
  few rooms can afford; see --max-per-cube).

MANUAL EDITS:
  When the output set has manual edits beside it (level.ppr.edits.json, written by
  ppr-inspector), they are re-applied to the fresh extraction, matched by the reflectors'
  stable ids, and the edits file is rewritten for the new set. Each edit re-applied and each
  that no longer matches is listed by name; when one no longer matches, the previous set and
  its edits are kept as level.ppr.previous.json and level.ppr.previous.edits.json. With
  --ignore-edits the fresh extraction is written as it is, the edits file is removed and
  the previous set and its edits are kept the same way.

EXIT CODES:
  0  success (the set was written; it may be empty: see the notes)
  1  usage error (bad arguments)
  2  the input cannot be read: missing file, not glTF, truncated .glb, missing external
     buffer, accessor out of range, NaN positions, a required extension it cannot read
     or the manual edits beside the output (<set>.edits.json) cannot be read or applied
  3  the output cannot be written (nothing partial is left behind)
  4  internal error: the extracted set failed validation (please report it)";

/// Extract planar reflectors (rectangles, occluder lists) from a glTF level.
///
/// Reads a .glb or .gltf, finds reflective planar areas, fits them with rectangles and
/// writes a reflector set (`*.ppr.json`) atomically, then prints a summary.
#[derive(Parser, Debug)]
#[command(name = "ppr-extract", version, about, long_about, after_long_help = AFTER_HELP, after_help = "See --help for the candidate rule, examples and exit codes.")]
struct Cli {
    /// The level: a .glb, or a .gltf with its buffers.
    input: PathBuf,
    /// Where to write the set [default: <input stem>.ppr.json beside the input].
    #[arg(short, long, value_name = "PATH")]
    output: Option<PathBuf>,
    /// Every planar area is a candidate, whatever its material.
    #[arg(long)]
    all_planar: bool,
    /// Size of one level unit in metres, for levels not modelled in metres (glTF's unit):
    /// 0.01 for centimetres. Every length and area below is in metres and m² and is
    /// converted.
    #[arg(long, value_name = "METRES", default_value_t = 1.0)]
    unit: f64,
    /// Smallest reflective area kept, m² (a 10 × 10 cm tile by default).
    #[arg(long, value_name = "M2", default_value_t = ExtractParams::default().min_area_m2)]
    min_area: f64,
    /// Largest angle between a triangle and its plane, degrees.
    #[arg(long, value_name = "DEG", default_value_t = ExtractParams::default().angle_tolerance_deg)]
    angle_tolerance: f64,
    /// Largest distance of a vertex from its plane, metres (the reflection moves by twice this).
    #[arg(long, value_name = "METRES", default_value_t = ExtractParams::default().distance_tolerance_m)]
    distance_tolerance: f64,
    /// Gap bridged between triangles of one region (T-junctions, loose welds), metres.
    #[arg(long, value_name = "METRES", default_value_t = ExtractParams::default().gap_tolerance_m)]
    gap_tolerance: f64,
    /// How far in front of a reflector occluders are looked for, metres [default: anywhere
    /// in front of it].
    #[arg(long, value_name = "METRES")]
    reach: Option<f64>,
    /// Most occluders listed per reflector (the largest as seen from it are kept; the
    /// summary says how many lists were cut).
    #[arg(long, value_name = "N", default_value_t = ExtractParams::default().max_occluders)]
    max_occluders: usize,
    /// Touching regions whose planes are less than this apart merge into one plane when the
    /// reflection error stays under --max-reflection-error, degrees (0: never).
    #[arg(long, value_name = "DEG", default_value_t = ExtractParams::default().near_planar_angle_deg)]
    near_planar_angle: f64,
    /// Largest reflection error a near-planar merge may cause: how far the image of a point
    /// 1 m in front of the surface moves, metres (each merge is reported with its error).
    #[arg(long, value_name = "METRES", default_value_t = ExtractParams::default().max_reflection_error_m)]
    max_reflection_error: f64,
    /// Split a non-convex region when each extra rectangle saves this fraction of the
    /// region's rectangle.
    #[arg(long, value_name = "FRACTION", default_value_t = ExtractParams::default().split_min_gain)]
    split_min_gain: f64,
    /// Density budget: most rectangles in any cube of --budget-cube metres (regions and
    /// splits are kept by the area they buy per rectangle; the summary says what was left).
    #[arg(long, value_name = "N", default_value_t = ExtractParams::default().max_shapes_per_cube)]
    max_per_cube: usize,
    /// Edge of the density budget's cubes, metres (a grid aligned with the world origin).
    #[arg(long, value_name = "METRES", default_value_t = ExtractParams::default().budget_cube_m)]
    budget_cube: f64,
    /// Most rectangles per region.
    #[arg(long, value_name = "N", default_value_t = ExtractParams::default().max_shapes_per_region)]
    max_shapes_per_region: usize,
    /// Write the fresh extraction without re-applying the manual edits found beside the
    /// output (`<set>.edits.json`); the previous set and its edits are kept as
    /// `<set stem>.previous.json` and `.previous.edits.json`.
    #[arg(long)]
    ignore_edits: bool,
    /// No progress bar and no summary (errors still go to stderr).
    #[arg(short, long)]
    quiet: bool,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let code = if e.use_stderr() { EXIT_USAGE } else { EXIT_OK };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    match run(&cli) {
        Ok(()) => ExitCode::from(EXIT_OK),
        Err(failure) => {
            eprintln!("ppr-extract: error: {:#}", failure.error);
            ExitCode::from(failure.code)
        }
    }
}

struct Failure {
    code: u8,
    error: anyhow::Error,
}

fn fail(code: u8) -> impl FnOnce(anyhow::Error) -> Failure {
    move |error| Failure { code, error }
}

fn params_from(cli: &Cli) -> Result<ExtractParams, String> {
    if !(cli.unit.is_finite() && cli.unit > 0.0) {
        return Err(format!("unit must be finite and positive, not {}", cli.unit));
    }
    let params = ExtractParams {
        candidates: if cli.all_planar { CandidateRule::AllPlanar } else { CandidateRule::Materials },
        min_area_m2: cli.min_area,
        angle_tolerance_deg: cli.angle_tolerance,
        distance_tolerance_m: cli.distance_tolerance,
        gap_tolerance_m: cli.gap_tolerance,
        reach_m: cli.reach,
        max_occluders: cli.max_occluders,
        split_min_gain: cli.split_min_gain,
        max_shapes_per_region: cli.max_shapes_per_region,
        max_shapes_per_cube: cli.max_per_cube,
        near_planar_angle_deg: cli.near_planar_angle,
        max_reflection_error_m: cli.max_reflection_error,
        budget_cube_m: cli.budget_cube,
        ..ExtractParams::default()
    };
    params.validate()?;
    Ok(params.in_level_units(cli.unit))
}

/// `<stem>.ppr.json` beside the input.
fn default_output(input: &Path) -> PathBuf {
    let stem = input.file_stem().map_or_else(|| "level".into(), |s| s.to_string_lossy().into_owned());
    input.with_file_name(format!("{stem}.ppr.json"))
}

fn run(cli: &Cli) -> Result<(), Failure> {
    let params = params_from(cli).map_err(|e| fail(EXIT_USAGE)(anyhow::anyhow!("bad parameter: {e}")))?;
    let output = cli.output.clone().unwrap_or_else(|| default_output(&cli.input));

    let started = Instant::now();
    let level = load_level(&cli.input).map_err(|e| fail(EXIT_INPUT)(e.into()))?;
    let load_time = started.elapsed();

    let bar = ProgressBar::hidden();
    let show_bar = !cli.quiet && std::io::stderr().is_terminal();
    let extract_started = Instant::now();
    let extraction = extract(&level, &params, &|stage, f| {
        if show_bar && bar.is_hidden() && extract_started.elapsed() >= PROGRESS_AFTER {
            show_progress(&bar);
        }
        bar.set_message(stage.name());
        bar.set_position((f.clamp(0.0, 1.0) * 100.0) as u64);
    });
    bar.finish_and_clear();

    let started = Instant::now();
    let edited = with_manual_edits(cli, &output, EditedSet::from_extraction(&extraction))?;
    let text =
        edited.set.to_json_string().context("the extracted set is invalid").map_err(fail(EXIT_INTERNAL))?;
    ppr_format::write_atomically(&output, text.as_bytes())
        .with_context(|| format!("{}: cannot write", output.display()))
        .map_err(fail(EXIT_OUTPUT))?;
    save_edits(&output, &edited.edits).map_err(|e| fail(EXIT_OUTPUT)(e.into()))?;
    let write_time = started.elapsed();

    if !cli.quiet {
        let mut timings: Vec<(Stage, Duration)> = vec![(Stage::Load, load_time)];
        timings.extend(extraction.timings.iter().copied());
        timings.push((Stage::Write, write_time));
        println!("ppr-extract: {} -> {}", cli.input.display(), output.display());
        print!("{}", summary_table(&extraction, &timings));
    }
    Ok(())
}

/// `fresh` with the manual edits beside `output` re-applied (or, with `--ignore-edits`,
/// unchanged, the previous set kept aside); says on stderr what was and was not applied.
fn with_manual_edits(cli: &Cli, output: &Path, fresh: EditedSet) -> Result<EditedSet, Failure> {
    let edits = edits_path(output);
    if cli.ignore_edits {
        if edits.exists() {
            let previous = keep_previous(output).map_err(|e| fail(EXIT_OUTPUT)(e.into()))?;
            save_edits(output, &ManualEdits::default()).map_err(|e| fail(EXIT_OUTPUT)(e.into()))?;
            eprintln!(
                "ppr-extract: --ignore-edits: the manual edits in {} were not applied; the previous set \
                 and its edits are kept as {}",
                edits.display(),
                previous.display()
            );
        }
        return Ok(fresh);
    }
    let (carried, report) = reapply_edits(output, fresh)
        .context("pass --ignore-edits to write the fresh extraction without them")
        .map_err(fail(EXIT_INPUT))?;
    let Some(report) = report else {
        return Ok(carried);
    };
    eprintln!("ppr-extract: re-applied {} of the manual edits in {}", report.kept.len(), edits.display());
    for kept in &report.kept {
        eprintln!("  re-applied: {kept}");
    }
    if !report.not_applicable.is_empty() {
        let previous = keep_previous(output).map_err(|e| fail(EXIT_OUTPUT)(e.into()))?;
        for lost in &report.not_applicable {
            eprintln!("ppr-extract: warning: {lost}");
        }
        eprintln!(
            "ppr-extract: warning: {} manual edit(s) no longer match the level; the previous set and its \
             edits are kept as {}",
            report.not_applicable.len(),
            previous.display()
        );
    }
    Ok(carried)
}

/// Draws `bar` on stderr from now on.
fn show_progress(bar: &ProgressBar) {
    bar.set_length(100);
    if let Ok(style) = ProgressStyle::with_template("{msg:>10} [{bar:40}] {pos:>3}% {elapsed}") {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_draw_target(ProgressDrawTarget::stderr());
    bar.enable_steady_tick(Duration::from_millis(200));
}
