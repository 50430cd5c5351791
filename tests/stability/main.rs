//! The stability suite: hard cases, what "stable" means for each, and the check that holds
//! it (docs/stability.md lists them with the bounds measured here).

mod accuracy;
mod cameras;
mod encoding;
mod extractor;
mod positions;
mod temporal;

use glam::{DVec3, Vec3, Vec4};
use ppr_runtime::{Camera, EncodingLayout, FramePlan};
use ppr_tests::scene::{Albedo, AnalyticScene, Frame};

/// A large floor mirror in a room: wavy back wall, gradient side walls, two boxes.
pub fn floor_room(mirror_half: f64) -> AnalyticScene {
    let mut s = AnalyticScene::default();
    s.mirror("floor", DVec3::new(0.0, 0.0, -4.0), DVec3::X, DVec3::NEG_Z, [mirror_half, mirror_half]);
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
    s.cuboid(DVec3::new(-1.2, 0.0, -4.6), DVec3::new(-0.2, 1.0, -3.8), Vec3::new(0.9, 0.15, 0.1));
    s.cuboid(DVec3::new(1.4, 0.0, -3.0), DVec3::new(2.2, 0.6, -2.2), Vec3::new(0.9, 0.9, 0.2));
    s
}

/// What every frame, however hard its case, must satisfy.
#[derive(Debug, Default)]
pub struct Invariants {
    /// Output pixels that are NaN or infinite (must be 0).
    pub non_finite: usize,
    /// Intermediate values whose decoded source pixel lies outside the viewport or on a
    /// pixel without depth (must be 0).
    pub bad_sources: usize,
    /// Intermediate values written.
    pub written: usize,
    /// Output pixels with a reflection.
    pub reflected: usize,
}

/// Checks the output and the intermediate buffer of a frame (all tiles are cleared: the
/// runner must use `Choice::Off` for indirect dispatch).
pub fn invariants(frame: &Frame, plan: &FramePlan, pixels: &[Vec4], intermediate: &[u32]) -> Invariants {
    let [w, h] = frame.size;
    let layout: EncodingLayout = plan.encoding;
    let mut inv = Invariants {
        non_finite: pixels.iter().filter(|p| !p.is_finite()).count(),
        reflected: pixels.iter().filter(|p| p.w > 0.0).count(),
        ..Default::default()
    };
    if plan.is_empty() {
        return inv;
    }
    for (i, &v) in intermediate.iter().take((w * h) as usize).enumerate() {
        let Some(d) = ppr_runtime::encoding::decode(v, &layout) else { continue };
        inv.written += 1;
        let c = glam::Vec2::new((i as u32 % w) as f32 + 0.5, (i as u32 / w) as f32 + 0.5);
        let s = c - d.whole_offset();
        let inside = s.x >= 0.0 && s.y >= 0.0 && s.x < w as f32 && s.y < h as f32;
        let ok = inside && {
            let j = (s.y as u32 * w + s.x as u32) as usize;
            let depth = frame.depth[j];
            depth.is_finite() && (0.0..=1.0).contains(&depth) && depth != far_depth(frame)
        };
        inv.bad_sources += usize::from(!ok);
    }
    inv
}

fn far_depth(frame: &Frame) -> f32 {
    frame.far_depth
}

/// Renders `scene` from `camera` and runs the runtime with full clears.
pub fn run_case(
    scene: &AnalyticScene,
    camera: &Camera,
    size: [u32; 2],
) -> (Frame, ppr_tests::harness::Output) {
    let frame = scene.render(camera, size);
    let gpu = ppr_tests::harness::GpuFrame::upload(&frame);
    let mut r = ppr_tests::harness::renderer();
    r.plan_params.indirect = ppr_runtime::Choice::Off;
    r.set_reflectors(&ppr_tests::harness::validated(&scene.reflector_set()));
    let out = ppr_tests::harness::run(&mut r, &gpu, camera);
    (frame, out)
}
