//! A lost device is recreated with every resource, and the frame after it is the frame
//! there would have been.

use ppr_walkthrough::run_headless;

use crate::common::{difference, gpu_lock, headless_args};

#[test]
fn rendering_goes_on_after_the_device_is_lost() {
    let _gpu = gpu_lock();
    let steady =
        run_headless(&headless_args(&["--camera", "cam_steps", "--size", "160x90", "--frames", "2"]))
            .expect("run without loss");
    let lost = run_headless(&headless_args(&[
        "--camera",
        "cam_steps",
        "--size",
        "160x90",
        "--frames",
        "2",
        "--lose-device-at",
        "0",
    ]))
    .expect("run with a device loss after the first frame");
    assert_eq!(steady.device_recoveries, 0);
    assert_eq!(lost.device_recoveries, 1, "the loss was noticed and the device recreated");
    assert_eq!(lost.gpu_errors, 0, "the new device reported no error");
    let d = difference(&steady.reflection, &lost.reflection, |_, _| true);
    assert!(
        d.mean_abs_error < 1e-6,
        "the recovered frame equals the steady one (mean error {})",
        d.mean_abs_error
    );
    let d = difference(&steady.scene_color, &lost.scene_color, |_, _| true);
    assert!(d.mean_abs_error < 1e-6, "scene colour differs after recovery ({})", d.mean_abs_error);
}

#[test]
fn a_loss_after_the_last_frame_still_yields_a_frame() {
    let _gpu = gpu_lock();
    let frame = run_headless(&headless_args(&["--size", "96x54", "--frames", "1", "--lose-device-at", "0"]))
        .expect("run with a loss after the only frame");
    assert_eq!(frame.device_recoveries, 1);
    assert_eq!(frame.image.dimensions(), (96, 54));
}
