//! `--stereo`: both eyes side by side, PPR for both from one renderer. Each eye is checked
//! against the mono frame of the head's camera at the eye's size (32 mm of parallax: the
//! reflections must land on nearly the same pixels).

use ppr_walkthrough::run_headless;

use crate::common::{gpu_lock, headless_args};

#[test]
fn stereo_renders_both_eyes_side_by_side_with_their_reflections() {
    let _gpu = gpu_lock();
    let stereo = run_headless(&headless_args(&["--camera", "cam_mirror", "--size", "320x120", "--stereo"]))
        .expect("stereo run");
    let mono =
        run_headless(&headless_args(&["--camera", "cam_mirror", "--size", "160x120"])).expect("mono run");
    assert_eq!(stereo.gpu_errors, 0, "wgpu reported errors");
    assert_eq!((stereo.image.width(), stereo.image.height()), (320, 120));
    // The left eye's targets are the eye's size, and see the reflectors the head sees.
    assert_eq!(stereo.reflection.dimensions(), mono.reflection.dimensions());
    assert_eq!(stereo.plan.visible, mono.plan.visible, "{}\n{}", stereo.plan, mono.plan);
    let found = |img: &image::Rgba32FImage| img.pixels().filter(|p| p.0[3] > 0.0).count();
    let (eye, head) = (found(&stereo.reflection), found(&mono.reflection));
    eprintln!("reflections found: left eye {eye}, head alone {head}");
    assert!(head > 1000, "{head}");
    assert!(eye.abs_diff(head) * 10 <= head, "left eye {eye} against the head's {head}");
    // The two halves differ (parallax) and neither is empty.
    let half = |x0: u32| -> Vec<[u8; 4]> {
        (0..120)
            .flat_map(|y| (x0..x0 + 160).map(move |x| (x, y)))
            .map(|(x, y)| stereo.image.get_pixel(x, y).0)
            .collect()
    };
    let (left, right) = (half(0), half(160));
    let differing = left.iter().zip(&right).filter(|(a, b)| a != b).count();
    assert!(differing > 100, "the eyes see the same image ({differing} pixels differ)");
    assert!(
        left.iter().chain(&right).filter(|p| p[0] as u32 + p[1] as u32 + p[2] as u32 > 30).count() > 20000
    );
}
