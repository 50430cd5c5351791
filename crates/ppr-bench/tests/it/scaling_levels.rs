//! The generated scaling levels: exactly the requested reflector count, valid sets
//! (axes, extents, occluder indices), one parallel group per family, and a camera that
//! sees the reflectors.

use ppr_bench::scaling::coverage_level::coverage_level;
use ppr_bench::scaling::level_family::{LevelFamily, generate};
use ppr_runtime::plan::{FramePlan, PlanParams};
use ppr_runtime::shapes::ShapeTable;

#[test]
fn every_family_has_the_requested_count_and_a_valid_set() {
    for family in LevelFamily::ALL {
        for n in [1, 2, 10, 100, 1000, 10_000] {
            let g = generate(family, n);
            let what = format!("{} with {n}", family.as_str());
            assert_eq!(g.reflectors.reflectors.len(), n, "{what}");
            g.reflectors.validate().unwrap_or_else(|e| panic!("{what}: {e}"));
            g.level.validate().unwrap_or_else(|e| panic!("{what}: {e}"));
            let rooms = family == LevelFamily::Rooms;
            let groups = g.reflectors.reflectors.iter().map(|r| r.parallel_group).max().unwrap_or(0) + 1;
            if rooms {
                // Every way: from 100 reflectors on, more orientations than a box has faces.
                assert!(n < 100 || groups > 20, "{what}: only {groups} orientations");
            } else {
                assert_eq!(groups, 1, "{what}: one orientation");
            }
            if n <= 1000 {
                let plan = FramePlan::build(
                    &ShapeTable::from_set(&g.reflectors),
                    &g.camera,
                    [3840, 2160],
                    &PlanParams::default(),
                );
                // Rooms: one face of each two-faced panel faces the camera.
                let share = if rooms { 4 } else { 9 };
                assert!(plan.visible.len() * 10 >= n * share, "{what}: only {} visible", plan.visible.len());
            }
            if family == LevelFamily::Stairway && n >= 10 {
                // Higher treads stand in front of lower ones.
                assert!(
                    g.reflectors.reflectors.iter().any(|r| !r.occluders.is_empty()),
                    "{what}: no occluders"
                );
            }
        }
    }
}

#[test]
fn coverage_levels_cover_the_requested_share_of_the_screen() {
    for c in [0.05, 0.3, 0.7, 1.0] {
        let g = coverage_level(c);
        g.reflectors.validate().expect("valid set");
        let plan = FramePlan::build(
            &ShapeTable::from_set(&g.reflectors),
            &g.camera,
            [3840, 2160],
            &PlanParams::default(),
        );
        assert_eq!(plan.visible.len(), 1);
        assert!((f64::from(plan.coverage) - c).abs() < 0.02, "asked {c}, got {}", plan.coverage);
    }
}
