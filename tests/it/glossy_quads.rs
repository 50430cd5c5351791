//! Glossy quads sharing their taps (`PlanParams::glossy_shared_taps`): where the device
//! has subgroups (the `subgroups` binary's lavapipe), 2 x 2 pixels with wide footprints each
//! take a quarter of the taps and share the sum, as close to the glossy reference as each
//! pixel taking all its own; where it has none (llvmpipe through GL in `it`), the option is
//! ignored and the image is the unshared one bit for bit.

use glam::Vec4;
use ppr_runtime::{Choice, ReflectionSettings};
use ppr_tests::glossy_scene::{SIZE, against, camera, scene};
use ppr_tests::gpu::gpu;
use ppr_tests::harness::{GpuFrame, renderer, run, validated};

/// Opens this binary's device (first thing in every test: the first `gpu()` picks it).
fn open_device() {
    crate::select_backends();
    if crate::REQUIRE_SUBGROUPS {
        assert!(
            gpu().device.features().contains(wgpu::Features::SUBGROUP),
            "this test binary needs an adapter with subgroups (lavapipe through Vulkan); got {:?}",
            gpu().info
        );
    }
}

#[test]
fn glossy_quads_sharing_their_taps_stay_as_close_to_the_glossy_reference() {
    open_device();
    let s = scene(0.35);
    let cam = camera();
    let frame = s.render(&cam, SIZE);
    let gpu_frame = GpuFrame::upload(&frame);
    let dir = env!("CARGO_TARGET_TMPDIR");
    for indirect in [Choice::Off, Choice::On] {
        let render = |shared: bool| {
            let mut r = renderer();
            r.settings = ReflectionSettings { glossy: true, ..ReflectionSettings::ALL };
            r.plan_params.indirect = indirect;
            r.plan_params.glossy_shared_taps = if shared { Choice::On } else { Choice::Off };
            r.set_reflectors(&validated(&s.reflector_set()));
            let out = run(&mut r, &gpu_frame, &cam);
            assert_eq!(out.plan.indirect, indirect == Choice::On);
            assert_eq!(out.plan.glossy.len(), 1, "{}", out.plan);
            (r.shares_glossy_taps(), out.pixels)
        };
        let (_, own) = render(false);
        let (shares, shared) = render(true);
        assert_eq!(shares, crate::REQUIRE_SUBGROUPS, "quads share where the device has subgroups");
        let bits = |v: Vec4| v.to_array().map(f32::to_bits);
        let name = |n: &str| format!("glossy_quads_{n}_{indirect:?}");
        let own_psnr = against(dir, &name("own"), &frame, &own, &frame.glossy_reference);
        let shared_psnr = against(dir, &name("shared"), &frame, &shared, &frame.glossy_reference);
        let differ = (0..own.len()).filter(|&i| bits(own[i]) != bits(shared[i])).count();
        eprintln!(
            "indirect {indirect:?}: own taps {own_psnr:?}\n  shared {shared_psnr:?}, {differ} pixels differ"
        );
        if !shares {
            assert_eq!(differ, 0, "without subgroups the option changes nothing");
            continue;
        }
        // Most of the rough floor's pixels have footprints of several pixels here.
        assert!(differ * 4 > own_psnr.pixels, "quads shared: {differ} of {} pixels differ", own_psnr.pixels);
        // Each pixel still averages as many taps, a pixel at most off its own footprint.
        assert!(shared_psnr.psnr >= own_psnr.psnr - 0.3, "{shared_psnr:?} vs {own_psnr:?}");
        // Few pixels far off the unshared blur: each quad's footprints are alike, but its
        // neighbours' taps are other samples of the lobe (12 taps stand for it).
        let mut diffs: Vec<f32> =
            own.iter().zip(&shared).map(|(a, b)| (*a - *b).truncate().abs().max_element()).collect();
        diffs.sort_by(f32::total_cmp);
        let p99 = diffs[diffs.len() * 99 / 100];
        let over = diffs.iter().filter(|&&d| d > 0.1).count();
        eprintln!(
            "  difference from the unshared blur: 99th percentile {p99}, largest {}, {over} over 0.1",
            diffs[diffs.len() - 1]
        );
        assert!(p99 < 0.1, "99th percentile difference from the unshared blur {p99}");
    }
}
