//! One frame of an analytic mirror room through both builds: the wgpu-29 build's output is
//! the wgpu-30 build's, bit for bit, on the same software adapter.

use glam::{DVec3, Vec3};
use ppr_tests::harness::{GpuFrame, renderer, run};
use ppr_tests::scene::{Albedo, AnalyticScene};

use crate::gpu29::{Frame29, gpu29};

const SIZE: [u32; 2] = [160, 120];

fn room() -> AnalyticScene {
    let mut s = AnalyticScene::default();
    s.mirror("floor mirror", DVec3::new(0.0, 0.0, -4.0), DVec3::X, DVec3::NEG_Z, [4.0, 4.0]);
    s.quad(DVec3::new(0.0, 2.5, -8.0), DVec3::X, DVec3::Y, [6.0, 2.5], Albedo::Waves(0.25));
    for side in [-1.0, 1.0] {
        let albedo = Albedo::Gradient(Vec3::new(0.9, 0.6, 0.2), Vec3::new(0.2, 0.5, 0.9));
        s.quad(DVec3::new(4.5 * side, 2.5, -4.0), DVec3::Z, DVec3::Y, [6.0, 2.5], albedo);
    }
    s.cuboid(DVec3::new(-1.2, 0.0, -4.6), DVec3::new(-0.2, 1.0, -3.8), Vec3::new(0.9, 0.15, 0.1));
    s.cuboid(DVec3::new(1.4, 0.0, -3.0), DVec3::new(2.2, 0.6, -2.2), Vec3::new(0.9, 0.9, 0.2));
    s
}

/// The wgpu-30 build's camera, field by field, as the wgpu-29 build's type.
fn camera29(c: &ppr_runtime::Camera) -> ppr_runtime_wgpu29::Camera {
    let depth = match c.projection.depth {
        ppr_runtime::DepthMode::Standard => ppr_runtime_wgpu29::DepthMode::Standard,
        ppr_runtime::DepthMode::Reversed => ppr_runtime_wgpu29::DepthMode::Reversed,
    };
    let p = &c.projection;
    let projection =
        ppr_runtime_wgpu29::Projection { fov_y: p.fov_y, near: p.near, far: p.far, depth, matrix: p.matrix };
    ppr_runtime_wgpu29::Camera { position: c.position, rotation: c.rotation, projection }
}

#[test]
fn wgpu29_build_matches_the_wgpu30_build_bit_for_bit() {
    let scene = room();
    let set = ppr_format::ValidatedSet::new(scene.reflector_set()).expect("a valid set");
    let camera = ppr_runtime::Camera::look_at(
        DVec3::new(0.3, 1.6, 2.5),
        DVec3::new(-0.2, 0.6, -5.0),
        Vec3::Y,
        ppr_runtime::Projection {
            fov_y: 60f32.to_radians(),
            near: 0.1,
            far: Some(100.0),
            ..Default::default()
        },
    );
    let frame = scene.render(&camera, SIZE);

    let mut ppr30 = renderer();
    ppr30.set_reflectors(&set);
    let out30 = run(&mut ppr30, &GpuFrame::upload_raw_depth(&frame), &camera).pixels;
    drop(ppr30);

    let g = gpu29();
    eprintln!("wgpu 29 adapter: {}", g.adapter);
    let mut ppr29 = ppr_runtime_wgpu29::ReflectionRenderer::new(&g.device, &g.queue, &Default::default());
    ppr29.set_reflectors(&set);
    let plan = ppr29.prepare(&camera29(&camera), SIZE).clone();
    assert!(!plan.is_empty(), "the mirror floor must be visible");
    let f29 = Frame29::upload(g, &frame);
    let view = |t: &wgpu::Texture| t.create_view(&Default::default());
    let (color, depth, output) = (view(&f29.color), view(&f29.depth), view(&f29.output));
    let mut encoder = g.device.create_command_encoder(&Default::default());
    ppr29.encode(&mut encoder, &ppr_runtime_wgpu29::FrameInputs::new(&color, &depth, &output));
    g.queue.submit([encoder.finish()]);
    let out29 = f29.read_output(g);

    let found = out29.iter().filter(|p| p.w > 0.0).count();
    assert!(found > 2000, "the mirror floor must show reflections: {found} pixels");
    let differ = out29
        .iter()
        .zip(&out30)
        .filter(|(a, b)| a.to_array().map(f32::to_bits) != b.to_array().map(f32::to_bits))
        .count();
    assert_eq!(differ, 0, "{differ} of {} pixels differ between the wgpu 29 and 30 builds", out29.len());
}
