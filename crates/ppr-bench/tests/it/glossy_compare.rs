//! `ppr-bench compare --quick` with the glossy reference: PPR with and without its glossy
//! blur, ssr-low and ssr-glossy side by side on the demo level at 64×36, every row scored.

use std::path::PathBuf;

use ppr_bench::report::csv_file::split_line;

fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn quick_compare_scores_ssr_glossy_against_the_glossy_reference() {
    let out = tempfile::tempdir().expect("temp dir");
    let root = repo_root();
    let mut args: Vec<String> =
        ["ppr-bench", "compare", "--quick", "--reference", "glossy", "--glossy-samples", "16"]
            .map(String::from)
            .to_vec();
    for t in ["ppr", "ppr:glossy=off", "ppr:glossy-taps=2", "ssr-low", "ssr-glossy", "exact"] {
        args.extend(["--technique".to_string(), t.to_string()]);
    }
    args.extend([
        "--out".into(),
        out.path().display().to_string(),
        "--repo-root".into(),
        root.display().to_string(),
        "--scenes-dir".into(),
        root.join("../shared/scenes").display().to_string(),
    ]);
    ppr_bench::cli::run_cli(args).expect("quick glossy bench runs");

    let csv = std::fs::read_to_string(out.path().join("comparison.csv")).expect("csv");
    let rows: Vec<Vec<String>> = csv.lines().skip(1).map(split_line).collect();
    let techniques: Vec<&str> = rows.iter().map(|r| r[4].as_str()).collect();
    assert_eq!(techniques, ["ppr", "ppr glossy=off", "ppr glossy-taps=2", "ssr-low", "ssr-glossy", "exact"]);
    for row in &rows {
        assert_eq!(row[12], "measured", "{}: quality not measured", row[4]);
    }
    // `glossy-taps=` reaches the renderer: two taps a pixel blur otherwise than twelve.
    let psnr = |t: &str| rows.iter().find(|r| r[4] == t).map(|r| r[13].clone()).expect("row");
    eprintln!("on-screen PSNR: ppr {}, two taps {}", psnr("ppr"), psnr("ppr glossy-taps=2"));
    assert_ne!(psnr("ppr"), psnr("ppr glossy-taps=2"));
    // The demo's brushed metal (0.3) and rough water (0.15) make it a glossy scene.
    let md = std::fs::read_to_string(out.path().join("comparison.md")).expect("markdown");
    assert!(md.contains("scored against the exact glossy reference"), "{md}");
    assert!(md.contains("effective sample size mean"), "{md}");
}

#[test]
fn the_reference_flag_takes_mirror_or_glossy_only() {
    let err = ppr_bench::cli::run_cli(["ppr-bench", "compare", "--quick", "--reference", "blurry"])
        .expect_err("an unknown reference is refused");
    assert!(err.to_string().contains("blurry"), "{err}");
}
