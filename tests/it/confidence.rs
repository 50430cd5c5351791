//! The output's alpha as a confidence a renderer can blend with: 1 where the reflection was
//! found well inside the screen, fading to 0 as the reflected point nears a screen border,
//! 0 where there is no data.

use glam::{DVec3, Vec3, Vec4};
use ppr_runtime::{Camera, Choice, Projection};

use ppr_tests::harness::{GpuFrame, renderer, run};
use ppr_tests::scene::{Albedo, AnalyticScene, Frame};

const SIZE: [u32; 2] = [160, 120];

/// A floor mirror in front of a tall wall whose top is above the screen: the mirror's near
/// rows reflect points above the top border (no data), the rows above them points just
/// below it.
fn wall_and_mirror() -> (AnalyticScene, Camera) {
    let mut s = AnalyticScene::default();
    s.quad(
        DVec3::new(0.0, -0.001, -4.0),
        DVec3::X,
        DVec3::NEG_Z,
        [8.0, 8.0],
        Albedo::Solid(Vec3::splat(0.25)),
    );
    s.quad(DVec3::new(0.0, 4.0, -7.0), DVec3::X, DVec3::Y, [6.0, 4.0], Albedo::Waves(0.3));
    s.mirror("floor mirror", DVec3::new(0.0, 0.0, -3.0), DVec3::X, DVec3::NEG_Z, [3.0, 3.0]);
    let camera = Camera::look_at(
        DVec3::new(0.0, 1.2, 1.5),
        DVec3::new(0.0, 0.0, -4.0),
        Vec3::Y,
        Projection::default(),
    );
    (s, camera)
}

/// Whether pixel `i` and its hole-filling neighbours (the seed's four, then the second
/// ring: the pixel above and those two away) hold no intermediate value.
fn no_data(frame: &Frame, intermediate: &[u32], i: usize) -> bool {
    let [w, h] = frame.size.map(|v| v as i32);
    let (x, y) = (i as i32 % w, i as i32 / w);
    [(0, 0), (1, 0), (0, 1), (1, 1), (-1, 0), (0, -1), (2, 0), (0, 2), (-2, 0)].iter().all(|(dx, dy)| {
        let (nx, ny) = (x + dx, y + dy);
        nx < 0
            || ny < 0
            || nx >= w
            || ny >= h
            || intermediate[(ny * w + nx) as usize] == ppr_runtime::CLEAR_VALUE
    })
}

#[test]
fn alpha_is_one_inside_fades_towards_the_border_and_is_zero_without_data() {
    let (scene, camera) = wall_and_mirror();
    let frame = scene.render(&camera, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let mut r = renderer();
    r.plan_params.indirect = Choice::Off;
    // A tenth of the shorter side (the default is off).
    r.settings.border_fade = 0.1;
    r.set_reflectors(&ppr_tests::harness::validated(&scene.reflector_set()));
    let out = run(&mut r, &gpu, &camera);
    let [w, h] = SIZE;
    let alpha = |x: u32, y: u32| out.pixels[(y * w + x) as usize].w;

    // No data: alpha exactly 0 (and no colour).
    let without =
        (0..out.pixels.len()).filter(|&i| no_data(&frame, &out.intermediate, i)).collect::<Vec<_>>();
    assert!(without.iter().all(|&i| out.pixels[i] == Vec4::ZERO), "a pixel without data has alpha or colour");
    let mirror_without = without.iter().filter(|&&i| frame.mirror[i].is_some()).count();
    assert!(mirror_without > 200, "the near rows reflect points above the screen: {mirror_without}");

    // Interior: sources at least a quarter of the screen from every border are fully trusted.
    let far_from_border = |i: usize| {
        let s = frame.source_px[i];
        let d = s.x.min(s.y).min(w as f32 - s.x).min(h as f32 - s.y);
        frame.on_screen[i] && d > 0.25 * h as f32
    };
    let interior: Vec<usize> =
        (0..out.pixels.len()).filter(|&i| far_from_border(i) && out.pixels[i].w > 0.0).collect();
    let below_one = interior.iter().filter(|&&i| out.pixels[i].w < 1.0).count();
    assert!(interior.len() > 1000, "{}", interior.len());
    assert_eq!(below_one, 0, "{below_one} of {} interior pixels are not fully trusted", interior.len());

    // Down each middle column, the reflected point climbs to the top border and beyond:
    // from the first fully trusted pixel on, alpha must fall monotonically to 0 over the
    // fade, not jump.
    let (mut faded, mut columns, mut worst_rise) = (0usize, 0usize, 0.0f32);
    for x in w * 2 / 5..w * 3 / 5 {
        let rows: Vec<u32> = (0..h).filter(|&y| frame.mirror[(y * w + x) as usize].is_some()).collect();
        let column: Vec<f32> = rows.iter().map(|&y| alpha(x, y)).collect();
        let trusted = column.iter().position(|&a| a == 1.0);
        assert!(trusted.is_some(), "column {x} has trusted pixels: {column:?}");
        assert!(column.last().is_some_and(|&a| a == 0.0), "column {x} ends without data: {column:?}");
        let down = &column[trusted.unwrap_or(0)..];
        for pair in down.windows(2) {
            worst_rise = worst_rise.max(pair[1] - pair[0]);
        }
        faded += down.iter().filter(|&&a| a > 0.0 && a < 1.0).count();
        columns += 1;
    }
    eprintln!("{columns} columns: {faded} pixels partly trusted; largest rise going down {worst_rise}");
    assert!(faded >= 3 * columns, "the fade spans several pixels per column: {faded}");
    assert!(worst_rise <= 0.02, "alpha rises towards the border by {worst_rise}");
}

#[test]
fn the_fade_width_is_a_setting_and_found_pixels_stay_found() {
    let (scene, camera) = wall_and_mirror();
    let frame = scene.render(&camera, SIZE);
    let gpu = GpuFrame::upload(&frame);
    let run_with = |border_fade: f32| {
        let mut r = renderer();
        r.plan_params.indirect = Choice::Off;
        r.settings.border_fade = border_fade;
        r.set_reflectors(&ppr_tests::harness::validated(&scene.reflector_set()));
        run(&mut r, &gpu, &camera).pixels
    };
    let off = run_with(0.0);
    // Without a fade, alpha says "found" and nothing else: the seed's output.
    assert!(off.iter().all(|p| p.w == 0.0 || p.w == 1.0), "alpha is 0 or 1 without a fade");
    let found = off.iter().filter(|p| p.w > 0.0).count();
    assert!(found > 2000, "{found}");
    let mut partly = Vec::new();
    for fade in [0.05, 0.1, 0.3] {
        let px = run_with(fade);
        // Whatever the width, the found pixels (alpha > 0) and the colours are the same.
        let changed = (0..px.len()).filter(|&i| (px[i].w > 0.0) != (off[i].w > 0.0)).count();
        let recoloured = (0..px.len()).filter(|&i| px[i].truncate() != off[i].truncate()).count();
        assert_eq!((changed, recoloured), (0, 0), "border_fade {fade}");
        assert!(px.iter().all(|p| (0.0..=1.0).contains(&p.w)), "alpha in [0, 1]");
        partly.push(px.iter().filter(|p| p.w > 0.0 && p.w < 1.0).count());
    }
    eprintln!("{found} found; partly trusted with border_fade 0.05, 0.1, 0.3: {partly:?}");
    assert!(partly[0] > 0 && partly[0] < partly[1] && partly[1] < partly[2], "{partly:?}");
}
