//! The reflection pass's two layouts for mirrors in direct dispatch, one pixel per
//! invocation and two by two pixels sharing their neighbourhood reads, store the same image
//! bit for bit: the seed's far-replacement rule on and off, and a viewport that is no
//! multiple of the quads' 32 × 32 pixels; the frames that always take one pixel per
//! invocation (indirect dispatch, glossy) store it too.

use ppr_runtime::{Choice, ReflectionSettings};
use ppr_tests::harness::{GpuFrame, renderer, run, validated};

use crate::reflection::{mirror_room, room_camera};

#[test]
fn quads_store_the_same_image_as_one_pixel_per_invocation() {
    let mut scene = mirror_room(true);
    scene.roughen("floor mirror", 0.2);
    let camera = room_camera();
    for size in [[160, 120], [157, 115]] {
        let frame = scene.render(&camera, size);
        let gpu = GpuFrame::upload(&frame);
        for indirect in [Choice::Off, Choice::On] {
            for (glossy, replace_far) in [(false, false), (false, true), (true, false)] {
                let render = |quads: bool| {
                    let mut r = renderer();
                    r.plan_params.indirect = indirect;
                    r.settings = ReflectionSettings {
                        glossy,
                        replace_far_reflections: replace_far,
                        ..ReflectionSettings::ALL
                    };
                    r.debug.reflection_quads = quads;
                    r.set_reflectors(&validated(&scene.reflector_set()));
                    run(&mut r, &gpu, &camera)
                };
                let (pixels, quads) = (render(false), render(true));
                let case =
                    format!("{size:?} indirect={indirect:?} glossy={glossy} replace_far={replace_far}");
                assert_eq!(quads.plan.indirect, indirect == Choice::On, "{case}");
                assert_eq!(quads.plan.glossy.len(), 1, "{case}: the rough floor");
                let reflected = pixels.pixels.iter().filter(|p| p.w > 0.0).count();
                assert!(
                    reflected > size[0] as usize * size[1] as usize / 10,
                    "{case}: {reflected} pixels reflect"
                );
                let differ: Vec<usize> = (0..pixels.pixels.len())
                    .filter(|&i| {
                        pixels.pixels[i].to_array().map(f32::to_bits)
                            != quads.pixels[i].to_array().map(f32::to_bits)
                    })
                    .collect();
                assert!(
                    differ.is_empty(),
                    "{case}: {} of {} pixels differ, first at {:?}: {:?} one per invocation, {:?} quads",
                    differ.len(),
                    pixels.pixels.len(),
                    differ.first().map(|&i| [i as u32 % size[0], i as u32 / size[0]]),
                    differ.first().map(|&i| pixels.pixels[i]),
                    differ.first().map(|&i| quads.pixels[i]),
                );
            }
        }
    }
}
