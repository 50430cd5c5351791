//! The comparison's files: `comparison.csv` (one row per run), `comparison_passes.csv` (one
//! row per pass), `comparison_causes.csv` (full PPR's error by cause), `comparison.md` (tables
//! per scene and size, the seed's ratios, the Pareto fronts, the error by cause),
//! `pareto_<scene>.png` and `image_sheet.png`.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::config::Resolution;
use crate::error::BenchError;
use crate::report::causes_report::{causes_csv, causes_markdown};
use crate::report::csv_file::{CsvTable, num};
use crate::report::image_sheet::write_sheet;
use crate::report::markdown::{MarkdownTable, ms};
use crate::report::plot::{PALETTE, PlotPoint, PlotSeries, PlotSpec, write_plot};
use crate::run_result::RunResult;
use crate::suites::compare::CompareOutcome;
use crate::technique::Family;

/// Columns of `comparison.csv`.
pub const RESULT_COLUMNS: [&str; 24] = [
    "scene",
    "camera",
    "width",
    "height",
    "technique",
    "family",
    "frames",
    "timing_source",
    "gpu_total_median_ms",
    "gpu_total_p95_ms",
    "passes_median_ms",
    "passes_p95_ms",
    "quality",
    "psnr_on_screen_db",
    "psnr_off_screen_db",
    "flip_on_screen",
    "flip_off_screen",
    "no_data_on_screen",
    "no_data_all",
    "on_screen_px",
    "off_screen_px",
    "adapter",
    "plan",
    "command",
];

/// Text of a quality column when quality was not measured at that size.
pub const SKIPPED: &str = "skipped";

/// `comparison.csv`.
pub fn results_csv(outcome: &CompareOutcome, command: &str) -> CsvTable {
    let mut t = CsvTable::new(&RESULT_COLUMNS);
    for r in &outcome.results {
        let total = r.timings.total();
        let passes = r.timings.passes();
        let join = |p95: bool| {
            passes
                .iter()
                .map(|(n, s)| format!("{n}={:.4}", if p95 { s.p95 } else { s.median }))
                .collect::<Vec<_>>()
                .join(";")
        };
        let q = |f: &dyn Fn(&crate::quality::Quality) -> String| {
            r.quality.as_ref().map_or(SKIPPED.to_string(), f)
        };
        t.push(vec![
            r.scene.clone(),
            r.camera.clone(),
            r.resolution.width.to_string(),
            r.resolution.height.to_string(),
            r.technique.clone(),
            r.family.as_str().into(),
            r.timings.frames().to_string(),
            r.timing_source.as_str().into(),
            total.map_or("nan".into(), |s| num(s.median, 4)),
            total.map_or("nan".into(), |s| num(s.p95, 4)),
            join(false),
            join(true),
            if r.quality.is_some() { "measured".into() } else { SKIPPED.into() },
            q(&|q| num(q.psnr_on, 3)),
            q(&|q| num(q.psnr_off, 3)),
            q(&|q| num(q.flip_on, 5)),
            q(&|q| num(q.flip_off, 5)),
            q(&|q| num(q.holes_on, 5)),
            q(&|q| num(q.holes_all, 5)),
            q(&|q| q.pixels.0.to_string()),
            q(&|q| q.pixels.1.to_string()),
            outcome.adapter.clone(),
            r.plan.clone(),
            command.into(),
        ]);
    }
    t
}

/// `comparison_passes.csv`.
pub fn passes_csv(outcome: &CompareOutcome) -> CsvTable {
    let mut t = CsvTable::new(&[
        "scene",
        "camera",
        "width",
        "height",
        "technique",
        "pass",
        "median_ms",
        "p95_ms",
        "frames",
        "timing_source",
    ]);
    for r in &outcome.results {
        for (pass, s) in r.timings.passes() {
            t.push(vec![
                r.scene.clone(),
                r.camera.clone(),
                r.resolution.width.to_string(),
                r.resolution.height.to_string(),
                r.technique.clone(),
                pass,
                num(s.median, 4),
                num(s.p95, 4),
                s.count.to_string(),
                r.timing_source.as_str().into(),
            ]);
        }
    }
    t
}

/// A technique on one scene and size, averaged over the scene's cameras.
#[derive(Clone, Debug, Default)]
pub struct Aggregate {
    pub technique: String,
    pub family: Option<Family>,
    pub cameras: usize,
    pub total_median: f64,
    pub total_p95: f64,
    /// Pass name → (mean median, mean p95).
    pub passes: Vec<(String, f64, f64)>,
    pub psnr_on: Option<f64>,
    pub psnr_off: Option<f64>,
    pub flip_on: Option<f64>,
    pub flip_off: Option<f64>,
    pub holes_on: Option<f64>,
    pub holes_all: Option<f64>,
}

fn mean(v: &[f64]) -> Option<f64> {
    (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
}

/// Mean over cameras per (scene, resolution, technique), techniques in run order.
pub fn aggregate(results: &[RunResult]) -> BTreeMap<(String, Resolution), Vec<Aggregate>> {
    let mut out: BTreeMap<(String, Resolution), Vec<Aggregate>> = BTreeMap::new();
    let mut runs: BTreeMap<(String, Resolution, String), Vec<&RunResult>> = BTreeMap::new();
    let mut order: Vec<(String, Resolution, String)> = Vec::new();
    for r in results {
        let key = (r.scene.clone(), r.resolution, r.technique.clone());
        if !runs.contains_key(&key) {
            order.push(key.clone());
        }
        runs.entry(key).or_default().push(r);
    }
    for key in order {
        let rs = &runs[&key];
        let totals: Vec<(f64, f64)> =
            rs.iter().filter_map(|r| r.timings.total()).map(|s| (s.median, s.p95)).collect();
        let mut pass_names: Vec<String> = Vec::new();
        for r in rs {
            for (n, _) in r.timings.passes() {
                if !pass_names.contains(&n) {
                    pass_names.push(n);
                }
            }
        }
        let passes = pass_names
            .into_iter()
            .map(|n| {
                let s: Vec<(f64, f64)> =
                    rs.iter().filter_map(|r| r.timings.pass(&n)).map(|s| (s.median, s.p95)).collect();
                let m = mean(&s.iter().map(|p| p.0).collect::<Vec<_>>()).unwrap_or(f64::NAN);
                let p = mean(&s.iter().map(|p| p.1).collect::<Vec<_>>()).unwrap_or(f64::NAN);
                (n, m, p)
            })
            .collect();
        let q = |f: &dyn Fn(&crate::quality::Quality) -> f64| {
            mean(&rs.iter().filter_map(|r| r.quality.as_ref().map(f)).collect::<Vec<_>>())
        };
        out.entry((key.0.clone(), key.1)).or_default().push(Aggregate {
            technique: key.2.clone(),
            family: rs.first().map(|r| r.family),
            cameras: rs.len(),
            total_median: mean(&totals.iter().map(|t| t.0).collect::<Vec<_>>()).unwrap_or(f64::NAN),
            total_p95: mean(&totals.iter().map(|t| t.1).collect::<Vec<_>>()).unwrap_or(f64::NAN),
            passes,
            psnr_on: q(&|q| q.psnr_on),
            psnr_off: q(&|q| q.psnr_off),
            flip_on: q(&|q| q.flip_on),
            flip_off: q(&|q| q.flip_off),
            holes_on: q(&|q| q.holes_on),
            holes_all: q(&|q| q.holes_all),
        });
    }
    out
}

fn opt(v: Option<f64>, decimals: usize) -> String {
    match v {
        None => SKIPPED.into(),
        Some(v) if v.is_infinite() => "∞".into(),
        Some(v) => format!("{v:.decimals$}"),
    }
}

fn pct(v: Option<f64>) -> String {
    v.map_or(SKIPPED.into(), |v| format!("{:.2}%", v * 100.0))
}

/// Indices of the points on the Pareto front of (time ↓, accuracy ↑).
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    (0..points.len())
        .filter(|&i| {
            let (t, a) = points[i];
            t.is_finite()
                && !a.is_nan()
                && !points.iter().enumerate().any(|(j, &(t2, a2))| {
                    j != i && t2.is_finite() && !a2.is_nan() && t2 <= t && a2 >= a && (t2 < t || a2 > a)
                })
        })
        .collect()
}

/// The markdown table of one scene and size.
pub fn scene_table(aggs: &[Aggregate]) -> String {
    let mut t = MarkdownTable::new(&[
        "technique",
        "#GPU ms median",
        "#p95",
        "passes: median / p95 ms",
        "#PSNR on-screen dB",
        "#PSNR off-screen dB",
        "#FLIP on",
        "#FLIP off",
        "#no data (on-screen)",
        "#no data (all)",
    ]);
    for a in aggs {
        let passes: Vec<String> = a.passes.iter().map(|(n, m, p)| format!("{n} {m:.3} / {p:.3}")).collect();
        t.push(vec![
            a.technique.clone(),
            ms(a.total_median),
            ms(a.total_p95),
            passes.join("; "),
            opt(a.psnr_on, 2),
            opt(a.psnr_off, 2),
            opt(a.flip_on, 4),
            opt(a.flip_off, 4),
            pct(a.holes_on),
            pct(a.holes_all),
        ]);
    }
    t.render()
}

/// The seed's ratios on one scene and size: named baselines over PPR.
fn ratio_rows(scene: &str, res: Resolution, aggs: &[Aggregate], table: &mut MarkdownTable) {
    let Some(ppr) = aggs.iter().find(|a| a.technique == "ppr") else { return };
    let seed: [(&str, &str); 3] = [
        ("ssr-brute", "brute-force SSR / PPR (seed 20.6 / 0.95 = 21.7×)"),
        ("ssr-hiz", "Hi-Z SSR with its build / PPR (seed 3.55 / 0.95 = 3.7×)"),
        ("ssr-low", "low-quality SSR / PPR (seed 0.95 / 0.95 = 1.0×)"),
    ];
    for a in aggs.iter().filter(|a| a.technique != "ppr") {
        let what = seed
            .iter()
            .find(|(prefix, _)| a.technique.starts_with(prefix))
            .map_or_else(|| format!("{} / PPR", a.technique), |(_, w)| (*w).to_string());
        table.push(vec![
            scene.into(),
            res.to_string(),
            what,
            a.technique.clone(),
            ms(a.total_median),
            ms(ppr.total_median),
            format!("{:.2}×", a.total_median / ppr.total_median),
        ]);
    }
}

/// Writes every file of the comparison under `dir`; returns their paths.
///
/// # Errors
/// A file cannot be written.
pub fn write_compare_report(
    dir: &Path,
    outcome: &CompareOutcome,
    command: &str,
    pareto_resolution: Resolution,
    quality_max_pixels: u64,
) -> Result<Vec<PathBuf>, BenchError> {
    std::fs::create_dir_all(dir).map_err(|e| BenchError::io(dir, e))?;
    let mut files = Vec::new();
    let csv = dir.join("comparison.csv");
    results_csv(outcome, command).write(&csv)?;
    files.push(csv);
    let csv = dir.join("comparison_passes.csv");
    passes_csv(outcome).write(&csv)?;
    files.push(csv);
    if !outcome.causes.is_empty() {
        let csv = dir.join("comparison_causes.csv");
        causes_csv(&outcome.causes).write(&csv)?;
        files.push(csv);
    }

    let aggs = aggregate(&outcome.results);
    let mut md = String::new();
    let _ = writeln!(md, "# Comparison: PPR against the exact reflection and the baselines\n");
    let _ = writeln!(md, "Machine: **{}**.\n", outcome.adapter);
    let _ = writeln!(md, "Command:\n\n```sh\n{command}\n```\n");
    let frames = outcome.results.iter().map(|r| r.timings.frames()).max().unwrap_or(0);
    let _ = writeln!(
        md,
        "Every number is per technique and size, averaged over the scene's cameras (`comparison.csv` \
         has each camera). GPU times are medians (and 95th percentiles) of {frames} frames' GPU \
         timestamps after warm-up, the faster of two runs (one run, with fewer frames, see the \
         `frames` column of the CSV, for runs whose first timed frame took over 50 ms: \
         brute-force SSR and the exact re-render at high resolutions); each frame first overwrites a scratch buffer so that no input sits in \
         the L2 cache. Quality is against the exact planar reflection (the scene \
         re-rendered from the mirrored camera; on reflectors with roughness > 0, unless \
         `--reference mirror`, the exact glossy reference: views from eye points around the \
         mirrored camera summed with GGX importance weights, see the notes), over reflector \
         pixels, split into pixels whose \
         reflected point is on screen (what a screen-space method can get) and the rest; \
         \"no data\" is the share of those pixels a technique left without a reflection. Each \
         technique is scored as a renderer shows it, its colour blended by its alpha over one \
         fallback that is the same for all: the scene's own colour at the pixel (so writing \
         nothing earns nothing). Quality \
         is measured at sizes up to {quality_max_pixels} pixels and marked `{SKIPPED}` beyond \
         (8K: FLIP on the CPU would dominate the run).\n"
    );
    if !outcome.notes.is_empty() {
        let _ = writeln!(md, "Notes:\n");
        for n in &outcome.notes {
            let _ = writeln!(md, "- {n}");
        }
        let _ = writeln!(md);
    }
    let mut ratios =
        MarkdownTable::new(&["scene", "size", "ratio", "technique", "#its ms", "#PPR ms", "#ratio"]);
    let ratio_res = pareto_resolution;
    for ((scene, res), list) in &aggs {
        if *res == ratio_res {
            ratio_rows(scene, *res, list, &mut ratios);
        }
    }
    if !ratios.is_empty() {
        let _ = writeln!(md, "## Cost against PPR at {ratio_res} (one run)\n");
        md.push_str(&ratios.render());
        let _ = writeln!(md);
    }
    let _ = writeln!(md, "## Pareto fronts (GPU time against on-screen PSNR)\n");
    let scenes: Vec<String> = {
        let mut v: Vec<String> = Vec::new();
        for r in &outcome.results {
            if !v.contains(&r.scene) {
                v.push(r.scene.clone());
            }
        }
        v
    };
    for scene in &scenes {
        let res = pick_pareto_resolution(&aggs, scene, pareto_resolution);
        let Some(list) = res.and_then(|r| aggs.get(&(scene.clone(), r))) else { continue };
        let res = res.unwrap_or(pareto_resolution);
        let pts: Vec<(f64, f64)> =
            list.iter().map(|a| (a.total_median, a.psnr_on.unwrap_or(f64::NAN))).collect();
        let mut front = pareto_front(&pts);
        front.sort_by(|&a, &b| pts[a].0.total_cmp(&pts[b].0));
        let names: Vec<String> = front.iter().map(|&i| list[i].technique.clone()).collect();
        let _ = writeln!(md, "- **{scene}** at {res}, fastest first: {}", names.join(" → "));
        let path = dir.join(format!("pareto_{}.png", file_stem(scene)));
        pareto_plot(&path, scene, res, list, &front)?;
        let _ = writeln!(
            md,
            "  ![{scene}]({})",
            path.file_name().map_or(String::new(), |n| n.to_string_lossy().into())
        );
        files.push(path);
    }
    let _ = writeln!(md);
    for ((scene, res), list) in &aggs {
        let _ = writeln!(md, "## {scene}, {res}\n");
        md.push_str(&scene_table(list));
        let _ = writeln!(md);
    }
    md.push_str(&causes_markdown(&outcome.causes));
    if !outcome.sheets.is_empty() {
        let path = dir.join("image_sheet.png");
        write_sheet(&path, &outcome.sheets)?;
        let _ = writeln!(
            md,
            "## Image sheet\n\n`image_sheet.png`: per scene (first camera), the crop with the most \
             on-screen reflector pixels; reflections on reflector pixels, reflector pixels without data in \
             magenta, the rest of the scene darkened.\n"
        );
        files.push(path);
    }
    let path = dir.join("comparison.md");
    std::fs::write(&path, md).map_err(|e| BenchError::io(&path, e))?;
    files.push(path);
    Ok(files)
}

/// `wanted` if that size was measured with quality on `scene`, else the largest that was.
fn pick_pareto_resolution(
    aggs: &BTreeMap<(String, Resolution), Vec<Aggregate>>,
    scene: &str,
    wanted: Resolution,
) -> Option<Resolution> {
    let has_quality = |r: &Resolution| {
        aggs.get(&(scene.to_string(), *r)).is_some_and(|l| l.iter().any(|a| a.psnr_on.is_some()))
    };
    if has_quality(&wanted) {
        return Some(wanted);
    }
    aggs.keys().filter(|(s, r)| s == scene && has_quality(r)).map(|(_, r)| *r).max()
}

fn file_stem(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' { c } else { '_' }).collect()
}

fn pareto_plot(
    path: &Path,
    scene: &str,
    res: Resolution,
    list: &[Aggregate],
    front: &[usize],
) -> Result<(), BenchError> {
    let finite_max = list.iter().filter_map(|a| a.psnr_on).filter(|v| v.is_finite()).fold(f64::MIN, f64::max);
    let ceiling = if finite_max > f64::MIN { finite_max + 5.0 } else { 40.0 };
    let mut by_family: BTreeMap<Family, Vec<PlotPoint>> = BTreeMap::new();
    for a in list {
        let Some(p) = a.psnr_on else { continue };
        let (y, label) = if p.is_infinite() {
            (ceiling, format!("{} (∞ dB)", a.technique))
        } else {
            (p, a.technique.clone())
        };
        by_family.entry(a.family.unwrap_or(Family::Ppr)).or_default().push(PlotPoint {
            x: a.total_median,
            y,
            label,
        });
    }
    let mut series: Vec<PlotSeries> = by_family
        .into_iter()
        .enumerate()
        .map(|(k, (family, points))| PlotSeries {
            name: family.as_str().into(),
            color: PALETTE[k % PALETTE.len()],
            points,
            line: false,
        })
        .collect();
    let mut front_pts: Vec<PlotPoint> = front
        .iter()
        .map(|&i| {
            let y = list[i].psnr_on.map_or(f64::NAN, |p| if p.is_infinite() { ceiling } else { p });
            PlotPoint { x: list[i].total_median, y, label: String::new() }
        })
        .collect();
    front_pts.sort_by(|a, b| a.x.total_cmp(&b.x));
    series.push(PlotSeries { name: "Pareto front".into(), color: PALETTE[7], points: front_pts, line: true });
    let spec = PlotSpec {
        title: format!("{scene} {res}: accuracy against GPU time"),
        x_label: "GPU ms (median, log scale)".into(),
        y_label: "PSNR on-screen reflector pixels (dB)".into(),
        log_x: true,
        log_y: false,
        size: (1100, 700),
    };
    write_plot(path, &spec, &series)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pareto_front_keeps_non_dominated_points() {
        // (time, accuracy): b dominates c; a is fastest; d is most accurate.
        let pts = [(0.1, 20.0), (0.5, 30.0), (0.6, 25.0), (5.0, f64::INFINITY), (1.0, f64::NAN)];
        assert_eq!(pareto_front(&pts), vec![0, 1, 3]);
    }
}
