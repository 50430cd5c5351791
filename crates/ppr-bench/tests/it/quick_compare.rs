//! `ppr-bench compare --quick` on the demo level at 64×36: every file is written and the
//! CSV has every column of every row filled.

use std::path::PathBuf;

use ppr_bench::report::compare_report::RESULT_COLUMNS;
use ppr_bench::report::csv_file::split_line;

fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn quick_compare_writes_a_full_csv_a_table_and_a_plot() {
    let out = tempfile::tempdir().expect("temp dir");
    let root = repo_root();
    let args = [
        "ppr-bench".to_string(),
        "compare".into(),
        "--quick".into(),
        "--out".into(),
        out.path().display().to_string(),
        "--repo-root".into(),
        root.display().to_string(),
        "--scenes-dir".into(),
        root.join("../shared/scenes").display().to_string(),
    ];
    let files = ppr_bench::cli::run_cli(args).expect("quick bench runs");
    for name in [
        "comparison.csv",
        "comparison_passes.csv",
        "comparison_causes.csv",
        "comparison.md",
        "pareto_demo.png",
        "image_sheet.png",
    ] {
        let path = out.path().join(name);
        assert!(path.is_file(), "{name} missing (wrote {files:?})");
        assert!(std::fs::metadata(&path).expect("metadata").len() > 0, "{name} is empty");
    }

    let csv = std::fs::read_to_string(out.path().join("comparison.csv")).expect("csv");
    let mut lines = csv.lines();
    let header = split_line(lines.next().expect("header"));
    assert_eq!(header, RESULT_COLUMNS);
    let rows: Vec<Vec<String>> = lines.map(split_line).collect();
    // One camera, one size: one row per technique (4 PPR settings, exact, baselines).
    assert!(rows.len() >= 5, "{} rows", rows.len());
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), header.len(), "row {i} has {} fields", row.len());
        for (name, value) in header.iter().zip(row) {
            assert!(!value.trim().is_empty(), "row {i} ({}): column {name} is empty", row[4]);
            assert_ne!(value, "nan", "row {i} ({}): column {name} is NaN", row[4]);
        }
    }
    let techniques: Vec<&str> = rows.iter().map(|r| r[4].as_str()).collect();
    for t in ["ppr-raw", "ppr-holes", "ppr-filter", "ppr", "exact"] {
        assert!(techniques.contains(&t), "{t} missing from {techniques:?}");
    }
    // At 64x36 every run measured quality; PPR finds reflections on the mirror camera.
    let ppr = rows.iter().find(|r| r[4] == "ppr").expect("ppr row");
    assert_eq!(ppr[12], "measured");
    let holes: f64 = ppr[17].parse().expect("number");
    assert!(holes < 0.5, "PPR left {holes} of the on-screen pixels without data");

    let md = std::fs::read_to_string(out.path().join("comparison.md")).expect("markdown");
    assert!(md.contains("| technique |") && md.contains("## demo, 64x36"), "{md}");
}

#[test]
fn timing_frame_times_ppr_and_ssr_as_whole_frames_where_the_adapter_can() {
    let out = tempfile::tempdir().expect("temp dir");
    let root = repo_root();
    let args: Vec<String> = [
        "ppr-bench",
        "compare",
        "--quick",
        "--technique",
        "ppr:timing=frame",
        "--technique",
        "ssr-low:timing=frame",
        "--technique",
        "ssr-low",
        "--out",
    ]
    .iter()
    .map(|s| (*s).to_string())
    .chain([
        out.path().display().to_string(),
        "--repo-root".into(),
        root.display().to_string(),
        "--scenes-dir".into(),
        root.join("../shared/scenes").display().to_string(),
    ])
    .collect();
    ppr_bench::cli::run_cli(args).expect("quick bench runs");
    let csv = std::fs::read_to_string(out.path().join("comparison.csv")).expect("csv");
    let mut lines = csv.lines();
    let header = split_line(lines.next().expect("header"));
    let col = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("{name}"));
    let rows: Vec<Vec<String>> = lines.map(split_line).collect();
    let passes = |technique: &str| {
        rows.iter().find(|r| r[col("technique")] == technique).unwrap_or_else(|| panic!("no {technique} row"))
            [col("passes_median_ms")]
        .clone()
    };
    let gpu = ppr_testbed::GpuContext::new_headless().expect("a wgpu adapter (llvmpipe without a GPU)");
    let spans = gpu.device.features().contains(wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS);
    for technique in ["ppr timing=frame", "ssr-low timing=frame"] {
        let p = passes(technique);
        eprintln!("{technique}: {p} (encoder timestamps: {spans})");
        // A whole frame's one span where the adapter writes timestamps between passes
        // (llvmpipe's GL timers may leave a run without times: then no pass at all).
        assert!(p.is_empty() || p.starts_with("frame=") && !p.contains(';'), "{technique}: {p}");
        if !spans {
            assert!(p.is_empty(), "{technique}: no encoder timestamps, no span: {p}");
        }
    }
    assert!(passes("ssr-low").starts_with("ssr march="), "{}", passes("ssr-low"));
}
