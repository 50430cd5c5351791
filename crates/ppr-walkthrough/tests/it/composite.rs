//! The walkthrough's composite: PPR's reflection over a constant sky colour (the fallback a
//! game would take from its reflection probe) by PPR's confidence, then over the scene by
//! the surface's reflection weight.

use glam::Vec3;
use ppr_walkthrough::composite_pass::FALLBACK_REFLECTION;
use ppr_walkthrough::run_headless;

use crate::common::{gpu_lock, headless_args};

/// Narkowicz's ACES fit, as `composite_pass.wgsl`.
fn tonemap(x: Vec3) -> Vec3 {
    ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(Vec3::ZERO, Vec3::ONE)
}

fn srgb8(c: Vec3) -> [i32; 3] {
    c.to_array().map(|v| {
        let s = if v <= 0.003_130_8 { v * 12.92 } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 };
        (s * 255.0).round() as i32
    })
}

#[test]
fn the_final_image_blends_ppr_over_the_sky_fallback_by_its_confidence() {
    let _gpu = gpu_lock();
    let f = run_headless(&headless_args(&["--camera", "cam_steps", "--size", "320x180", "--frames", "1"]))
        .expect("headless run");
    assert!(!f.plan.is_empty(), "{}", f.plan);
    let fallback = Vec3::from(FALLBACK_REFLECTION);
    let (w, h) = f.image.dimensions();
    let (mut compared, mut off, mut differs_from_old, mut old_off) = (0usize, 0usize, 0usize, 0usize);
    // The lower 40 %: the status text and its panel are drawn at the top (down to row 91 of
    // 180 here).
    for y in h * 3 / 5..h {
        for x in 0..w {
            let weight = f32::from(f.reflection_weight.get_pixel(x, y).0[0]) / 255.0;
            if weight <= 0.0 {
                continue;
            }
            let scene = Vec3::from_slice(&f.scene_color.get_pixel(x, y).0[..3]);
            let ppr = f.reflection.get_pixel(x, y).0;
            let (rgb, alpha) = (Vec3::from_slice(&ppr[..3]), ppr[3].clamp(0.0, 1.0));
            let expected = srgb8(tonemap(scene.lerp(fallback.lerp(rgb, alpha), weight).max(Vec3::ZERO)));
            // The composite before: the surface's own colour where PPR had nothing.
            let old = srgb8(tonemap(scene.lerp(rgb, weight * alpha).max(Vec3::ZERO)));
            let got = f.image.get_pixel(x, y).0;
            let far = |e: [i32; 3]| (0..3).any(|c| (e[c] - i32::from(got[c])).abs() > 2);
            compared += 1;
            off += usize::from(far(expected));
            old_off += usize::from(far(old));
            differs_from_old += usize::from((0..3).any(|c| (expected[c] - old[c]).abs() > 3));
        }
    }
    eprintln!(
        "{compared} reflective pixels: {off} off the blend over the fallback, {old_off} off the old \
         composite; {differs_from_old} where the two differ"
    );
    assert!(compared > 2000, "{compared}");
    assert!(differs_from_old > 50, "the fallback must show somewhere: {differs_from_old}");
    assert!(
        off * 200 <= compared,
        "{off} of {compared} pixels are not mix(scene, mix(fallback, ppr, a), weight)"
    );
}
