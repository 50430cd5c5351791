//! Temporal: a camera moving in 1e-3 px steps must not make reflections flicker. With the
//! seed's fraction mirroring the filtered reflection changes continuously; without it, a
//! pixel jumps whenever the pixel that writes it changes (the "shaking" of the bonus
//! slides).

use glam::{DVec3, Vec3, Vec4};
use ppr_runtime::{Camera, Choice, Projection, ReflectionSettings};
use ppr_tests::harness::{GpuFrame, renderer, run};

use crate::floor_room;

const SIZE: [u32; 2] = [128, 96];
const FRAMES: usize = 24;

/// Per-pixel changes between consecutive frames over reflector pixels valid in both,
/// away from silhouettes: (largest, mean, changes above 1/255).
fn frame_to_frame(mirror_fractions: bool) -> (f32, f64, usize) {
    let scene = floor_room(8.0);
    let set = scene.reflector_set();
    let base = DVec3::new(0.3, 1.6, 2.5);
    let target = DVec3::new(-0.2, 0.6, -5.0);
    // 1e-3 px of motion for a point 7 m away with a 60° field of view over 96 rows.
    let focal_px = SIZE[1] as f64 / 2.0 / (30f64.to_radians()).tan();
    let step = 1e-3 * 7.0 / focal_px;
    let mut previous: Option<Vec<Vec4>> = None;
    let (mut worst, mut sum, mut n, mut visible) = (0.0f32, 0.0f64, 0usize, 0usize);
    for k in 0..FRAMES {
        let shift = DVec3::new(step * k as f64, step * 0.5 * k as f64, 0.0);
        let camera = Camera::look_at(base + shift, target + shift, Vec3::Y, Projection::default());
        let frame = scene.render(&camera, SIZE);
        let gpu = GpuFrame::upload(&frame);
        let mut r = renderer();
        r.plan_params.indirect = Choice::Off;
        r.settings = ReflectionSettings {
            holes: true,
            filtering: true,
            anti_bleeding: false,
            ..ReflectionSettings::ALL
        };
        r.set_reflectors(&ppr_tests::harness::validated(&set));
        let layout = ppr_runtime::EncodingLayout::for_resolution(SIZE[0], SIZE[1]);
        r.debug.encoding = Some(ppr_runtime::EncodingLayout { mirror_fractions, ..layout });
        let out = run(&mut r, &gpu, &camera);
        // Away from silhouettes, where a different surface legitimately takes over.
        let edges = ppr_tests::masks::reference_edges(&frame, 0.15);
        let smooth = ppr_tests::masks::interior(&frame, 2, |i| frame.on_screen[i] && !edges[i]);
        if let Some(prev) = &previous {
            for (i, (a, b)) in prev.iter().zip(&out.pixels).enumerate() {
                if a.w > 0.0 && b.w > 0.0 && smooth[i] {
                    let d = (*a - *b).truncate().abs().max_element();
                    worst = worst.max(d);
                    visible += usize::from(d > 1.0 / 255.0);
                    sum += f64::from(d);
                    n += 1;
                }
            }
        }
        previous = Some(out.pixels);
    }
    (worst, sum / n.max(1) as f64, visible)
}

#[test]
fn sub_pixel_camera_motion_does_not_make_reflections_flicker() {
    let (with, with_mean, with_jumps) = frame_to_frame(true);
    let (without, without_mean, without_jumps) = frame_to_frame(false);
    eprintln!(
        "{FRAMES} frames, 1e-3 px steps: with fraction mirroring largest change {with:.4}, mean {with_mean:.2e}, {with_jumps} changes above 1/255; without: {without:.4}, {without_mean:.2e}, {without_jumps}"
    );
    // Bounds (linear colour of a [0, 1] scene): no change above 0.05 with mirroring, and
    // without it more visible jumps and a larger mean change.
    assert!(with <= 0.05, "{with}");
    assert!(without_jumps > with_jumps, "{without_jumps} vs {with_jumps}");
    assert!(without_mean > 1.3 * with_mean, "{without_mean} vs {with_mean}");
}
