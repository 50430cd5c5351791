//! Cameras: grazing angles, on and below the plane, mirrored points behind the camera, a
//! reflector through the near plane, infinite far plane, reversed Z, 5° to 170° fields of
//! view, and viewports from 1×1 to 7680×4320. Stable: no NaN or infinity in the output,
//! every stored offset points at a rendered pixel inside the viewport, degenerate views
//! plan nothing; and every case holds an accuracy bound (`accuracy.rs`): the GPU stores
//! what the f64 CPU projection stores, and reflects a stated share of the exact
//! reflection's on-screen pixels with a stated PSNR, which an empty output fails.

use glam::{DVec3, DVec4, Vec3};
use ppr_format::ReflectorSet;
use ppr_runtime::{Camera, DepthMode, Projection};
use ppr_tests::scene::Frame;

use crate::accuracy::{Accuracy, Bounds, measure};
use crate::{floor_room, invariants, run_case};

const SIZE: [u32; 2] = [96, 64];

fn look(eye: DVec3, target: DVec3, projection: Projection) -> Camera {
    Camera::look_at(eye, target, Vec3::Y, projection)
}

/// The accuracy bounds of a case (docs/stability.md, "Cameras", says why): the GPU stores
/// the f64 CPU projection's source for at least 98% of its writes and writes at most 2% more
/// (none where it writes nothing); at least `covered` of the exact reflection's on-screen
/// pixels are reflected, with a PSNR of at least `psnr` dB over them (about 3 dB under
/// what llvmpipe gives today).
const fn bounds(covered: f64, psnr: f64) -> Bounds {
    Bounds { matched: 0.98, extra: 0.02, covered, psnr }
}

/// For frames where the f64 CPU projection writes nothing (the case asserts it): the GPU
/// must write nothing either.
const NOTHING_TO_WRITE: Bounds = bounds(0.0, f64::NEG_INFINITY);

/// What [`check`] measured.
struct Checked {
    /// Output pixels with a reflection.
    reflected: usize,
    accuracy: Accuracy,
    /// [`mirrored_behind_camera`].
    behind: usize,
}

/// Runs a case, checks the invariants and asserts `bounds` on its accuracy against the
/// f64 CPU projection and the exact reflection.
fn check(
    name: &str,
    scene: &ppr_tests::scene::AnalyticScene,
    camera: &Camera,
    size: [u32; 2],
    bounds: Bounds,
) -> Checked {
    let (frame, out) = run_case(scene, camera, size);
    let inv = invariants(&frame, &out.plan, &out.pixels, &out.intermediate);
    let set = scene.reflector_set();
    let cpu = ppr_tests::harness::cpu_projection(&frame, camera, &set);
    let a = measure(&frame, &cpu, &out.plan.encoding, &out.pixels, &out.intermediate);
    let behind = mirrored_behind_camera(&frame, camera, &set);
    assert_eq!(inv.non_finite, 0, "{name}: non-finite output");
    assert_eq!(inv.bad_sources, 0, "{name}: offsets pointing outside the rendered pixels");
    let empty = bounds.check(name, &frame, &cpu, &a);
    eprintln!(
        "{name}: {} visible, {} written, {} reflected; CPU reference {} written, {} matched ({:.1}%), {} extra; {} on-screen px, {} covered ({:.1}%), PSNR {:.1} dB (writing nothing: {:.1} dB); {} mirrored behind",
        out.plan.visible.len(),
        inv.written,
        inv.reflected,
        a.cpu_written,
        a.matched,
        100.0 * a.matched_share(),
        a.extra,
        a.on_screen,
        a.covered,
        100.0 * a.covered_share(),
        a.psnr,
        empty.psnr,
        behind,
    );
    Checked { reflected: inv.reflected, accuracy: a, behind }
}

/// Rendered pixels on a reflector's reflecting side whose mirrored point lies behind the
/// camera (clip w ≤ 0) although the line from the eye towards it crosses the reflector's
/// rectangle: the points a projection without the `w > 0` test would write garbage for
/// (f64, like `cpu_projection`).
fn mirrored_behind_camera(frame: &Frame, camera: &Camera, set: &ReflectorSet) -> usize {
    let [w, h] = frame.size;
    let clip_from_rel = camera.clip_from_relative(w as f32 / h as f32).as_dmat4();
    let rel_from_clip = clip_from_rel.inverse();
    let mut behind = 0;
    for (i, &depth) in frame.depth.iter().enumerate() {
        if depth == frame.far_depth {
            continue;
        }
        let (x, y) = ((i as u32 % w) as f64, (i as u32 / w) as f64);
        let ndc =
            DVec4::new((x + 0.5) / w as f64 * 2.0 - 1.0, 1.0 - (y + 0.5) / h as f64 * 2.0, depth.into(), 1.0);
        let hp = rel_from_clip * ndc;
        let p = hp.truncate() / hp.w;
        behind += set
            .reflectors
            .iter()
            .filter(|r| {
                let pd = (r.center - camera.position).dot(r.normal);
                let dist = p.dot(r.normal) - pd;
                let m = p - 2.0 * dist * r.normal;
                let l = m * (pd / m.dot(r.normal)) - (r.center - camera.position);
                dist > 1e-6 * p.length()
                    && (clip_from_rel * m.extend(1.0)).w <= 0.0
                    && l.dot(r.axis_u).abs() <= r.half_extents.x
                    && l.dot(r.axis_v).abs() <= r.half_extents.y
            })
            .count();
    }
    behind
}

#[test]
fn grazing_angles_down_to_a_hundredth_of_a_degree() {
    let scene = floor_room(60.0);
    // At 10° the reflection of the wall's top edge leaves a row of 12 pixels empty: their
    // reflected points lie in the last half pixel of the wall, in pixels whose centres see
    // the sky, so no pixel projects there (the CPU projection writes none either).
    for (degrees, b) in [
        (10.0, bounds(0.85, 12.5)),
        (1.0, bounds(0.95, 18.5)),
        (0.1, bounds(0.95, 29.0)),
        (0.01f64, bounds(0.95, 29.0)),
    ] {
        // Looking along the mirror 30 m ahead at `degrees` above the plane.
        let height = 30.0 * degrees.to_radians().tan();
        let camera = look(DVec3::new(0.0, height, 26.0), DVec3::new(0.0, 0.0, -4.0), Projection::default());
        check(&format!("grazing {degrees}°"), &scene, &camera, SIZE, b);
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
fn steep_views_mirrored_points_behind_the_camera_and_a_reflector_through_the_near_plane() {
    let scene = floor_room(8.0);
    // Looking steeply down: what the floor shows is above and behind the camera, off
    // screen; nothing is reflected. (A camera that faces the reflecting side never has a
    // mirrored point behind it: clip w grows by 2 · distance · |forward · normal|.)
    let down = look(DVec3::new(0.0, 1.0, -2.0), DVec3::new(0.0, 0.0, -2.5), Projection::default());
    let a = check("looking down", &scene, &down, SIZE, NOTHING_TO_WRITE).accuracy;
    assert_eq!(a.cpu_written, 0, "looking down: {a:?}");
    // Looking up with a wide field of view, the floor at the bottom rows: the walls above
    // the camera's height, near it, have mirrored points behind the camera (w ≤ 0) whose
    // line from the eye crosses the floor behind it; those must be skipped, the rest of the
    // reflection kept. At 150° the bottom rows magnify the reflection: the projection
    // leaves holes there that hole filling only partly closes.
    for (pitch, fov, b) in [(35.0f64, 90.0f32, bounds(0.95, 18.5)), (60.0, 150.0, bounds(0.85, 12.5))] {
        let name = format!("looking up {pitch}°, fov {fov}°");
        let up = look(
            DVec3::new(0.0, 1.0, 1.0),
            DVec3::new(0.0, 1.0 + pitch.to_radians().tan(), 0.0),
            Projection { fov_y: fov.to_radians(), ..Default::default() },
        );
        let behind = check(&name, &scene, &up, SIZE, b).behind;
        assert!(behind > 100, "{name}: the case must have mirrored points behind the camera: {behind}");
    }
    // Lower than the near distance: the floor crosses the near plane at the bottom rows.
    let near = Projection { near: 0.5, ..Default::default() };
    let low = look(DVec3::new(0.0, 0.2, 1.0), DVec3::new(0.0, 0.1, -4.0), near);
    check("reflector through the near plane", &scene, &low, SIZE, bounds(0.95, 29.0));
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
        let camera = look(eye, target, Projection { fov_y: 1.0, near: 0.1, far, depth, matrix: None });
        let c = check(name, &scene, &camera, SIZE, bounds(0.95, 22.0));
        results.push((name, c.reflected, c.accuracy.psnr));
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
    for (fov, b) in [
        (5.0f32, bounds(0.95, 38.5)),
        (30.0, bounds(0.95, 21.0)),
        (90.0, bounds(0.95, 23.0)),
        (150.0, bounds(0.95, 28.0)),
        (170.0, bounds(0.95, 29.0)),
    ] {
        let camera = look(
            DVec3::new(0.3, 1.6, 2.5),
            DVec3::new(-0.2, 0.6, -5.0),
            Projection { fov_y: fov.to_radians(), near: 0.05, ..Default::default() },
        );
        let reflected = check(&format!("fov {fov}°"), &scene, &camera, SIZE, b).reflected;
        assert!(reflected > 0, "fov {fov}: the floor mirror is in view");
    }
}

#[test]
fn tiny_and_odd_viewports() {
    let scene = floor_room(8.0);
    let camera = look(DVec3::new(0.3, 1.6, 2.5), DVec3::new(-0.2, 0.3, -5.0), Projection::default());
    // One-row frames: the exact reflection counts a pixel as on screen (its reflected
    // point lies inside the frustum), but no pixel centre sees that point, so there is
    // nothing to project (the CPU projection writes nothing).
    for (size, b) in [
        ([1, 1], NOTHING_TO_WRITE),
        ([3, 7], bounds(0.95, 10.5)),
        ([7, 3], bounds(0.95, 9.0)),
        ([17, 31], bounds(0.95, 22.5)),
        ([33, 1], NOTHING_TO_WRITE),
        ([1, 45], bounds(0.95, 30.0)),
        ([101, 67], bounds(0.95, 22.0)),
    ] {
        let a = check(&format!("{}x{}", size[0], size[1]), &scene, &camera, size, b).accuracy;
        if size[1] == 1 {
            assert_eq!(a.cpu_written, 0, "{size:?}: {a:?}");
        }
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
        Projection { fov_y: 1.6, near: 0.1, far: None, depth: DepthMode::Reversed, matrix: None },
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
