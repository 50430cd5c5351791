//! The projection's write paths (`ppr_runtime::WritePath`, the bench's timed variants):
//! the default one, which computes the depth-occlusion test's tolerance only where the
//! surface at the target lies in front of the plane, writes the same intermediate buffer,
//! bit for bit, as the full test, as the path that reads the target's depth with the
//! plain load, and as the path without the plain load, on random scenes whose occlusion
//! test does reject writes.

use ppr_runtime::{Choice, ReflectionRenderer, WritePath};

use ppr_tests::harness::{GpuFrame, renderer, run, validated};
use ppr_tests::random_scenes::{Rng, grouped_set, random_camera, random_scene};

const SIZE: [u32; 2] = [96, 64];

fn configured(write_path: WritePath, depth_occlusion: Choice) -> ReflectionRenderer {
    let mut r = renderer();
    r.plan_params.indirect = Choice::Off;
    r.plan_params.depth_occlusion = depth_occlusion;
    r.debug.write_path = write_path;
    r
}

#[test]
fn every_write_path_writes_the_same_buffer() {
    let mut rng = Rng(0x5eed_0a11);
    let mut written = 0usize;
    let mut rejected = 0usize;
    for case in 0..6 {
        let parallel = case % 2 == 0;
        let scene = random_scene(&mut rng, parallel);
        let camera = random_camera(&mut rng);
        let frame = GpuFrame::upload(&scene.render(&camera, SIZE));
        let set = validated(&grouped_set(&scene));
        let mut default = configured(WritePath::Default, Choice::Auto);
        default.set_reflectors(&set);
        let a = run(&mut default, &frame, &camera);
        assert!(a.plan.depth_occlusion, "{}", a.plan);
        for path in [WritePath::FullTolerance, WritePath::LoadsTogether, WritePath::NoPreload] {
            let mut other = configured(path, Choice::Auto);
            other.set_reflectors(&set);
            let b = run(&mut other, &frame, &camera);
            assert_eq!(a.intermediate, b.intermediate, "{path:?} writes another buffer in case {case}");
        }
        // What the occlusion test rejects: values written without it and not with it.
        let mut unoccluded = configured(WritePath::Default, Choice::Off);
        unoccluded.set_reflectors(&set);
        let c = run(&mut unoccluded, &frame, &camera);
        rejected += a.intermediate.iter().zip(&c.intermediate).filter(|(a, c)| a != c).count();
        written += a.intermediate.iter().filter(|&&v| v != ppr_runtime::CLEAR_VALUE).count();
    }
    assert!(written > 1_000, "the random scenes must produce writes: {written}");
    assert!(
        rejected > 20,
        "the occlusion test must reject some writes for the paths to differ in: {rejected}"
    );
}
