//! The frame upload written straight into a mapped buffer that the passes bind
//! (`FrameBuffers::bindable_uploads`, on devices with `MAPPABLE_PRIMARY_BUFFERS`), against
//! the upload copied from a staging buffer into the frame buffers' own
//! (`DebugOptions::copied_upload`, every other device's path). Runs in `subgroups` on
//! lavapipe through Vulkan, which has the feature (llvmpipe through GL has not).

use ppr_runtime::{Choice, ResolutionTier, TestedEntry};

use ppr_tests::gpu::gpu;
use ppr_tests::harness::{GpuFrame, renderer, run, validated};
use ppr_tests::random_scenes::{Rng, grouped_set, puddle_floor, random_camera};
use ppr_tests::views::{SIZE, pond_views};

#[test]
fn a_bound_upload_renders_the_copied_upload_s_frames() {
    // Two views by turns (each encode its own upload buffer, the views' parts differ), a
    // water layer and a glossy pond, direct and indirect frames and a reduced tier: every
    // pass that reads the upload reads it from the bound buffer, with no copy recorded,
    // and renders the copied upload's frames bit for bit; frames waited for reuse one
    // buffer.
    crate::select_backends();
    assert!(
        gpu().device.features().contains(wgpu::Features::MAPPABLE_PRIMARY_BUFFERS),
        "this test needs an adapter that maps bindable buffers (lavapipe through Vulkan: \
         Debian's mesa-vulkan-drivers); got {:?}",
        gpu().info
    );
    let (set, cams, frames) = pond_views();
    for (indirect, tier) in [
        (Choice::Off, ResolutionTier::Full),
        (Choice::On, ResolutionTier::Full),
        (Choice::Off, ResolutionTier::Half),
    ] {
        let mut bound = renderer();
        let mut copied = renderer();
        copied.debug.copied_upload = true;
        for r in [&mut bound, &mut copied] {
            r.plan_params.indirect = indirect;
            r.settings.resolution = tier;
            r.set_reflectors(&set);
        }
        for (k, v) in [0, 1, 1, 0, 0, 1].into_iter().enumerate() {
            let what = format!("{indirect:?}, {tier:?}, frame {k} (view {v})");
            let a = run(&mut bound, &frames[v], &cams[v]);
            assert_eq!(bound.last_upload_copy_count(), 0, "{what}: the bound upload is copied nowhere");
            let b = run(&mut copied, &frames[v], &cams[v]);
            assert!(copied.last_upload_copy_count() >= 1, "{what}: the copied upload");
            assert!(!a.plan.visible.is_empty() && !a.plan.layers.is_empty(), "{what}: {}", a.plan);
            assert_eq!(a.plan.indirect, indirect == Choice::On, "{what}: {}", a.plan);
            assert!(a.pixels.iter().filter(|p| p.w > 0.0).count() > 500, "{what}: reflections found");
            assert!(a.layer_pixels.iter().any(|p| p.w > 0.0), "{what}: the water layer reflects");
            a.assert_same_frame(&b, &what);
        }
        assert!(
            bound.upload_buffers_created() <= 2,
            "{indirect:?}, {tier:?}: 6 frames, each waited for, created {} upload buffers",
            bound.upload_buffers_created()
        );
    }
}

#[test]
fn a_bound_upload_holds_the_plane_groups_static_words() {
    // Merged plane groups read their members' grid from words written once, when a
    // buffer is made (the frames write only the groups' headers): every bound buffer
    // holds them, as the copied upload's buffer does.
    crate::select_backends();
    let mut rng = Rng(0x5eed_0333);
    let scene = puddle_floor(&mut rng);
    let set = validated(&grouped_set(&scene));
    let cameras: Vec<_> = (0..3).map(|_| random_camera(&mut rng)).collect();
    let frames: Vec<_> = cameras.iter().map(|c| GpuFrame::upload(&scene.render(c, SIZE))).collect();
    let mut bound = renderer();
    let mut copied = renderer();
    copied.debug.copied_upload = true;
    for r in [&mut bound, &mut copied] {
        r.plan_params.plane_groups = Choice::On;
        r.set_reflectors(&set);
    }
    let mut grouped = 0;
    for (k, c) in [0, 1, 2, 1, 0].into_iter().enumerate() {
        let a = run(&mut bound, &frames[c], &cameras[c]);
        assert_eq!(bound.last_upload_copy_count(), 0, "frame {k}");
        let b = run(&mut copied, &frames[c], &cameras[c]);
        grouped += a.plan.tested.iter().filter(|e| matches!(e, TestedEntry::PlaneGroup(_))).count();
        a.assert_same_frame(&b, &format!("frame {k} (camera {c})"));
    }
    assert!(grouped >= 3, "the puddles must be tested as merged groups: {grouped} group entries");
}
