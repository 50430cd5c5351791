//! Glossy reflections against a CPU reference: the mean colour along GGX-sampled
//! reflected rays (`scene::GLOSSY_SAMPLES` per pixel), over the floor's on-screen pixels.

use glam::{DVec3, Vec3, Vec4};
use ppr_runtime::{Camera, Projection, ReflectionSettings};
use ppr_tests::harness::{Comparison, GpuFrame, compare, renderer, run, validated};
use ppr_tests::masks::interior;
use ppr_tests::scene::{Albedo, AnalyticScene, Frame};

const SIZE: [u32; 2] = [160, 120];

fn camera() -> Camera {
    Camera::look_at(DVec3::new(0.3, 1.9, 2.8), DVec3::new(-0.2, 0.4, -5.0), Vec3::Y, Projection::default())
}

/// A floor mirror (rough when `roughness` > 0) in a room with textured walls and a box.
fn scene(roughness: f64) -> AnalyticScene {
    let mut s = AnalyticScene::default();
    s.mirror("floor", DVec3::new(0.0, 0.0, -3.0), DVec3::X, DVec3::NEG_Z, [4.0, 5.0]);
    s.roughen("floor", roughness);
    s.quad(DVec3::new(0.0, 2.5, -8.0), DVec3::X, DVec3::Y, [6.0, 2.5], Albedo::Waves(0.25));
    for side in [-1.0, 1.0] {
        s.quad(
            DVec3::new(4.5 * side, 2.5, -4.0),
            DVec3::Z,
            DVec3::Y,
            [6.0, 2.5],
            Albedo::Gradient(Vec3::new(0.9, 0.6, 0.2), Vec3::new(0.2, 0.5, 0.9)),
        );
    }
    s.cuboid(DVec3::new(-1.2, 0.0, -4.6), DVec3::new(-0.4, 1.4, -3.8), Vec3::new(0.1, 0.8, 0.2));
    s.cuboid(DVec3::new(0.8, 0.0, -6.0), DVec3::new(1.6, 0.8, -5.2), Vec3::new(0.9, 0.2, 0.1));
    s
}

/// The output against `reference` over the floor's on-screen pixels, a pixel in from the
/// mask's border.
fn against(name: &str, frame: &Frame, out: &[Vec4], reference: &[Vec3]) -> Comparison {
    let f = Frame { reference: reference.to_vec(), ..frame.clone_images() };
    let mask = interior(&f, 1, |i| f.mirror[i].is_some() && f.on_screen[i]);
    ppr_tests::harness::save_comparison(env!("CARGO_TARGET_TMPDIR"), name, &f, out, |i| mask[i]);
    compare(&f, out, |i| mask[i])
}

fn render(s: &AnalyticScene, glossy: bool) -> (Frame, Vec<Vec4>) {
    let cam = camera();
    let frame = s.render(&cam, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let mut r = renderer();
    r.settings = ReflectionSettings { glossy, ..ReflectionSettings::ALL };
    r.set_reflectors(&validated(&s.reflector_set()));
    let out = run(&mut r, &gpu, &cam);
    assert_eq!(out.plan.glossy.len(), usize::from(s.set[0].roughness > 0.0), "{}", out.plan);
    (frame, out.pixels)
}

#[test]
fn a_rough_floor_is_as_close_to_its_glossy_reference_as_a_mirror_to_its_reflection() {
    let (mirror_frame, mirror) = render(&scene(0.0), true);
    let mirror_psnr = against("mirror", &mirror_frame, &mirror, &mirror_frame.reference);
    for roughness in [0.2, 0.35] {
        let s = scene(roughness);
        let (frame, glossy) = render(&s, true);
        let (_, sharp) = render(&s, false);
        let glossy_psnr = against(&format!("glossy_{roughness}"), &frame, &glossy, &frame.glossy_reference);
        let sharp_psnr = against(&format!("sharp_{roughness}"), &frame, &sharp, &frame.glossy_reference);
        eprintln!(
            "roughness {roughness}: glossy {glossy_psnr:?}\n  sharp {sharp_psnr:?}\n  mirror against its reflection {mirror_psnr:?}"
        );
        assert!(glossy_psnr.pixels > 3000, "{glossy_psnr:?}");
        // The goal on the lent GPU at 4K is 1 dB. At 160 x 120 on the software adapter a
        // far reflection's lobe spans tens of pixels, partly of content off screen or
        // hidden that PPR cannot see, and 4 to 12 taps (3 per pixel of footprint) stand for
        // it: measured 2.2 dB below at roughness 0.2 and 4.7 dB at 0.35 (12 taps always:
        // 1.6 and 4.7; sharp: 11.6 and 15.9 dB below). Bounds: 2.5 and 5.5 dB.
        let bound = if roughness < 0.3 { 2.5 } else { 5.5 };
        assert!(glossy_psnr.psnr >= mirror_psnr.psnr - bound, "{glossy_psnr:?} vs {mirror_psnr:?}");
        assert!(glossy_psnr.psnr > sharp_psnr.psnr + 5.0, "the blur must beat a mirror: {sharp_psnr:?}");
    }
}

#[test]
fn near_contact_the_glossy_reflection_stays_sharp() {
    // Where the boxes stand on the floor the reflection distance is near 0: the glossy
    // output equals the mirror output there, and differs where the reflected point is far.
    let s = scene(0.35);
    let (frame, glossy) = render(&s, true);
    let (_, sharp) = render(&s, false);
    let [w, h] = SIZE;
    let cam = camera();
    let rel_from_clip = cam.clip_from_relative(w as f32 / h as f32).inverse();
    let position = |x: f32, y: f32, depth: f32| {
        let ndc = Vec4::new(x / w as f32 * 2.0 - 1.0, 1.0 - y / h as f32 * 2.0, depth, 1.0);
        let p = rel_from_clip * ndc;
        p.truncate() / p.w
    };
    let differs = |i: usize| (glossy[i] - sharp[i]).truncate().abs().max_element() > 0.02;
    let (mut near, mut near_differ, mut far, mut far_differ) = (0, 0, 0, 0);
    for (i, src) in frame.source_px.iter().enumerate() {
        if frame.mirror[i].is_none() || !frame.on_screen[i] || glossy[i].w == 0.0 {
            continue;
        }
        let (x, y) = ((i as u32 % w) as f32 + 0.5, (i as u32 / w) as f32 + 0.5);
        let (sx, sy) = (src.x.clamp(0.0, w as f32 - 1.0), src.y.clamp(0.0, h as f32 - 1.0));
        let q_depth = frame.depth[(sy as u32 * w + sx as u32) as usize];
        let reach = (position(sx, sy, q_depth) - position(x, y, frame.depth[i])).length();
        if reach < 0.05 {
            near += 1;
            near_differ += usize::from(differs(i));
        } else if reach > 2.0 {
            far += 1;
            far_differ += usize::from(differs(i));
        }
    }
    eprintln!("within 5 cm of contact {near_differ} of {near} differ; beyond 2 m {far_differ} of {far}");
    assert!(near >= 10 && far >= 100, "{near} {far}");
    assert!(near_differ * 4 <= near, "near contact stays sharp: {near_differ} of {near}");
    assert!(far_differ * 2 >= far, "far away it spreads: {far_differ} of {far}");
}
