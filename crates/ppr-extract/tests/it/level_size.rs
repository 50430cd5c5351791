//! Physical units: the same room gives the same rectangles alone, inside a level with
//! distant geometry, and as many copies; occluders are found however far they are; the
//! output does not depend on the thread count.

use glam::{DQuat, DVec2, DVec3};
use ppr_extract::generated_levels::{RoomSpec, copies, level_of, quad, room_triangles};
use ppr_extract::{ExtractParams, Extraction, extract};

use crate::checks::assert_encloses_regions;

/// (centre, half extents, normal) of every rectangle, translated by `-offset`, sorted.
fn rectangles(x: &Extraction, keep: impl Fn(DVec3) -> bool, offset: DVec3) -> Vec<(DVec3, DVec2, DVec3)> {
    let mut v: Vec<(DVec3, DVec2, DVec3)> = x
        .set
        .reflectors
        .iter()
        .filter(|r| keep(r.center))
        .map(|r| (r.center - offset, r.half_extents, r.normal))
        .collect();
    v.sort_by(|a, b| a.0.to_array().partial_cmp(&b.0.to_array()).unwrap_or(std::cmp::Ordering::Equal));
    v
}

fn assert_same(a: &[(DVec3, DVec2, DVec3)], b: &[(DVec3, DVec2, DVec3)], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: {} rectangles, alone {}", b.len(), a.len());
    for (p, q) in a.iter().zip(b) {
        assert!(
            (p.0 - q.0).length() < 1e-6
                && (p.1 - q.1).abs().max_element() < 1e-6
                && p.2.dot(q.2) > 1.0 - 1e-9,
            "{what}: {p:?} vs alone {q:?}"
        );
    }
}

#[test]
fn the_same_room_gives_the_same_rectangles_at_any_level_size() {
    let spec = RoomSpec { cells_per_m: 2.0, ..RoomSpec::default() };
    let room = room_triangles(&spec, DVec3::ZERO);
    let inside = |c: DVec3| c.x > -1.0 && c.x < 7.0 && c.z > -1.0 && c.z < 6.0 && c.y < 4.0;
    for params in [ExtractParams::all_planar(), ExtractParams::default()] {
        let alone = extract(&level_of("room", &room), &params, &|_, _| {});
        assert_encloses_regions(&alone, 3.0 * params.distance_tolerance_m, "room alone");
        let want = rectangles(&alone, |_| true, DVec3::ZERO);
        assert!(want.len() >= 10, "the room has floor, ceiling, walls, furniture: {}", want.len());

        // The room with a 200 m square ground 400 m away (the level's diagonal grows 100×).
        let mut tris = room.clone();
        quad(
            &mut tris,
            DVec3::new(400.0, -5.0, 400.0),
            [DVec3::Z, DVec3::X],
            [200.0, 200.0],
            0.05,
            &|_, _| true,
        );
        let x = extract(&level_of("far", &tris), &params, &|_, _| {});
        assert!(x.stats.diagonal > 500.0);
        assert_same(&rectangles(&x, inside, DVec3::ZERO), &want, "with distant ground");

        // Twelve copies 20 m apart.
        let level = copies(&level_of("room", &room), 12, 20.0);
        let x = extract(&level, &params, &|_, _| {});
        assert_eq!(x.set.reflectors.len(), 12 * want.len());
        for k in 0..12 {
            let offset = DVec3::X * (20.0 * k as f64);
            let got = rectangles(&x, |c| inside(c - offset), offset);
            assert_same(&got, &want, &format!("copy {k}"));
        }
    }
}

#[test]
fn a_far_occluder_is_listed() {
    // A 4 × 4 m floor and a 1 × 1 m board 30 m above it: the board can stand between a
    // camera and the floor. (A reach of a quarter of the level's diagonal, 7.6 m, missed it.)
    let mut tris = Vec::new();
    quad(&mut tris, DVec3::new(-2.0, 0.0, -2.0), [DVec3::Z, DVec3::X], [4.0, 4.0], 1.0, &|_, _| true);
    quad(&mut tris, DVec3::new(-0.5, 30.0, -0.5), [DVec3::X, DVec3::Z], [1.0, 1.0], 1.0, &|_, _| true);
    let x = extract(&level_of("far board", &tris), &ExtractParams::default(), &|_, _| {});
    let rs = &x.set.reflectors;
    assert_eq!(rs.len(), 2);
    let floor = rs.iter().position(|r| r.normal.y > 0.9).expect("floor");
    let board = rs.iter().position(|r| r.normal.y < -0.9).expect("board");
    assert_eq!(rs[floor].occluders, vec![board as u32], "the board 30 m away occludes the floor");
    assert!(rs[board].occluders.contains(&(floor as u32)), "and the floor the board (seen from below)");
    // Asking for a reach still limits the lists.
    let near = ExtractParams { reach_m: Some(10.0), ..ExtractParams::default() };
    let x = extract(&level_of("far board", &tris), &near, &|_, _| {});
    assert!(x.set.reflectors.iter().all(|r| r.occluders.is_empty()));
}

#[test]
fn capped_occluder_lists_keep_the_largest_and_say_so() {
    // A floor under 40 small tiles at 1 m and one large board at 20 m: with a cap of 8,
    // the board (area 100 m² at 20 m outranks a 0.01 m² tile at 1 m) stays listed.
    let mut tris = Vec::new();
    quad(&mut tris, DVec3::new(-5.0, 0.0, -5.0), [DVec3::Z, DVec3::X], [10.0, 10.0], 1.0, &|_, _| true);
    for k in 0..40 {
        let p = DVec3::new(-4.0 + 0.2 * k as f64, 1.0, 0.0);
        quad(&mut tris, p, [DVec3::X, DVec3::Z], [0.15, 0.15], 10.0, &|_, _| true);
    }
    quad(&mut tris, DVec3::new(-5.0, 20.0, -5.0), [DVec3::X, DVec3::Z], [10.0, 10.0], 1.0, &|_, _| true);
    let params = ExtractParams { max_occluders: 8, min_area_m2: 0.001, ..ExtractParams::default() };
    let x = extract(&level_of("tiles", &tris), &params, &|_, _| {});
    let rs = &x.set.reflectors;
    assert_eq!(rs.len(), 42);
    let floor = rs.iter().position(|r| r.normal.y > 0.9).expect("floor");
    let board = rs.iter().position(|r| r.normal.y < -0.9 && r.center.y > 10.0).expect("board");
    assert_eq!(rs[floor].occluders.len(), 8);
    assert!(rs[floor].occluders.contains(&(board as u32)), "{:?}", rs[floor].occluders);
    assert!(
        x.warnings.iter().any(|w| w.to_string().contains("occluder lists at the cap of 8")),
        "{:?}",
        x.warnings
    );
}

#[test]
fn the_thread_count_does_not_change_the_bytes() {
    let spec = RoomSpec { cells_per_m: 2.0, left_wall_kink_deg: 1.0, ..RoomSpec::default() };
    let mut tris = ppr_extract::generated_levels::room_grid(&spec, 3, 2, 9.0);
    tris.extend(
        room_triangles(&spec, DVec3::new(0.0, 4.0, 30.0))
            .into_iter()
            .map(|t| t.map(|p| DQuat::from_rotation_y(0.3) * p)),
    );
    let level = level_of("grid", &tris);
    let bytes = |threads: usize| {
        let params = ExtractParams { threads, ..ExtractParams::all_planar() };
        extract(&level, &params, &|_, _| {}).set.to_json_string().expect("valid")
    };
    let one = bytes(1);
    assert_eq!(bytes(2), one);
    assert_eq!(bytes(5), one);
}

#[test]
fn the_density_budget_keeps_what_pays_per_cube_alike_in_every_copy() {
    // A 4 × 4 m floor under 300 small tiles (0.12 × 0.12 m, 2 cm apart in height): more
    // rectangles than a cube of 10 m affords.
    let mut room = Vec::new();
    quad(&mut room, DVec3::new(1.0, 0.0, 1.0), [DVec3::Z, DVec3::X], [4.0, 4.0], 1.0, &|_, _| true);
    for k in 0..300 {
        let p = DVec3::new(
            1.0 + 0.2 * (k % 20) as f64,
            0.5 + 0.02 * (k / 20) as f64,
            1.0 + 0.2 * (k / 20) as f64,
        );
        quad(&mut room, p, [DVec3::Z, DVec3::X], [0.12, 0.12], 10.0, &|_, _| true);
    }
    let params = ExtractParams { max_shapes_per_cube: 100, ..ExtractParams::default() };
    let alone = extract(&level_of("tiles", &room), &params, &|_, _| {});
    assert_eq!(alone.set.reflectors.len(), 100);
    assert!(alone.set.reflectors.iter().any(|r| r.area() > 15.0), "the floor buys the most and stays");
    let note = alone.warnings.iter().map(ToString::to_string).find(|w| w.contains("density budget"));
    assert!(note.as_ref().is_some_and(|n| n.contains("dropped 201 regions")), "{note:?}");
    let unbudgeted = extract(&level_of("tiles", &room), &params.clone().unbudgeted(), &|_, _| {});
    assert_eq!(unbudgeted.set.reflectors.len(), 301);
    // Copies a whole cube apart (20 m) keep the same rectangles each.
    let want = rectangles(&alone, |_| true, DVec3::ZERO);
    let x = extract(&copies(&level_of("tiles", &room), 5, 20.0), &params, &|_, _| {});
    for k in 0..5 {
        let offset = DVec3::X * (20.0 * k as f64);
        let got = rectangles(&x, |c| (c - offset).x.abs() < 10.0, offset);
        assert_same(&got, &want, &format!("copy {k}"));
    }
}
