//! Feeding PPR the previous frame's composite (`--feed-previous-frame`, key P): the first
//! frame is today's, later ones show reflections inside reflections.

use ppr_walkthrough::run_headless;

use crate::common::{gpu_lock, headless_args};

fn reflection(extra: &[&str]) -> image::Rgba32FImage {
    let mut argv = vec!["--camera", "cam_mirror", "--size", "160x90"];
    argv.extend_from_slice(extra);
    run_headless(&headless_args(&argv)).expect("headless frame").reflection
}

/// The demo room's `cam_mirror` at 160×90 on llvmpipe: 1217 of the 4801 reflected pixels
/// change after three fed frames (the mirror shows the reflective floor's reflection).
#[test]
fn the_previous_frame_feeds_ppr_from_the_second_frame() {
    let _gpu = gpu_lock();
    let plain = reflection(&["--frames", "1"]);
    let first = reflection(&["--frames", "1", "--feed-previous-frame"]);
    assert!(plain.as_raw() == first.as_raw(), "the first fed frame differs from an ordinary frame");
    let plain3 = reflection(&["--frames", "3"]);
    let fed3 = reflection(&["--frames", "3", "--feed-previous-frame"]);
    assert!(plain.as_raw() == plain3.as_raw(), "ordinary frames of one camera differ");
    let found = plain.pixels().filter(|p| p.0[3] > 0.0).count();
    let changed = plain
        .pixels()
        .zip(fed3.pixels())
        .filter(|(a, b)| a.0[3] > 0.0 && (0..3).any(|c| (a.0[c] - b.0[c]).abs() > 1e-3))
        .count();
    eprintln!("cam_mirror 160x90: {changed} of {found} reflected pixels changed by the fed-back frames");
    assert!(changed * 20 > found, "{changed} of {found} reflected pixels changed");
}
