//! Near-planar surfaces: a wall whose two triangles differ by 1° is one rectangle, and the
//! merge is reported with the reflection error it causes.

use glam::DVec3;
use ppr_extract::generated_levels::{RoomSpec, level_of, room_triangles};
use ppr_extract::{ExtractParams, Extraction, Warning, extract};

use crate::checks::assert_encloses_regions;

fn left_wall(x: &Extraction) -> Vec<&ppr_format::Reflector> {
    x.set.reflectors.iter().filter(|r| r.normal.x > 0.9 && r.center.x < 0.5).collect()
}

#[test]
fn a_wall_kinked_by_one_degree_is_one_rectangle() {
    let spec = RoomSpec { left_wall_kink_deg: 1.0, ..RoomSpec::default() };
    let tris = room_triangles(&spec, DVec3::ZERO);
    let params = ExtractParams::all_planar();
    let x = extract(&level_of("kinked", &tris), &params, &|_, _| {});
    assert_encloses_regions(&x, params.max_reflection_error_m / 2.0, "kinked room");
    let wall = left_wall(&x);
    assert_eq!(wall.len(), 1, "{wall:#?}");
    assert!((wall[0].area() - 15.0).abs() < 0.2, "5 × 3 m: {}", wall[0].area());
    let merge = x.warnings.iter().find_map(|w| match w {
        Warning::NearPlanarMerge { report } => Some(report.clone()),
        _ => None,
    });
    let merge = merge.expect("the merge is reported");
    eprintln!("1° kink: {merge:?}");
    assert_eq!(merge.regions, 2);
    assert!(merge.angle_deg > 0.4 && merge.angle_deg < 0.6, "{merge:?}");
    assert!(merge.error_m > 0.0 && merge.error_m <= params.max_reflection_error_m, "{merge:?}");
    assert!(x.warnings.iter().any(|w| w.to_string().contains("reflection error")));

    // Without merging, the two triangles are two regions and several rectangles.
    let apart = ExtractParams { near_planar_angle_deg: 0.0, ..ExtractParams::all_planar() };
    let x = extract(&level_of("kinked", &tris), &apart, &|_, _| {});
    assert!(left_wall(&x).len() >= 2, "{}", left_wall(&x).len());
    // A bound tighter than the error keeps them apart too.
    let strict = ExtractParams { max_reflection_error_m: merge.error_m * 0.9, ..ExtractParams::all_planar() };
    let x = extract(&level_of("kinked", &tris), &strict, &|_, _| {});
    assert!(left_wall(&x).len() >= 2);
    // A kink of 5° is not near-planar.
    let spec = RoomSpec { left_wall_kink_deg: 5.0, ..RoomSpec::default() };
    let x = extract(&level_of("bent", &room_triangles(&spec, DVec3::ZERO)), &params, &|_, _| {});
    assert!(left_wall(&x).len() >= 2);
}
