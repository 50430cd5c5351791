//! The binary itself: `--headless --frames N --screenshot out.png --camera ...`.

use std::path::Path;
use std::process::{Command, Output};

use crate::common::{asset, demo_set_file, gpu_lock};

#[test]
fn headless_command_writes_the_screenshot() {
    let _gpu = gpu_lock();
    let dir = tempfile::tempdir().expect("temp dir");
    let shot = dir.path().join("frame.png");
    let output = Command::new(env!("CARGO_BIN_EXE_ppr-walkthrough"))
        .arg(asset("demo_room.glb"))
        .arg("--set")
        .arg(demo_set_file())
        .args([
            "--headless",
            "--frames",
            "2",
            "--size",
            "200x120",
            "--camera",
            "eye=0,1.6,4;target=0,1,-6;fov=70",
        ])
        .arg("--screenshot")
        .arg(&shot)
        .output()
        .expect("the binary runs");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&output.stderr));
    assert!(stdout.contains("visible reflector"), "the plan is printed: {stdout}");
    let image = image::open(&shot).expect("screenshot readable");
    assert_eq!((image.width(), image.height()), (200, 120));
}

#[test]
fn headless_without_frames_is_refused() {
    let output = Command::new(env!("CARGO_BIN_EXE_ppr-walkthrough"))
        .arg(asset("demo_room.glb"))
        .arg("--headless")
        .output()
        .expect("the binary runs");
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("--frames"));
}

/// Runs the headless binary on the demo level with `set` and `extra` arguments.
fn headless_with_set(set: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ppr-walkthrough"))
        .arg(asset("demo_room.glb"))
        .arg("--set")
        .arg(set)
        .args([
            "--headless",
            "--frames",
            "1",
            "--size",
            "64x48",
            "--camera",
            "eye=0,1.6,4;target=0,1,-6;fov=70",
        ])
        .args(extra)
        .output()
        .expect("the binary runs")
}

#[test]
fn headless_without_its_set_exits_2_naming_the_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let missing = dir.path().join("nowhere.ppr.json");
    let output = headless_with_set(&missing, &[]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("nowhere.ppr.json"), "the message names the file: {stderr}");
}

#[test]
fn headless_with_an_invalid_set_exits_2_naming_the_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let broken = dir.path().join("broken.ppr.json");
    std::fs::write(&broken, "{ \"format\": \"ppr-reflector-set\", ").expect("written");
    let output = headless_with_set(&broken, &[]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("broken.ppr.json"), "the message names the file: {stderr}");
}

#[test]
fn a_set_of_another_level_is_refused_unless_accepted() {
    let _gpu = gpu_lock();
    let dir = tempfile::tempdir().expect("temp dir");
    let other = dir.path().join("other.ppr.json");
    let mut set = ppr_format::ReflectorSet::load(demo_set_file()).expect("demo set");
    set.source.hash = format!("blake3:{}", "0".repeat(64));
    set.save(&other).expect("saved");

    let refused = headless_with_set(&other, &[]);
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(2), "{stderr}");
    for needle in ["other.ppr.json", "demo_room.glb", "--accept-level-mismatch"] {
        assert!(stderr.contains(needle), "the refusal names {needle}: {stderr}");
    }

    let accepted = headless_with_set(&other, &["--accept-level-mismatch"]);
    let stderr = String::from_utf8_lossy(&accepted.stderr);
    assert!(accepted.status.success(), "{stderr}");
    assert!(stderr.contains("warning") && stderr.contains("other.ppr.json"), "a warning remains: {stderr}");
}
