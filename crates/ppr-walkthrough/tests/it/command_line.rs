//! The binary itself: `--headless --frames N --screenshot out.png --camera ...`.

use std::process::Command;

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
