//! The profile rows that take a frame apart, run on the software adapter: the ablation
//! without the atomic writes nothing while the real pass writes, and `runtime.md` gets the
//! table of each pass timed on its own.

use std::path::PathBuf;

fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `written_pixels` of the rows of `runtime.csv` whose scene label is `label` exactly.
fn written(csv: &str, label: &str) -> Vec<u64> {
    let header: Vec<&str> = csv.lines().next().expect("a header").split(',').collect();
    let col = header.iter().position(|h| *h == "written_pixels").expect("written_pixels");
    csv.lines()
        .skip(1)
        .filter(|l| l.starts_with(&format!("{label},")))
        .map(|l| l.split(',').nth(col).expect("the column").parse().expect("a count"))
        .collect()
}

#[test]
fn the_frame_parts_rows_run_and_the_atomic_free_projection_writes_nothing() {
    let out = tempfile::tempdir().expect("temp dir");
    let args: Vec<String> = ["ppr-bench", "runtime", "--quick", "--projection-profile"]
        .into_iter()
        .map(String::from)
        .chain(
            [
                "no atomic",
                "no atomic, reflection own pass",
                "empty, reflection own pass",
                "reflection own pass",
            ]
            .into_iter()
            .flat_map(|r| ["--profile-row".to_owned(), r.to_owned()]),
        )
        .chain(["--out".into(), out.path().display().to_string()])
        .chain(["--repo-root".into(), repo_root().display().to_string()])
        .collect();
    ppr_bench::cli::run_cli(args).expect("quick runtime runs");
    let csv = std::fs::read_to_string(out.path().join("runtime.csv")).expect("runtime.csv");
    let default = written(&csv, "demo");
    assert!(!default.is_empty() && default.iter().all(|&n| n > 0), "the real pass writes: {csv}");
    let ablated = written(&csv, "demo [no atomic]");
    assert!(!ablated.is_empty() && ablated.iter().all(|&n| n == 0), "no atomic, no write: {csv}");
    let md = std::fs::read_to_string(out.path().join("runtime.md")).expect("runtime.md");
    let line = md
        .lines()
        .find(|l| l.starts_with("| demo | `") && l.contains("64x36"))
        .unwrap_or_else(|| panic!("no frame-parts line: {md}"));
    let cells: Vec<&str> = line.split('|').map(str::trim).filter(|c| !c.is_empty()).collect();
    // projection: empty, no atomic, default; reflection: nothing written, default; fixed.
    for c in [6, 9, 10, 12, 16, 17] {
        assert!(cells[c].parse::<f64>().is_ok_and(|v| v > 0.0), "column {c} of {line}");
    }
}
