//! Cameras: grazing angles, on and below the plane, mirrored points behind the camera, a
//! reflector through the near plane, infinite far plane, reversed Z, 5° to 170° fields of
//! view, and viewports from 1×1 to 7680×4320. Stable: no NaN or infinity in the output,
//! every stored offset points at a rendered pixel inside the viewport, degenerate views
//! plan nothing; where reflections are on screen, they match the exact reflection.

use glam::{DVec3, Vec3};
use ppr_runtime::{Camera, DepthMode, Projection};
use ppr_tests::harness::compare;

use crate::{floor_room, invariants, run_case};

const SIZE: [u32; 2] = [96, 64];

fn look(eye: DVec3, target: DVec3, projection: Projection) -> Camera {
    Camera::look_at(eye, target, Vec3::Y, projection)
}

/// Runs a case and checks the invariants; returns (reflected pixels, PSNR on screen).
fn check(
    name: &str,
    scene: &ppr_tests::scene::AnalyticScene,
    camera: &Camera,
    size: [u32; 2],
) -> (usize, f64) {
    let (frame, out) = run_case(scene, camera, size);
    let inv = invariants(&frame, &out.plan, &out.pixels, &out.intermediate);
    let quality = compare(&frame, &out.pixels, |i| frame.on_screen[i]);
    eprintln!(
        "{name}: {} visible, {} written, {} reflected, {} on-screen px, PSNR {:.1} dB",
        out.plan.visible.len(),
        inv.written,
        inv.reflected,
        quality.pixels,
        quality.psnr
    );
    assert_eq!(inv.non_finite, 0, "{name}: non-finite output");
    assert_eq!(inv.bad_sources, 0, "{name}: offsets pointing outside the rendered pixels");
    (inv.reflected, if quality.pixels > 0 { quality.psnr } else { f64::INFINITY })
}

#[test]
fn grazing_angles_down_to_a_hundredth_of_a_degree() {
    let scene = floor_room(60.0);
    for degrees in [10.0, 1.0, 0.1, 0.01f64] {
        // Looking along the mirror 30 m ahead at `degrees` above the plane.
        let height = 30.0 * degrees.to_radians().tan();
        let camera = look(DVec3::new(0.0, height, 26.0), DVec3::new(0.0, 0.0, -4.0), Projection::default());
        check(&format!("grazing {degrees}°"), &scene, &camera, SIZE);
    }
}

#[test]
fn camera_on_and_below_the_plane_plans_nothing() {
    let scene = floor_room(8.0);
    for (name, y) in [("on the plane", 0.0), ("1 mm below", -1e-3), ("below", -1.0)] {
        let camera = look(DVec3::new(0.0, y, 3.0), DVec3::new(0.0, y + 0.5, -4.0), Projection::default());
        let (frame, out) = run_case(&scene, &camera, SIZE);
        assert!(out.plan.is_empty(), "{name}: {}", out.plan);
        assert_eq!(out.plan.culled_back_side, 1, "{name}");
        assert_eq!(invariants(&frame, &out.plan, &out.pixels, &out.intermediate).non_finite, 0);
    }
}

#[test]
fn mirrored_points_behind_the_camera_and_a_reflector_through_the_near_plane() {
    let scene = floor_room(8.0);
    // Looking steeply down: much of what the mirror would show is behind the camera.
    let down = look(DVec3::new(0.0, 1.0, -2.0), DVec3::new(0.0, 0.0, -2.5), Projection::default());
    check("looking down", &scene, &down, SIZE);
    // Lower than the near distance: the floor crosses the near plane at the bottom rows.
    let near = Projection { near: 0.5, ..Default::default() };
    let low = look(DVec3::new(0.0, 0.2, 1.0), DVec3::new(0.0, 0.1, -4.0), near);
    check("reflector through the near plane", &scene, &low, SIZE);
}

#[test]
fn infinite_far_plane_and_reversed_z_match_the_standard_projection() {
    let scene = floor_room(8.0);
    let eye = DVec3::new(0.3, 1.6, 2.5);
    let target = DVec3::new(-0.2, 0.6, -5.0);
    let mut results = Vec::new();
    for (name, far, depth) in [
        ("standard", Some(100.0), DepthMode::Standard),
        ("reversed", Some(100.0), DepthMode::Reversed),
        ("infinite", None, DepthMode::Standard),
        ("infinite reversed", None, DepthMode::Reversed),
    ] {
        let camera = look(eye, target, Projection { fov_y: 1.0, near: 0.1, far, depth });
        let (reflected, psnr) = check(name, &scene, &camera, SIZE);
        results.push((name, reflected, psnr));
    }
    let (_, base_reflected, base_psnr) = results[0];
    for (name, reflected, psnr) in &results[1..] {
        // The depth conventions store different depths, so positions differ in the last
        // bits; the reflection must stay as good and as complete.
        assert!(
            (*reflected as f64 - base_reflected as f64).abs() <= 0.01 * base_reflected as f64,
            "{name}: {reflected} vs {base_reflected}"
        );
        assert!(*psnr >= base_psnr - 1.0, "{name}: {psnr} vs {base_psnr}");
    }
}

#[test]
fn fields_of_view_from_5_to_170_degrees() {
    let scene = floor_room(8.0);
    for fov in [5.0f32, 30.0, 90.0, 150.0, 170.0] {
        let camera = look(
            DVec3::new(0.3, 1.6, 2.5),
            DVec3::new(-0.2, 0.6, -5.0),
            Projection { fov_y: fov.to_radians(), near: 0.05, ..Default::default() },
        );
        let (reflected, _) = check(&format!("fov {fov}°"), &scene, &camera, SIZE);
        assert!(reflected > 0, "fov {fov}: the floor mirror is in view");
    }
}

#[test]
fn tiny_and_odd_viewports() {
    let scene = floor_room(8.0);
    let camera = look(DVec3::new(0.3, 1.6, 2.5), DVec3::new(-0.2, 0.3, -5.0), Projection::default());
    for size in [[1, 1], [3, 7], [7, 3], [17, 31], [33, 1], [1, 45], [101, 67]] {
        check(&format!("{}x{}", size[0], size[1]), &scene, &camera, size);
    }
}

#[test]
fn an_8k_frame_stores_every_offset_the_cpu_reference_stores() {
    // The floor mirror seen by a camera rolled by 45°: the wall's reflection lies far away
    // along the screen's diagonal, so offsets have long major and minor components.
    // Reversed Z: at 8K the f32 position error of a standard-Z depth buffer is already
    // a pixel at a few metres (with standard Z this case loses 0.3% of the writes).
    let scene = floor_room(8.0);
    let camera = Camera::look_at(
        DVec3::new(0.0, 3.5, 3.0),
        DVec3::new(0.0, 0.0, -4.0),
        Vec3::new(1.0, 1.0, 0.0).normalize(),
        Projection { fov_y: 1.6, near: 0.1, far: None, depth: DepthMode::Reversed },
    );
    let size = [7680, 4320];
    let (frame, out) = run_case(&scene, &camera, size);
    let inv = invariants(&frame, &out.plan, &out.pixels, &out.intermediate);
    let cpu = ppr_tests::harness::cpu_projection(&frame, &camera, &scene.reflector_set());
    let layout = out.plan.encoding;
    let (mut stored, mut lost, mut far_apart, mut longest_minor, mut seed_cannot) =
        (0usize, 0usize, 0usize, 0.0f32, 0usize);
    for (&c, &g) in cpu.iter().zip(&out.intermediate) {
        let (Some(a), b) =
            (ppr_runtime::encoding::decode(c, &layout), ppr_runtime::encoding::decode(g, &layout))
        else {
            continue;
        };
        stored += 1;
        let o = a.whole_offset().abs();
        longest_minor = longest_minor.max(o.min_element());
        seed_cannot += usize::from(
            ppr_runtime::encoding::encode(a.offset(), &ppr_runtime::EncodingLayout::SEED)
                == ppr_runtime::CLEAR_VALUE,
        );
        match b {
            None => lost += 1,
            Some(b) => far_apart += usize::from((a.offset() - b.offset()).length() > 1.0),
        }
    }
    eprintln!(
        "7680x4320 (layout {:?}): {stored} offsets stored by the CPU reference, longest minor component {longest_minor} px ({seed_cannot} of them do not fit the seed's layout); GPU lost {lost}, {far_apart} differ by > 1 px",
        layout
    );
    assert_eq!(inv.non_finite, 0);
    assert_eq!(inv.bad_sources, 0);
    assert!(seed_cannot > 0, "the case must need more than the seed's ±2048 px minor range: {longest_minor}");
    assert!(lost as f64 <= 1e-3 * stored as f64, "{lost} of {stored}");
    assert!(far_apart as f64 <= 1e-2 * stored as f64, "{far_apart} of {stored}");
}
