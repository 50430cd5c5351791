//! The reduced tiers' upsample in its two layouts, one output pixel per invocation and two
//! by two sharing their reduced samples, stores the same image bit for bit: half and
//! quarter tiers, direct and indirect dispatch, a viewport that is no multiple of the
//! quads' 32 × 32 output pixels.

use ppr_runtime::{Choice, ReflectionSettings, ResolutionTier};
use ppr_tests::harness::{GpuFrame, renderer, run, validated};

use crate::reflection::{mirror_room, room_camera};

#[test]
fn quads_upsample_the_same_image_as_one_pixel_per_invocation() {
    let scene = mirror_room(true);
    let camera = room_camera();
    for size in [[160, 120], [157, 115]] {
        let frame = scene.render(&camera, size);
        let gpu = GpuFrame::upload(&frame);
        for tier in [ResolutionTier::Half, ResolutionTier::Quarter] {
            for indirect in [Choice::Off, Choice::On] {
                let render = |pixel_per_thread: bool| {
                    let mut r = renderer();
                    r.plan_params.indirect = indirect;
                    r.settings = ReflectionSettings { resolution: tier, ..ReflectionSettings::ALL };
                    r.debug.upsample_pixel_per_thread = pixel_per_thread;
                    r.set_reflectors(&validated(&scene.reflector_set()));
                    run(&mut r, &gpu, &camera)
                };
                let (pixels, quads) = (render(true), render(false));
                let case = format!("{size:?} {tier:?} indirect={indirect:?}");
                assert_eq!(quads.plan.viewport, tier.reduced(size), "{case}: the plan runs reduced");
                assert_eq!(quads.plan.indirect, indirect == Choice::On, "{case}");
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
