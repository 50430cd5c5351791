//! `extract_trade.md`, `extract_trade.csv` and one plot per scene: rectangles against
//! coverage, with the run-time cost of each extraction setting.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::config::Resolution;
use crate::error::BenchError;
use crate::report::csv_file::{CsvTable, num};
use crate::report::markdown::{MarkdownTable, ms};
use crate::report::plot::{PALETTE, PlotPoint, PlotSeries, PlotSpec, write_plot};
use crate::suites::extract_trade::TradeRow;

/// Writes the report files under `dir`.
///
/// # Errors
/// A file cannot be written.
pub fn write_trade_report(
    dir: &Path,
    rows: &[TradeRow],
    notes: &[String],
    adapter: &str,
    res: Resolution,
    command: &str,
) -> Result<Vec<PathBuf>, BenchError> {
    std::fs::create_dir_all(dir).map_err(|e| BenchError::io(dir, e))?;
    let mut files = Vec::new();
    let mut csv = CsvTable::new(&[
        "scene",
        "setting",
        "split_min_gain",
        "max_shapes_per_region",
        "angle_tolerance_deg",
        "distance_tolerance_m",
        "rectangles",
        "coverage",
        "rect_area_m2",
        "visible_shapes",
        "projection_ms",
        "reflection_ms",
        "total_ms",
        "resolution",
        "adapter",
    ]);
    for r in rows {
        csv.push(vec![
            r.scene.clone(),
            r.setting.clone(),
            r.params.0.to_string(),
            r.params.1.to_string(),
            r.params.2.to_string(),
            r.params.3.to_string(),
            r.rectangles.to_string(),
            num(r.coverage, 4),
            num(r.rect_area, 4),
            num(r.visible, 1),
            num(r.projection_ms, 4),
            num(r.reflection_ms, 4),
            num(r.total_ms, 4),
            res.to_string(),
            adapter.into(),
        ]);
    }
    let path = dir.join("extract_trade.csv");
    csv.write(&path)?;
    files.push(path);

    let mut md = String::new();
    let _ = writeln!(md, "# The extractor's trade: rectangles against coverage, and their run-time cost\n");
    let _ = writeln!(md, "Machine: **{adapter}**, PPR at {res}.\n");
    let _ = writeln!(md, "Command:\n\n```sh\n{command}\n```\n");
    let _ = writeln!(
        md,
        "Per scene, each extraction setting's rectangle count and coverage (reflective area over \
         rectangle area, area-weighted: the share of the rectangles' area where a reflection is \
         wanted; the rest is where PPR projects for nothing and the occluder tests get looser), \
         and PPR's GPU time per frame with that set (median over the scene's cameras of each \
         camera's median). Split threshold: a non-convex region is split when every extra \
         rectangle saves at least this share of its parent's area; ≤ n: rectangles per region; \
         tolerances: angle (°) and distance (m) that make triangles one plane.\n"
    );
    for n in notes {
        let _ = writeln!(md, "- {n}");
    }
    let mut scenes: Vec<String> = Vec::new();
    for r in rows {
        if !scenes.contains(&r.scene) {
            scenes.push(r.scene.clone());
        }
    }
    for scene in &scenes {
        let list: Vec<&TradeRow> = rows.iter().filter(|r| &r.scene == scene).collect();
        let mut t = MarkdownTable::new(&[
            "setting",
            "#rectangles",
            "#coverage",
            "#rectangle area m²",
            "#visible",
            "#projection ms",
            "#reflection ms",
            "#frame ms",
        ]);
        for r in &list {
            t.push(vec![
                r.setting.clone(),
                r.rectangles.to_string(),
                format!("{:.1}%", r.coverage * 100.0),
                format!("{:.2}", r.rect_area),
                format!("{:.1}", r.visible),
                ms(r.projection_ms),
                ms(r.reflection_ms),
                ms(r.total_ms),
            ]);
        }
        let _ = writeln!(md, "\n## {scene}\n");
        md.push_str(&t.render());
        let file = format!(
            "extract_trade_{}.png",
            scene.replace(|c: char| !c.is_ascii_alphanumeric() && c != '-', "_")
        );
        let points: Vec<PlotPoint> = list
            .iter()
            .map(|r| PlotPoint {
                x: r.rectangles as f64,
                y: r.coverage * 100.0,
                label: format!("{} ({:.3} ms)", r.setting, r.projection_ms + r.reflection_ms),
            })
            .collect();
        let series = [PlotSeries {
            name: "extraction setting (projection + reflection ms)".into(),
            color: PALETTE[0],
            points,
            line: false,
        }];
        let spec = PlotSpec {
            title: format!("{scene}: rectangles against coverage (PPR at {res})"),
            x_label: "rectangles (log scale)".into(),
            y_label: "coverage, % of rectangle area".into(),
            log_x: true,
            log_y: false,
            size: (1100, 700),
        };
        let path = dir.join(&file);
        write_plot(&path, &spec, &series)?;
        let _ = writeln!(md, "\n![{scene}]({file})");
        files.push(path);
    }
    let path = dir.join("extract_trade.md");
    std::fs::write(&path, md).map_err(|e| BenchError::io(&path, e))?;
    files.push(path);
    Ok(files)
}
