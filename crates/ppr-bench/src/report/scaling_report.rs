//! `scaling.md`, `scaling.csv` and `scaling.png`: cost against shape count without tile
//! culling, with flat tile lists and with super-tile lists, and the plan's thresholds.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::error::BenchError;
use crate::report::csv_file::{CsvTable, num};
use crate::report::markdown::{MarkdownTable, ms};
use crate::report::plot::{PALETTE, PlotPoint, PlotSeries, PlotSpec, write_plot};
use crate::suites::scaling::{
    CULLING_OFF, CULLING_ON, NO_SUBGROUPS, PARALLEL_TREES, PLANE_GROUPS, SUBGROUPS_ON, SUPER_TILES,
    ScalingOutcome, ScalingRow, TREES_NO_INDEX, crossover, indirect_crossover,
};

/// The culling variants, in table and plot order.
const VARIANTS: [&str; 8] = [
    CULLING_OFF,
    CULLING_ON,
    SUPER_TILES,
    PLANE_GROUPS,
    PARALLEL_TREES,
    TREES_NO_INDEX,
    NO_SUBGROUPS,
    SUBGROUPS_ON,
];

fn csv_rows(csv: &mut CsvTable, sweep: &str, rows: &[ScalingRow], adapter: &str, res: &str) {
    for r in rows {
        for (pass, s) in r.timings.passes() {
            csv.push(vec![
                sweep.into(),
                r.family.clone(),
                r.shapes.to_string(),
                r.variant.clone(),
                r.visible.to_string(),
                format!("{:.4}", r.coverage),
                r.passes.clone(),
                pass,
                num(s.median, 4),
                num(s.p95, 4),
                s.count.to_string(),
                r.source.as_str().into(),
                res.into(),
                adapter.into(),
            ]);
        }
    }
}

fn find<'a>(rows: &'a [ScalingRow], family: &str, n: usize, variant: &str) -> Option<&'a ScalingRow> {
    rows.iter().find(|r| r.family == family && r.shapes == n && r.variant == variant)
}

/// Writes the report files under `dir`.
///
/// # Errors
/// A file cannot be written.
pub fn write_scaling_report(
    dir: &Path,
    o: &ScalingOutcome,
    command: &str,
) -> Result<Vec<PathBuf>, BenchError> {
    std::fs::create_dir_all(dir).map_err(|e| BenchError::io(dir, e))?;
    let res = o.resolution.to_string();
    let mut csv = CsvTable::new(&[
        "sweep",
        "family",
        "shapes",
        "variant",
        "visible",
        "coverage",
        "passes",
        "pass",
        "median_ms",
        "p95_ms",
        "frames",
        "timing_source",
        "resolution",
        "adapter",
    ]);
    csv_rows(&mut csv, "scaling", &o.rows, &o.adapter, &res);
    csv_rows(&mut csv, "culling-threshold", &o.threshold_rows, &o.adapter, &res);
    csv_rows(&mut csv, "indirect-threshold", &o.coverage_rows, &o.adapter, &res);
    let csv_path = dir.join("scaling.csv");
    csv.write(&csv_path)?;

    let mut md = String::new();
    let _ = writeln!(md, "# Scaling: GPU time against shape count\n");
    let _ = writeln!(md, "Machine: **{}**, {res}.\n", o.adapter);
    let _ = writeln!(md, "Command:\n\n```sh\n{command}\n```\n");
    let _ = writeln!(
        md,
        "Generated levels (`ppr-bench`'s `scaling::level_family`): a stairway of mirror treads \
         (6 m wide, 6 m rise over a 12 m run, occluders: treads above within 3 step depths), \
         puddles on a 16 m × 16 m tiled floor (one per tile, 50–90 % of it, one plane), \
         windows on a 20 m × 16 m facade (one plane) and rooms and corridors on a 3D grid, \
         each turned its own way, every panel a mirror on both faces (`room_maze`); the \
         overall extent is fixed, so the \
         reflecting screen area stays about the same while the count grows. Times are \
         medians of GPU timestamps, the faster of two rounds over the variants of a level, the second in reverse order (PPR with every reflection step on); `overhead` is the \
         frame's total minus the same family's total with one shape.\n"
    );
    let mut families: Vec<String> = Vec::new();
    for r in &o.rows {
        if !families.contains(&r.family) {
            families.push(r.family.clone());
        }
    }
    let mut counts: Vec<usize> = o.rows.iter().map(|r| r.shapes).collect();
    counts.sort_unstable();
    counts.dedup();
    let mut t = MarkdownTable::new(&[
        "family",
        "#shapes",
        "#visible",
        "#off: projection",
        "#off: total",
        "#on: projection",
        "#on: total",
        "#super: projection",
        "#super: total",
        "#groups: tests",
        "#groups: projection",
        "#groups: total",
        "#trees: tests",
        "#trees: projection",
        "#trees: total",
        "#no subgroups: total",
        "#on: overhead",
        "#super: overhead",
        "#groups: overhead",
        "#trees: overhead",
        "#best: overhead",
    ]);
    let first = counts.first().copied().unwrap_or(1);
    // The fastest variant's total at a count.
    let best = |f: &str, n: usize| {
        VARIANTS
            .iter()
            .filter_map(|v| find(&o.rows, f, n, v))
            .map(ScalingRow::total_ms)
            .fold(f64::NAN, f64::min)
    };
    for f in &families {
        let base = |v: &str| find(&o.rows, f, first, v).map_or(f64::NAN, ScalingRow::total_ms);
        for &n in &counts {
            let (Some(off), Some(on)) = (find(&o.rows, f, n, CULLING_OFF), find(&o.rows, f, n, CULLING_ON))
            else {
                continue;
            };
            let sup = find(&o.rows, f, n, SUPER_TILES);
            let sup_ms = |get: fn(&ScalingRow) -> f64| sup.map_or(f64::NAN, get);
            let grp = find(&o.rows, f, n, PLANE_GROUPS);
            let grp_ms = |get: fn(&ScalingRow) -> f64| grp.map_or(f64::NAN, get);
            let tree = find(&o.rows, f, n, PARALLEL_TREES);
            let tree_ms = |get: fn(&ScalingRow) -> f64| tree.map_or(f64::NAN, get);
            t.push(vec![
                f.clone(),
                n.to_string(),
                on.visible.to_string(),
                ms(off.pass_ms("projection")),
                ms(off.total_ms()),
                ms(on.pass_ms("projection")),
                ms(on.total_ms()),
                ms(sup_ms(|r| r.pass_ms("projection"))),
                ms(sup_ms(ScalingRow::total_ms)),
                grp.map_or("–".into(), |r| r.tested.to_string()),
                ms(grp_ms(|r| r.pass_ms("projection"))),
                ms(grp_ms(ScalingRow::total_ms)),
                tree.map_or("–".into(), |r| r.tested.to_string()),
                ms(tree_ms(|r| r.pass_ms("projection"))),
                ms(tree_ms(ScalingRow::total_ms)),
                ms(find(&o.rows, f, n, NO_SUBGROUPS).map_or(f64::NAN, ScalingRow::total_ms)),
                ms(on.total_ms() - base(CULLING_ON)),
                ms(sup_ms(ScalingRow::total_ms) - base(SUPER_TILES)),
                ms(grp_ms(ScalingRow::total_ms) - base(PLANE_GROUPS)),
                ms(tree_ms(ScalingRow::total_ms) - base(PARALLEL_TREES)),
                ms(best(f, n) - best(f, first)),
            ]);
        }
    }
    let _ = writeln!(md, "## Per pass against shape count (ms)\n");
    md.push_str(&t.render());
    let _ = writeln!(
        md,
        "\n(`off`, `on`, `super`: every visible shape tested alone; `on`: tile lists built \
         from every visible shape; `super`: from 64 × 64-pixel super-tile lists, whose pass \
         is timed inside the projection; `groups`: coplanar shapes merged into plane groups \
         (`tests`: the projection's tests per pixel loop), culling as the plan picks it; \
         `trees`: parallel families walked as trees, plane groups and culling as the plan \
         picks them; every variant with the projection's subgroup culling where the device \
         has subgroups, but `no subgroups`: the plan's own choices without it.)\n\n\
         Growth of the total between successive counts, as the exponent k of time ∝ shapesᵏ:\n"
    );
    for f in &families {
        for v in [CULLING_ON, SUPER_TILES, PLANE_GROUPS, PARALLEL_TREES] {
            let mut parts = Vec::new();
            for w in counts.windows(2) {
                if let (Some(a), Some(b)) = (find(&o.rows, f, w[0], v), find(&o.rows, f, w[1], v)) {
                    let k = (b.total_ms() / a.total_ms()).ln() / (w[1] as f64 / w[0] as f64).ln();
                    parts.push(format!("{}→{}: {k:.2}", w[0], w[1]));
                }
            }
            let _ = writeln!(md, "- {f}, {v}: {}", parts.join(", "));
        }
    }
    let _ = writeln!(md, "\nEvery pass of every row is in `scaling.csv`.\n");

    let mut t = MarkdownTable::new(&[
        "family",
        "#shapes",
        "#culling off: total ms",
        "#culling on: total ms",
        "#super-tiles: total ms",
        "#plane groups: total ms",
        "#parallel trees: total ms",
        "#no subgroup culling: total ms",
        "#subgroup culling on: total ms",
        "fastest",
    ]);
    let mut tcounts: Vec<usize> = o.threshold_rows.iter().map(|r| r.shapes).collect();
    tcounts.sort_unstable();
    tcounts.dedup();
    for f in &families {
        for &n in &tcounts {
            let rows: Vec<Option<&ScalingRow>> =
                VARIANTS.iter().map(|v| find(&o.threshold_rows, f, n, v)).collect();
            if rows[0].is_none() || rows[1].is_none() {
                continue;
            }
            let fastest = VARIANTS
                .iter()
                .zip(&rows)
                .filter_map(|(v, r)| r.map(|r| (*v, r.total_ms())))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map_or("—", |(v, _)| v);
            let mut row = vec![f.clone(), n.to_string()];
            row.extend(rows.iter().map(|r| ms(r.map_or(f64::NAN, ScalingRow::total_ms))));
            row.push(fastest.into());
            t.push(row);
        }
    }
    let _ = writeln!(
        md,
        "## Culling thresholds (`PlanParams::tile_culling_min_shapes`, `super_tiles_min_shapes`, \
         `plane_group_min_shapes`, `parallel_tree_min_shapes`)\n"
    );
    md.push_str(&t.render());
    for f in &families {
        let never = || "— (never)".to_string();
        let c = crossover(&o.threshold_rows, f, CULLING_ON, CULLING_OFF);
        let s = crossover(&o.threshold_rows, f, SUPER_TILES, CULLING_ON);
        let g = crossover(&o.threshold_rows, f, PLANE_GROUPS, CULLING_OFF);
        let p = crossover(&o.threshold_rows, f, PARALLEL_TREES, PLANE_GROUPS);
        let _ = writeln!(
            md,
            "- {f}: culling is never slower than none from {} shapes on; super-tiles never slower \
             than flat tile lists from {} shapes on; plane groups never slower than every shape \
             alone without culling from {} shapes on; parallel trees never slower than the plan \
             without them from {} shapes on",
            c.map_or_else(never, |n| n.to_string()),
            s.map_or_else(never, |n| n.to_string()),
            g.map_or_else(never, |n| n.to_string()),
            p.map_or_else(never, |n| n.to_string())
        );
    }
    let _ = writeln!(md, "\n## Indirect-dispatch threshold (`PlanParams::indirect_max_coverage`)\n");
    let _ = writeln!(
        md,
        "One floor mirror seen from straight above, sized so that its screen rectangle covers the \
         given share of the screen; classify + clear + reflection (+ projection, the same in both) \
         with indirect dispatch forced off and on (with it on, the classification clears the \
         active tiles: no clear pass unless the frame has layers).\n"
    );
    let mut t = MarkdownTable::new(&[
        "#coverage",
        "#off: total ms",
        "#on: total ms",
        "#on: classify",
        "#on: clear",
        "#on: reflection",
        "#off: clear",
        "#off: reflection",
        "faster",
    ]);
    let mut covs: Vec<f32> = o.coverage_rows.iter().map(|r| r.coverage).collect();
    covs.sort_by(f32::total_cmp);
    covs.dedup();
    for c in covs {
        let get = |v: &str| o.coverage_rows.iter().find(|r| r.coverage == c && r.variant == v);
        let (Some(off), Some(on)) = (get("indirect off"), get("indirect on")) else { continue };
        t.push(vec![
            format!("{c:.3}"),
            ms(off.total_ms()),
            ms(on.total_ms()),
            ms(on.pass_ms("classify")),
            ms(on.pass_ms("clear")),
            ms(on.pass_ms("reflection")),
            ms(off.pass_ms("clear")),
            ms(off.pass_ms("reflection")),
            if on.total_ms() <= off.total_ms() { "on".into() } else { "off".into() },
        ]);
    }
    md.push_str(&t.render());
    let _ = writeln!(
        md,
        "- indirect dispatch is never slower up to a coverage of {}\n- the plan's limit at {} \
         (`PlanParams::indirect_coverage_limit`): {:.3}\n",
        indirect_crossover(&o.coverage_rows).map_or("— (never)".into(), |c| format!("{c:.3}")),
        o.resolution,
        ppr_runtime::PlanParams::default()
            .indirect_coverage_limit(u64::from(o.resolution.width) * u64::from(o.resolution.height))
    );

    let plot_path = dir.join("scaling.png");
    let mut series = Vec::new();
    for (k, f) in families.iter().enumerate() {
        for (j, v) in VARIANTS.iter().enumerate() {
            let points: Vec<PlotPoint> = counts
                .iter()
                .filter_map(|&n| find(&o.rows, f, n, v))
                .map(|r| PlotPoint { x: r.shapes as f64, y: r.total_ms(), label: String::new() })
                .collect();
            series.push(PlotSeries {
                name: format!("{f}, {v}"),
                color: PALETTE[(VARIANTS.len() * k + j) % PALETTE.len()],
                points,
                line: true,
            });
        }
    }
    let spec = PlotSpec {
        title: format!("PPR frame GPU time against shape count, {res}"),
        x_label: "reflectors (log scale)".into(),
        y_label: "GPU ms, all passes (median, log scale)".into(),
        log_x: true,
        log_y: true,
        size: (1100, 700),
    };
    write_plot(&plot_path, &spec, &series)?;
    let _ = writeln!(md, "![scaling](scaling.png)\n");
    let md_path = dir.join("scaling.md");
    std::fs::write(&md_path, md).map_err(|e| BenchError::io(&md_path, e))?;
    Ok(vec![md_path, csv_path, plot_path])
}
