//! The runtime against the exact reflection of an analytic scene: quality over on-screen
//! pixels, and each artefact of the talk reproduced with its step off and fixed with it on.

use glam::{DVec3, Vec3};
use ppr_runtime::{CLEAR_VALUE, Camera, Projection, ReflectionSettings, WriteMode};

use ppr_tests::harness::{GpuFrame, compare, renderer, run};
use ppr_tests::masks::{interior, reference_edges};
use ppr_tests::scene::{Albedo, AnalyticScene, Frame};

/// 160 × 120: small enough for llvmpipe, large enough for stretching and squeezing.
pub const SIZE: [u32; 2] = [160, 120];

/// A room with a mirror floor, a wavy back wall, gradient side walls (or high-contrast
/// stripes), a red box (the "flowerpot") in front of a green pillar, and a yellow box.
pub fn mirror_room(stripes: bool) -> AnalyticScene {
    let mut s = AnalyticScene::default();
    s.mirror("floor mirror", DVec3::new(0.0, 0.0, -4.0), DVec3::X, DVec3::NEG_Z, [4.0, 4.0]);
    // Floor around the mirror, just below it.
    s.quad(
        DVec3::new(0.0, -0.001, -4.0),
        DVec3::X,
        DVec3::NEG_Z,
        [8.0, 8.0],
        Albedo::Solid(Vec3::splat(0.25)),
    );
    s.quad(DVec3::new(0.0, 2.5, -8.0), DVec3::X, DVec3::Y, [6.0, 2.5], Albedo::Waves(0.25));
    for side in [-1.0, 1.0] {
        let albedo = if stripes {
            Albedo::Stripes(Vec3::new(0.95, 0.95, 0.9), Vec3::new(0.05, 0.08, 0.1), 1.0 / 12.0)
        } else {
            Albedo::Gradient(Vec3::new(0.9, 0.6, 0.2), Vec3::new(0.2, 0.5, 0.9))
        };
        s.quad(DVec3::new(4.5 * side, 2.5, -4.0), DVec3::Z, DVec3::Y, [6.0, 2.5], albedo);
    }
    s.cuboid(DVec3::new(-1.2, 0.0, -4.6), DVec3::new(-0.2, 1.0, -3.8), Vec3::new(0.9, 0.15, 0.1));
    s.cuboid(DVec3::new(-0.9, 0.0, -6.6), DVec3::new(-0.3, 2.4, -6.0), Vec3::new(0.1, 0.8, 0.2));
    s.cuboid(DVec3::new(1.4, 0.0, -3.0), DVec3::new(2.2, 0.6, -2.2), Vec3::new(0.9, 0.9, 0.2));
    s
}

pub fn room_camera() -> Camera {
    Camera::look_at(
        DVec3::new(0.3, 1.6, 2.5),
        DVec3::new(-0.2, 0.6, -5.0),
        Vec3::Y,
        Projection { fov_y: 60f32.to_radians(), near: 0.1, far: Some(100.0), ..Default::default() },
    )
}

struct Case {
    frame: Frame,
    gpu: GpuFrame,
    camera: Camera,
    set: ppr_format::ReflectorSet,
}

fn room_case() -> Case {
    room_case_with(false)
}

fn room_case_with(stripes: bool) -> Case {
    let scene = mirror_room(stripes);
    let camera = room_camera();
    let frame = scene.render(&camera, SIZE);
    let gpu = GpuFrame::upload(&frame);
    Case { frame, gpu, camera, set: scene.reflector_set() }
}

fn render(case: &Case, settings: ReflectionSettings, mode: WriteMode) -> ppr_tests::harness::Output {
    render_with(case, settings, |r| r.debug.write_mode = mode)
}

/// [`render`] with the renderer configured by `configure` (plan parameters, debug options)
/// before its reflectors are set.
fn render_with(
    case: &Case,
    settings: ReflectionSettings,
    configure: impl FnOnce(&mut ppr_runtime::ReflectionRenderer),
) -> ppr_tests::harness::Output {
    let mut r = renderer();
    // Full clears, so that the whole intermediate buffer can be compared.
    r.plan_params.indirect = ppr_runtime::Choice::Off;
    configure(&mut r);
    r.set_reflectors(&ppr_tests::harness::validated(&case.set));
    r.settings = settings;
    run(&mut r, &case.gpu, &case.camera)
}

const HOLES_ONLY: ReflectionSettings =
    ReflectionSettings { holes: true, filtering: false, anti_bleeding: false, ..ReflectionSettings::ALL };
const FILTERED: ReflectionSettings =
    ReflectionSettings { holes: true, filtering: true, anti_bleeding: false, ..ReflectionSettings::ALL };

#[test]
fn reflection_matches_the_exact_reference_on_screen() {
    let case = room_case();
    assert!(
        case.frame.on_screen_count() > 2000,
        "scene has {} on-screen pixels",
        case.frame.on_screen_count()
    );
    let out = render(&case, HOLES_ONLY, WriteMode::AtomicMin);
    assert_eq!(out.plan.visible.len(), 1, "{}", out.plan);
    let all = compare(&case.frame, &out.pixels, |i| case.frame.on_screen[i]);
    // Away from silhouettes: on-screen pixels whose reference has no edge within one pixel.
    let edges = reference_edges(&case.frame, 0.15);
    let smooth = interior(&case.frame, 1, |i| case.frame.on_screen[i] && !edges[i]);
    let away = compare(&case.frame, &out.pixels, |i| smooth[i]);
    eprintln!("holes on, filtering off: all on-screen {all:?}\n  away from silhouettes {away:?}");
    ppr_tests::harness::save_comparison(
        env!("CARGO_TARGET_TMPDIR"),
        "mirror_room_holes_unfiltered",
        &case.frame,
        &out.pixels,
        |i| case.frame.on_screen[i],
    );
    // Issue 4 asks for 35 dB. It holds away from silhouettes. At a silhouette the nearest
    // colour-buffer pixel can lie on the other side of the edge (any screen-space method
    // shares this), which costs about 10 dB over all on-screen pixels of this scene.
    assert!(away.pixels * 2 > all.pixels, "most on-screen pixels are away from edges: {away:?} of {all:?}");
    assert!(away.psnr >= 35.0, "{away:?}");
    assert!(all.psnr >= 22.0, "{all:?}");
    assert!(all.empty * 1000 <= all.pixels, "{all:?}");
}

#[test]
fn write_order_atomic_min_keeps_the_closest_surface() {
    let case = room_case();
    let on_screen = |i: usize| case.frame.on_screen[i];
    let min = compare(&case.frame, &render(&case, HOLES_ONLY, WriteMode::AtomicMin).pixels, on_screen);
    let max = compare(&case.frame, &render(&case, HOLES_ONLY, WriteMode::AtomicMax).pixels, on_screen);
    let last = compare(&case.frame, &render(&case, HOLES_ONLY, WriteMode::LastWriter).pixels, on_screen);
    eprintln!("write order: atomicMin {min:?}\n  last writer {last:?}\n  atomicMax (worst order) {max:?}");
    // The flowerpot artefact: pixels showing a farther surface than the reference.
    assert!(max.wrong > 3 * min.wrong.max(20), "{max:?} vs {min:?}");
    assert!(max.psnr + 3.0 < min.psnr, "{max:?} vs {min:?}");
    assert!(last.wrong >= min.wrong, "last-writer cannot beat atomicMin: {last:?} vs {min:?}");
}

#[test]
fn hole_filling_fills_the_stretched_reflection() {
    let case = room_case();
    let on_screen = |i: usize| case.frame.on_screen[i];
    let raw =
        compare(&case.frame, &render(&case, ReflectionSettings::RAW, WriteMode::AtomicMin).pixels, on_screen);
    let filled = compare(&case.frame, &render(&case, HOLES_ONLY, WriteMode::AtomicMin).pixels, on_screen);
    eprintln!("holes: raw {} empty of {} -> filled {} empty", raw.empty, raw.pixels, filled.empty);
    assert!(raw.empty * 100 > raw.pixels, "the raw reflection must have holes (> 1%): {raw:?}");
    assert!(filled.empty * 10 < raw.empty, "filling must remove at least 90% of them: {raw:?} -> {filled:?}");
}

/// Whether the hole filling finds a value for pixel (x, y) of `intermediate`: its own, else
/// the first ring's (PPR_HOLE_OFFSETS of shading.wgsl), else the second's; outside the
/// viewport reads as no data. Also whether the value came from a ring.
fn cpu_hole_choice(intermediate: &[u32], [w, h]: [u32; 2], x: i32, y: i32) -> (bool, bool) {
    let get = |dx: i32, dy: i32| {
        let (px, py) = (x + dx, y + dy);
        if px < 0 || py < 0 || px >= w as i32 || py >= h as i32 {
            CLEAR_VALUE
        } else {
            intermediate[(px + py * w as i32) as usize]
        }
    };
    if get(0, 0) != CLEAR_VALUE {
        return (true, false);
    }
    let ring1 = [(1, 0), (0, 1), (1, 1), (-1, 0)];
    let ring2 = [(0, -1), (2, 0), (0, 2), (-2, 0)];
    let found = ring1.iter().chain(&ring2).any(|&(dx, dy)| get(dx, dy) != CLEAR_VALUE);
    (found, found)
}

#[test]
fn hole_filling_reads_neighbours_across_tile_borders() {
    // The reflection pass reads each 16x16 tile's values with a two-pixel apron into
    // workgroup memory: a pixel at a tile border must see its neighbours in the next tile
    // exactly as the buffer holds them.
    let case = room_case();
    let out = render(&case, HOLES_ONLY, WriteMode::AtomicMin);
    let [w, h] = SIZE;
    let (mut mismatches, mut filled, mut filled_at_borders) = (0, 0, 0);
    for y in 0..h as i32 {
        for x in 0..w as i32 {
            let (found, from_ring) = cpu_hole_choice(&out.intermediate, SIZE, x, y);
            let shown = out.pixels[(x + y * w as i32) as usize].w > 0.0;
            mismatches += usize::from(found != shown);
            if from_ring && shown {
                filled += 1;
                let border = |c: i32| c % 16 <= 1 || c % 16 >= 14;
                filled_at_borders += usize::from(border(x) || border(y));
            }
        }
    }
    eprintln!("hole filling: {filled} filled pixels, {filled_at_borders} of them at tile borders");
    assert_eq!(mismatches, 0, "pixels where the GPU's hole filling disagrees with the CPU model");
    assert!(filled_at_borders > 20, "the case must fill holes at tile borders: {filled_at_borders}");
}

#[test]
fn filtering_reduces_distortion() {
    let case = room_case();
    // Distortion shows on the smooth back wall; keep pixels whose reference and whose
    // neighbours' references come from it (away from silhouettes, where filtering bleeds).
    let wall =
        interior(&case.frame, 2, |i| case.frame.on_screen[i] && is_back_wall_colour(case.frame.reference[i]));
    let smooth = |i: usize| wall[i];
    let unfiltered = compare(&case.frame, &render(&case, HOLES_ONLY, WriteMode::AtomicMin).pixels, smooth);
    let filtered = compare(&case.frame, &render(&case, FILTERED, WriteMode::AtomicMin).pixels, smooth);
    eprintln!("distortion on the gradient wall: unfiltered {unfiltered:?}\n  filtered {filtered:?}");
    assert!(unfiltered.pixels > 500, "{unfiltered:?}");
    assert!(filtered.mean_abs < 0.9 * unfiltered.mean_abs, "{unfiltered:?} -> {filtered:?}");
}

#[test]
fn anti_bleeding_reduces_error_at_high_contrast_edges() {
    let case = room_case_with(true);
    let edges = high_contrast_edges(&case.frame);
    let mask = |i: usize| edges[i];
    let filtered = compare(&case.frame, &render(&case, FILTERED, WriteMode::AtomicMin).pixels, mask);
    let fixed =
        compare(&case.frame, &render(&case, ReflectionSettings::ALL, WriteMode::AtomicMin).pixels, mask);
    eprintln!(
        "bleeding at {} edge pixels: filtered {filtered:?}\n  anti-bleeding {fixed:?}",
        filtered.pixels
    );
    assert!(filtered.pixels > 100, "{filtered:?}");
    assert!(fixed.mean_abs < 0.9 * filtered.mean_abs, "{filtered:?} -> {fixed:?}");
}

/// The gradient wall's colours have blue and red both well above the stripes' grey.
fn is_back_wall_colour(c: Vec3) -> bool {
    (c.x - c.z).abs() > 0.05 && c.y > 0.3 && c.y < 0.65
}

/// On-screen mirror pixels whose reference differs strongly from a 4-neighbour's.
fn high_contrast_edges(f: &Frame) -> Vec<bool> {
    let [w, h] = f.size;
    let mut edges = vec![false; f.reference.len()];
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let i = (y * w + x) as usize;
            if !f.on_screen[i] {
                continue;
            }
            let c = f.reference[i];
            edges[i] = [i - 1, i + 1, i - w as usize, i + w as usize]
                .iter()
                .any(|&j| f.on_screen[j] && (f.reference[j] - c).abs().max_element() > 0.5);
        }
    }
    edges
}

/// Values equal to the CPU reference's, and values whose decoded offsets differ by more
/// than a pixel (f32 on the GPU, f64 on the CPU), over the whole buffer.
fn agreement(cpu: &[u32], gpu: &[u32]) -> (usize, usize) {
    let same = cpu.iter().zip(gpu).filter(|(a, b)| a == b).count();
    let layout = ppr_runtime::EncodingLayout::for_resolution(SIZE[0], SIZE[1]);
    let far_apart = cpu
        .iter()
        .zip(gpu)
        .filter(|(a, b)| {
            let (a, b) =
                (ppr_runtime::encoding::decode(**a, &layout), ppr_runtime::encoding::decode(**b, &layout));
            match (a, b) {
                (Some(a), Some(b)) => (a.offset() - b.offset()).length() > 1.0,
                (None, None) => false,
                _ => true,
            }
        })
        .count();
    (same, far_apart)
}

#[test]
fn projection_matches_the_cpu_reference() {
    let case = room_case();
    let out = render(&case, HOLES_ONLY, WriteMode::AtomicMin);
    let cpu = ppr_tests::harness::cpu_projection(&case.frame, &case.camera, &case.set);
    let written = cpu.iter().filter(|&&v| v != ppr_runtime::CLEAR_VALUE).count();
    let (same, far_apart) = agreement(&cpu, &out.intermediate);
    eprintln!(
        "projection: {written} pixels written by the CPU reference; {same} of {} values identical; {far_apart} differ by more than a pixel",
        cpu.len()
    );
    assert!(written > 4000, "{written}");
    assert!(same as f64 >= 0.97 * cpu.len() as f64, "{same} of {}", cpu.len());
    assert!(far_apart as f64 <= 0.01 * written as f64, "{far_apart} of {written}");
}

#[test]
fn projection_honours_occluder_lists() {
    // A panel floating between the camera and part of the mirror floor, facing down (the
    // camera sees its back: nothing reflects in it), listed as the floor's occluder: the
    // floor's reflections seen through it are not written.
    let mut case = room_case();
    let id = case.set.next_id();
    case.set.reflectors.push(ppr_format::Reflector::new(
        id,
        "occluder",
        ppr_format::ReflectorKind::Opaque,
        DVec3::new(0.3, 0.4, -2.5),
        DVec3::NEG_Y,
        DVec3::X,
        glam::DVec2::new(1.2, 1.0),
    ));
    case.set.reflectors[0].occluders = vec![1];
    case.set.assign_parallel_groups();
    // Occluder lists are off by default (the depth test catches every occluder).
    let out = render_with(&case, HOLES_ONLY, |r| r.plan_params.occluder_lists = ppr_runtime::Choice::On);
    assert!(out.plan.occluder_tests, "the plan runs the occluder tests: {}", out.plan);
    let cpu = ppr_tests::harness::cpu_projection(&case.frame, &case.camera, &case.set);
    let mut open = case.set.clone();
    open.reflectors[0].occluders.clear();
    let cpu_open = ppr_tests::harness::cpu_projection(&case.frame, &case.camera, &open);
    let blocked = cpu.iter().zip(&cpu_open).filter(|(a, b)| a != b).count();
    let written = cpu.iter().filter(|&&v| v != ppr_runtime::CLEAR_VALUE).count();
    let (same, far_apart) = agreement(&cpu, &out.intermediate);
    let (same_open, _) = agreement(&cpu_open, &out.intermediate);
    eprintln!(
        "occluded projection: {blocked} values blocked by the occluder, {written} written; {same} of {} identical to the reference ({same_open} to the one without occluders); {far_apart} differ by more than a pixel",
        cpu.len()
    );
    assert!(blocked > 300, "the occluder blocks part of the floor's reflection: {blocked}");
    assert!(same as f64 >= 0.97 * cpu.len() as f64, "{same} of {}", cpu.len());
    assert!(same >= same_open + blocked / 2, "{same} against {same_open} without occluders");
    assert!(far_apart as f64 <= 0.01 * written as f64, "{far_apart} of {written}");
}

#[test]
fn decoded_fractions_point_closer_to_the_exact_source() {
    // The mirrored fractions exist to find the reflected pixel's true (sub-pixel) position:
    // with them the estimate must be closer than with the whole offset alone.
    let case = room_case();
    let out = render(&case, HOLES_ONLY, WriteMode::AtomicMin);
    let layout = ppr_runtime::EncodingLayout::for_resolution(SIZE[0], SIZE[1]);
    let (mut whole, mut with_fract, mut n) = (0.0f64, 0.0f64, 0);
    for (i, &v) in out.intermediate.iter().enumerate().take(case.frame.on_screen.len()) {
        let Some(d) = ppr_runtime::encoding::decode(v, &layout) else { continue };
        if !case.frame.on_screen[i] {
            continue;
        }
        let c = glam::Vec2::new((i as u32 % SIZE[0]) as f32 + 0.5, (i as u32 / SIZE[0]) as f32 + 0.5);
        let exact = case.frame.source_px[i];
        whole += f64::from((c - d.whole_offset() - exact).length());
        with_fract += f64::from((c - d.offset() - exact).length());
        n += 1;
    }
    let (whole, with_fract) = (whole / n as f64, with_fract / n as f64);
    eprintln!(
        "mean distance to the exact source over {n} pixels: whole offset {whole:.3} px, with fractions {with_fract:.3} px"
    );
    assert!(n > 4000 && with_fract < 0.8 * whole, "{whole} -> {with_fract}");
}

#[test]
fn anti_bleeding_decides_the_same_at_any_exposure() {
    // HDR input: the same frame with its colour scaled by a large and a small factor must
    // give the same reflection (divided by the factor) and the same validity. Absolute
    // luma thresholds saturate on the bright frame (every pixel unfiltered) and do nothing
    // on the dark one (every pixel filtered).
    let scene = mirror_room(true);
    let camera = room_camera();
    let frame = scene.render(&camera, SIZE);
    let set = scene.reflector_set();
    let run_scaled = |k: f32| {
        let mut f = frame.clone_images();
        for c in &mut f.color {
            *c *= k;
        }
        let mut r = renderer();
        r.plan_params.indirect = ppr_runtime::Choice::Off;
        r.set_reflectors(&ppr_tests::harness::validated(&set));
        r.settings = ReflectionSettings::ALL;
        run(&mut r, &GpuFrame::upload(&f), &camera).pixels
    };
    let base = run_scaled(1.0);
    let reflected = base.iter().filter(|p| p.w > 0.0).count();
    assert!(reflected > 4000, "{reflected}");
    // Tolerance: the input is stored as f16 (relative rounding 2^-11 ≈ 5e-4, more for the
    // darkest colours at 1/1000, which are f16 subnormals), and the anti-bleeding weights
    // move with it; 1 % of the colour (plus 1e-3 absolute) bounds what rounding can do,
    // while a changed decision at an edge of the stripes moves a colour by up to 0.9.
    const RELATIVE: f32 = 0.01;
    const ABSOLUTE: f32 = 1e-3;
    for k in [1000.0f32, 0.001] {
        let scaled = run_scaled(k);
        let (mut off, mut validity, mut worst) = (0usize, 0usize, 0.0f32);
        for (a, b) in scaled.iter().zip(&base) {
            validity += usize::from(a.w != b.w);
            let d = (a.truncate() / k - b.truncate()).abs().max_element();
            let bound = RELATIVE * b.truncate().abs().max_element() + ABSOLUTE;
            off += usize::from(d > bound);
            worst = worst.max(d);
        }
        eprintln!(
            "colour x{k}: {off} pixels off by more than 1% + 1e-3 (worst {worst}), {validity} with another validity"
        );
        assert_eq!(validity, 0, "x{k}");
        assert_eq!(off, 0, "x{k}: worst difference {worst}");
    }
}

#[test]
fn a_far_mirror_under_standard_z_never_reflects_itself() {
    // Issue 14, item 3: with standard Z the depth buffer's resolution falls with distance
    // squared; 400 m away a depth step spans decimetres, more than a tolerance relative to
    // distance (1e-4 of it), so the mirror's own pixels came out in front of its plane and
    // were mirrored onto themselves (an offset near zero, which atomicMin always keeps).
    // The on-plane tolerance now follows the depth buffer's precision: an empty mirror
    // reflects nothing of itself.
    let mut s = AnalyticScene::default();
    s.mirror("far floor", DVec3::new(0.0, 0.0, -300.0), DVec3::X, DVec3::NEG_Z, [400.0, 400.0]);
    let camera = Camera::look_at(
        DVec3::new(0.0, 280.0, 0.0),
        DVec3::new(0.0, 0.0, -280.0),
        Vec3::Y,
        Projection { near: 0.05, far: Some(1000.0), ..Projection::default() },
    );
    let frame = s.render(&camera, SIZE);
    let on_mirror = frame.depth.iter().filter(|&&d| d < 1.0).count();
    let gpu = GpuFrame::upload(&frame);
    assert!(on_mirror > (SIZE[0] * SIZE[1]) as usize / 2, "the mirror fills the view: {on_mirror}");
    // With and without the depth-occlusion test (which also refuses a write onto a pixel
    // in front of the plane): the tolerance alone must hold.
    for occlusion in [ppr_runtime::Choice::Off, ppr_runtime::Choice::On] {
        let mut r = renderer();
        r.settings = ReflectionSettings::RAW;
        r.plan_params.depth_occlusion = occlusion;
        r.set_reflectors(&ppr_tests::harness::validated(&s.reflector_set()));
        let out = run(&mut r, &gpu, &camera);
        let written = out.intermediate.iter().filter(|&&v| v != ppr_runtime::CLEAR_VALUE).count();
        eprintln!("occlusion {occlusion:?}: {on_mirror} mirror pixels, {written} written");
        assert_eq!(written, 0, "the mirror reflected itself (occlusion {occlusion:?})");
    }
}
