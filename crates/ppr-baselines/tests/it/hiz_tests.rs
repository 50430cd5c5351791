//! Hi-Z SSR: the pyramid against a CPU reference, the trace against the exact reference.

use ppr_baselines::gpu_types::depth_linearisation;
use ppr_baselines::hiz_pyramid::SKY_DEPTH;
use ppr_baselines::{HiZPyramid, HiZSettings, HiZSsrTechnique, SsrSettings, SsrTechnique};
use ppr_runtime::{Camera, DepthMode, Projection};
use ppr_testbed::SyntheticScene;

use crate::common::{SIZE, TechniqueRun, gpu, run, timed};
use crate::scenes::floor_mirror;

fn run_hiz(scene: &SyntheticScene, camera: &Camera, size: [u32; 2]) -> (TechniqueRun, HiZSsrTechnique) {
    let g = gpu();
    let mut technique =
        HiZSsrTechnique::new(&g.ctx.device, &g.ctx.queue, &scene.reflectors, HiZSettings::seed());
    let r = run(scene, camera, size, &mut technique);
    eprintln!("{}", r.summary());
    (r, technique)
}

/// Hi-Z SSR on the floor mirror, over reflector pixels whose reflected point is on screen.
#[test]
fn hiz_ssr_matches_the_reference_on_screen() {
    timed("hiz_ssr_matches_the_reference_on_screen", || {
        let scene = floor_mirror();
        let (r, _) = run_hiz(&scene, &scene.camera, SIZE);
        let c = r.on_screen();
        assert!(c.pixels > 1000, "{c}");
        let g = gpu();
        let mut brute =
            SsrTechnique::new(&g.ctx.device, &g.ctx.queue, &scene.reflectors, SsrSettings::brute_force());
        let b = run(&scene, &scene.camera, SIZE, &mut brute);
        eprintln!("{}", b.summary());
    });
}

/// Level 0 of the pyramid is the linear view depth of the depth buffer, and every texel of
/// every further level is the minimum of its 2 × 2 children (plus the last row or column
/// of an odd-sized level below), checked against a CPU reference at an odd size and with
/// reversed Z.
#[test]
fn hiz_levels_are_the_min_of_their_children() {
    timed("hiz_levels_are_the_min_of_their_children", || {
        let scene = floor_mirror();
        let size = [151, 97];
        for depth in [DepthMode::Standard, DepthMode::Reversed] {
            let camera =
                Camera { projection: Projection { depth, ..scene.camera.projection }, ..scene.camera };
            let (r, technique) = run_hiz(&scene, &camera, size);
            let g = gpu();
            let pyramid = technique.pyramid().expect("prepared");
            assert_eq!(pyramid.levels(), 8, "151 wide: levels of 151, 75, 37, 18, 9, 4, 2, 1");

            let aspect = size[0] as f32 / size[1] as f32;
            let (a, b) = depth_linearisation(camera.projection.clip_from_view(aspect).as_dmat4());
            let far = camera.projection.far_depth();
            let level0 = pyramid.read_level(&g.ctx.device, &g.ctx.queue, 0).expect("level 0");
            for (i, (&d, &w)) in r.frame.depth.iter().zip(&level0).enumerate() {
                let expected = if d == far { f64::from(SKY_DEPTH) } else { b / (f64::from(d) - a) };
                assert!(
                    (f64::from(w) - expected).abs() <= 1e-4 * expected,
                    "{depth:?}: level 0 pixel {i}: {w} for depth {d}, expected {expected}"
                );
            }

            let mut below = level0;
            for level in 1..pyramid.levels() {
                let [sw, sh] = HiZPyramid::level_size(size, level - 1);
                let [w, h] = HiZPyramid::level_size(size, level);
                let values = pyramid.read_level(&g.ctx.device, &g.ctx.queue, level).expect("level");
                assert_eq!(values.len(), (w * h) as usize);
                for y in 0..h {
                    for x in 0..w {
                        let xs = 2 * x..(2 * x + 2 + u32::from(x == w - 1 && sw % 2 == 1)).min(sw);
                        let ys = 2 * y..(2 * y + 2 + u32::from(y == h - 1 && sh % 2 == 1)).min(sh);
                        let expected = ys
                            .flat_map(|yy| xs.clone().map(move |xx| (xx, yy)))
                            .map(|(xx, yy)| below[(yy * sw + xx) as usize])
                            .fold(f32::INFINITY, f32::min);
                        let got = values[(y * w + x) as usize];
                        assert_eq!(got, expected, "{depth:?}: level {level} texel ({x}, {y})");
                    }
                }
                below = values;
            }
            assert!(below[0] < SKY_DEPTH, "the top texel is the closest surface of the frame");
        }
    });
}
