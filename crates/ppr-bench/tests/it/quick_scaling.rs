//! `ppr-bench scaling --quick` on the generated levels at 64×36: the report has every
//! culling variant (none, flat tile lists, super-tile lists) for every family and count,
//! each with a measured total, and the threshold lines.

use std::path::PathBuf;

use ppr_bench::report::csv_file::split_line;

#[test]
fn quick_scaling_reports_every_culling_variant() {
    let out = tempfile::tempdir().expect("temp dir");
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let args = [
        "ppr-bench".to_string(),
        "scaling".into(),
        "--quick".into(),
        "--out".into(),
        out.path().display().to_string(),
        "--repo-root".into(),
        root.display().to_string(),
    ];
    ppr_bench::cli::run_cli(args).expect("quick scaling runs");
    let csv = std::fs::read_to_string(out.path().join("scaling.csv")).expect("csv");
    let mut lines = csv.lines();
    let header = split_line(lines.next().expect("header"));
    let col = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("{name}"));
    let rows: Vec<Vec<String>> = lines.map(split_line).collect();
    for family in ["stairway", "tiled-floor", "facade"] {
        for variant in ["culling off", "culling on", "super-tiles"] {
            for shapes in ["1", "10"] {
                let row = rows
                    .iter()
                    .find(|r| {
                        r[col("sweep")] == "scaling"
                            && r[col("family")] == family
                            && r[col("variant")] == variant
                            && r[col("shapes")] == shapes
                            && r[col("pass")] == "projection"
                    })
                    .unwrap_or_else(|| panic!("no {family} {variant} {shapes} projection row"));
                let ms: f64 = row[col("median_ms")].parse().expect("a number");
                assert!(ms.is_finite() && ms >= 0.0, "{row:?}");
                let passes = &row[col("passes")];
                let tiled = passes.contains("projection (tiled)");
                let super_tiled = passes.contains("projection (super-tiles, tiled)");
                match variant {
                    "culling off" => assert!(!tiled && !super_tiled, "{passes}"),
                    "culling on" => assert!(tiled, "{passes}"),
                    _ => assert!(super_tiled, "{passes}"),
                }
            }
        }
    }
    let md = std::fs::read_to_string(out.path().join("scaling.md")).expect("markdown");
    assert!(md.contains("super: overhead") && md.contains("super-tiles never slower"), "{md}");
    assert!(out.path().join("scaling.png").is_file());
}
