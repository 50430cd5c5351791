//! The exact planar reflection as a technique.

use ppr_baselines::PlanarReflectionTechnique;
use ppr_testbed::RenderSettings;

use crate::common::{SIZE, gpu, run, timed};
use crate::scenes::floor_mirror;

/// The technique is the reference: same level, same settings, same mirrored views, so its
/// output equals the reference bit for bit, off-screen reflected points included (no
/// screen-space technique has those).
#[test]
fn planar_reflection_is_the_reference() {
    timed("planar_reflection_is_the_reference", || {
        let scene = floor_mirror();
        let g = gpu();
        let mut technique = PlanarReflectionTechnique::new(
            &g.ctx.device,
            &g.ctx.queue,
            &scene.level,
            &scene.reflectors,
            RenderSettings::default(),
        );
        let r = run(&scene, &scene.camera, SIZE, &mut technique);
        eprintln!("{} timings {:?}", r.summary(), r.timings);
        assert_eq!(
            r.reflection.as_raw(),
            r.frame.reference.as_raw(),
            "planar technique differs from the reference"
        );
        let off = r.frame.off_screen_mask();
        assert!(off.count() > 1000, "the frame has off-screen reflected points: {}", off.count());
        assert_eq!(ppr_testbed::render_job::hole_share(&r.reflection, &r.frame.reflector_mask()), 0.0);
        match &r.timings {
            None => assert!(!g.ctx.has_timestamps(), "timestamps exist but none were read"),
            Some(t) => {
                let names: Vec<&str> = t.iter().map(|(n, _)| n.as_str()).collect();
                assert!(names.iter().all(|n| ["mirrored views", "copy to output"].contains(n)), "{names:?}");
            }
        }
    });
}
