//! `ppr-bench goals`: the thirty-fourth session's committed record (H100) judged as its
//! closing note judged it by hand, the thirty-seventh's as its report says, and the files the suites write today read back (a
//! quick `runtime` with the profile rows the goals read, on the software adapter).

use std::path::PathBuf;

use ppr_bench::goals::bench_rows::{CompareRow, RuntimeRow, read_rows};
use ppr_bench::goals::checks::{Check, Goal};
use ppr_bench::goals::{GoalFiles, GoalJudgement, judge_files};

fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn perf(name: &str) -> PathBuf {
    repo_root().join("docs/perf").join(name)
}

/// The judgement's check of `goal` for `subject`; panics with every check where there is none.
fn check_of<'a>(judgement: &'a GoalJudgement, goal: Goal, subject: &str) -> &'a Check {
    judgement
        .checks
        .iter()
        .find(|c| c.goal == goal && c.subject == subject)
        .unwrap_or_else(|| panic!("no {goal:?} check of {subject}: {:#?}", judgement.checks))
}

#[test]
fn the_thirty_fourth_session_s_record_is_judged_as_its_note_says() {
    let out = tempfile::tempdir().expect("temp dir");
    let report = out.path().join("goals.md");
    let s = |p: PathBuf| p.display().to_string();
    let args = [
        "ppr-bench".to_string(),
        "goals".into(),
        "--runtime".into(),
        s(perf("runtime_34_h100_blockers.csv")),
        "--compare".into(),
        s(perf("comparison_34_h100_blockers.csv")),
        "--compare".into(),
        s(perf("comparison_collision_34_h100_blockers.csv")),
        "--baseline-compare".into(),
        s(perf("comparison_34_h100.csv")),
        "--out".into(),
        s(report.clone()),
    ];
    let files = ppr_bench::cli::run_cli(args).expect("goals judges the committed files");
    assert_eq!(files, vec![report.clone()]);
    let written = std::fs::read_to_string(&report).expect("report");

    let judgement = judge_files(&GoalFiles {
        runtime: vec![perf("runtime_34_h100_blockers.csv")],
        compare: vec![
            perf("comparison_34_h100_blockers.csv"),
            perf("comparison_collision_34_h100_blockers.csv"),
        ],
        baseline: Some(perf("comparison_34_h100.csv")),
        psnr_tolerance_db: 0.02,
    })
    .expect("judged");
    assert_eq!(written, judgement.markdown);
    let check = |goal: Goal, subject: &str| check_of(&judgement, goal, subject);
    // The note: whole frames 0.257 / 0.315 / 0.221 and 0.120 (met) / 0.295 / 0.179.
    let mirror = check(Goal::Frame4k, "demo cam_mirror 4K");
    assert!((mirror.value - 0.3151).abs() < 1e-9 && !mirror.met);
    assert!(check(Goal::Frame4k, "kitchen overview 4K").met);
    assert_eq!(judgement.checks.iter().filter(|c| c.goal == Goal::Frame4k).count(), 6);
    // Full PPR against ssr-low by passes: 1.19x / 1.65x (demo), 0.88x (met) / 1.37x.
    for (subject, ratio, met) in [
        ("demo 4K, passes", 1.19, false),
        ("demo 1080p, passes", 1.65, false),
        ("kitchen 4K, passes", 0.88, true),
        ("kitchen 1080p, passes", 1.37, false),
        ("kitchen 4K, whole frames", 0.88, true),
    ] {
        let c = check(Goal::CompareCost, subject);
        assert!((c.value - ratio).abs() < 0.005 && c.met == met, "{c:?}");
    }
    // PSNR within 0.02 dB of the frames without the blockers.
    assert!(
        judgement
            .checks
            .iter()
            .filter(|c| c.goal == Goal::ComparePsnr)
            .all(|c| c.met && c.value.abs() < 0.02)
    );
    // The stairway 0.455 above its 1-tread frame (missed), the rooms 0.232 (met), 10 000
    // treads 1.46 ms (met).
    let stairway = check(Goal::Scaling1000, "stairway");
    assert!((stairway.value - 0.4551).abs() < 1e-6 && !stairway.met, "{stairway:?}");
    assert!(check(Goal::Scaling1000, "rooms").met);
    assert!(check(Goal::Scaling10000, "stairway").met);
    assert!(judgement.checks.iter().filter(|c| c.goal == Goal::CollisionWorld).all(|c| c.met));
    // The projection's floor rows were not in that call: the report says so.
    assert!(written.contains("Not measured: no rows for it in these files."), "{written}");
    assert!(written.contains("| stairway | 0.4551 ms | missed |"), "{written}");
}

/// The thirty-seventh session's record (H100, binary ff8a48a), the final run, as
/// `docs/perf/goals_37_h100.md` and `runtime.md` state it: 19 of 38 checks met, the
/// projection's floor measured this time (missed on all six cameras), the stairway's 1 000
/// and 10 000 treads missed.
#[test]
fn the_thirty_seventh_session_s_record_is_judged_as_its_report_says() {
    let judgement = judge_files(&GoalFiles {
        runtime: vec![perf("runtime_37_h100.csv"), perf("runtime_37_h100_generated.csv")],
        compare: vec![perf("comparison_37_h100.csv"), perf("comparison_collision_37_h100.csv")],
        baseline: Some(perf("comparison_29_h200.csv")),
        psnr_tolerance_db: 0.02,
    })
    .expect("judged");
    let met = judgement.checks.iter().filter(|c| c.met).count();
    assert_eq!((met, judgement.checks.len()), (19, 38), "{}", judgement.markdown);
    let committed = std::fs::read_to_string(perf("goals_37_h100.md")).expect("the committed report");
    assert!(committed.contains("**19 of 38 checks met.**"), "{committed}");
    let check = |goal: Goal, subject: &str| check_of(&judgement, goal, subject);
    let floor: Vec<_> = judgement.checks.iter().filter(|c| c.goal == Goal::ProjectionFloor).collect();
    assert_eq!(floor.len(), 6);
    assert!(floor.iter().all(|c| !c.met && c.value > 6.0), "{floor:#?}");
    let stairway = check(Goal::Scaling1000, "stairway");
    assert!((stairway.value - 0.3641).abs() < 1e-6 && !stairway.met, "{stairway:?}");
    let deep = check(Goal::Scaling10000, "stairway");
    assert!((deep.value - 2.2197).abs() < 1e-6 && !deep.met, "{deep:?}");
    assert!(check(Goal::CompareCost, "kitchen 4K, passes").met);
    assert!(!check(Goal::CompareCost, "demo 1080p, passes").met);
    assert!(judgement.checks.iter().filter(|c| c.goal == Goal::CollisionWorld).all(|c| c.met));
}

#[test]
fn goals_without_files_or_with_a_missing_file_say_what_is_wrong() {
    let err = ppr_bench::cli::run_cli(["ppr-bench", "goals"]).unwrap_err().to_string();
    assert!(err.contains("--runtime or --compare"), "{err}");
    let missing = repo_root().join("docs/perf/no_such_run.csv");
    let err =
        judge_files(&GoalFiles { compare: vec![missing], ..GoalFiles::default() }).unwrap_err().to_string();
    assert!(err.contains("no_such_run.csv"), "{err}");
}

/// The suites' CSV files of today read back: a quick `runtime` with the two profile rows
/// the goals read, and a quick `compare` with PPR and ssr-low as passes and whole frames.
#[test]
fn the_files_the_suites_write_read_back() {
    let out = tempfile::tempdir().expect("temp dir");
    let root = repo_root().display().to_string();
    let dir = |name: &str| out.path().join(name).display().to_string();
    let runtime: Vec<String> = [
        "ppr-bench",
        "runtime",
        "--quick",
        "--projection-profile",
        "--profile-row",
        "frame span",
        "--profile-row",
        "reflection own pass",
        "--out",
    ]
    .iter()
    .map(|s| (*s).to_string())
    .chain([dir("runtime"), "--repo-root".into(), root.clone()])
    .collect();
    ppr_bench::cli::run_cli(runtime).expect("quick runtime runs");
    let rows: Vec<RuntimeRow> =
        read_rows(&out.path().join("runtime/runtime.csv")).expect("runtime.csv reads");
    let row = |label: &str, pass: &str| {
        rows.iter().any(|r| r.scene_and_row() == ("demo", Some(label)) && r.pass == pass)
    };
    assert!(row("frame span", "frame") && row("reflection own pass", "projection"), "{rows:#?}");
    assert!(
        rows.iter().any(|r| r.scene == "demo"
            && r.pass == "projection + reflection"
            && r.ratio_to_floor.is_finite())
    );

    let compare: Vec<String> =
        ["ppr-bench", "compare", "--quick", "--technique", "ppr", "--technique", "ssr-low", "--out"]
            .iter()
            .map(|s| (*s).to_string())
            .chain([dir("compare"), "--repo-root".into(), root])
            .collect();
    ppr_bench::cli::run_cli(compare).expect("quick compare runs");
    let rows: Vec<CompareRow> =
        read_rows(&out.path().join("compare/comparison.csv")).expect("comparison.csv reads");
    for technique in ["ppr", "ssr-low"] {
        let r = rows
            .iter()
            .find(|r| r.technique == technique)
            .unwrap_or_else(|| panic!("no {technique}: {rows:#?}"));
        assert!(r.psnr_on_screen_db.is_finite() || r.psnr_on_screen_db.is_nan(), "{r:?}");
    }
    // The quick size is not 4K: the judgement measures the compare goal only, at that size.
    let judged = judge_files(&GoalFiles {
        runtime: vec![out.path().join("runtime")],
        compare: vec![out.path().join("compare")],
        ..GoalFiles::default()
    })
    .expect("judged");
    assert!(judged.checks.iter().all(|c| c.goal == Goal::CompareCost), "{:#?}", judged.checks);
    assert!(judged.markdown.contains("## A whole PPR frame at 4K"), "{}", judged.markdown);
}
