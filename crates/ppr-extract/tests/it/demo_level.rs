//! The demo level (`assets/demo_room.glb`) gives exactly the shapes of
//! `assets/demo_room.expected.json`: count, kinds, centres, normals, extents, areas,
//! parallel groups, and no reflector for the vetoed `table_top`.

use std::path::PathBuf;

use glam::{DVec2, DVec3};
use ppr_extract::{ExtractParams, extract, load_level};
use ppr_format::Reflector;
use serde_json::Value;

use crate::checks::assert_encloses_regions;

fn assets() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets")
}

fn vec3(v: &Value) -> DVec3 {
    let a: Vec<f64> = v.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect();
    DVec3::new(a[0], a[1], a[2])
}

fn matches(r: &Reflector, rect: &Value, kind: &str, tol: f64) -> bool {
    let half = rect["half_extents"].as_array().expect("half_extents");
    let (hu, hv) = (half[0].as_f64().expect("hu"), half[1].as_f64().expect("hv"));
    r.kind.as_str() == kind
        && (r.center - vec3(&rect["center"])).length() <= tol
        && (r.normal - vec3(&rect["normal"])).length() <= tol
        && (r.half_extents - DVec2::new(hu, hv)).abs().max_element() <= tol
        && (r.area() - rect["area"].as_f64().expect("area")).abs()
            <= tol * rect["area"].as_f64().expect("area")
}

#[test]
fn demo_room_gives_exactly_the_expected_shapes() {
    let expected: Value = serde_json::from_slice(
        &std::fs::read(assets().join("demo_room.expected.json")).expect("expected file"),
    )
    .expect("json");
    let tol = expected["conventions"]["suggested_position_tolerance_m"].as_f64().expect("tolerance");
    let level = load_level(assets().join("demo_room.glb")).expect("demo level");
    let x = extract(&level, &ExtractParams::default(), &|_, _| {});
    assert_encloses_regions(&x, 2e-3, "demo_room");
    let rs = &x.set.reflectors;

    let mut used = vec![false; rs.len()];
    let mut expected_count = 0;
    for e in expected["reflectors"].as_array().expect("reflectors") {
        let name = e["name"].as_str().expect("name");
        let kind = e["kind"].as_str().expect("kind");
        let mut options = vec![e["rectangles"].as_array().expect("rectangles").clone()];
        if let Some(alts) = e["alternative_rectangles"].as_array() {
            options.extend(alts.iter().map(|a| a.as_array().expect("alternative").clone()));
        }
        expected_count += options[0].len();
        let found = options.iter().any(|rects| {
            let picks: Vec<Option<usize>> = rects
                .iter()
                .map(|rect| (0..rs.len()).find(|&i| !used[i] && matches(&rs[i], rect, kind, tol)))
                .collect();
            if picks.iter().all(Option::is_some) {
                for p in picks.into_iter().flatten() {
                    used[p] = true;
                    assert!(
                        rs[p].source.nodes.iter().any(|n| n == e["node"].as_str().expect("node")),
                        "{name}: sources {:?}",
                        rs[p].source
                    );
                }
                true
            } else {
                false
            }
        });
        assert!(found, "{name}: no reflector matches {options:#?}\ngot {rs:#?}");
    }
    assert_eq!(rs.len(), expected_count, "exactly the expected shapes: {rs:#?}");
    for n in expected["non_reflectors"].as_array().expect("non_reflectors") {
        let node = n["node"].as_str().expect("node");
        assert!(rs.iter().all(|r| !r.source.nodes.iter().any(|s| s == node)), "{node} became a reflector");
    }
    // Parallel groups: members of one expected group share a group number, others differ.
    let group_of =
        |name: &str| rs.iter().find(|r| r.source.nodes.iter().any(|n| n == name)).map(|r| r.parallel_group);
    let groups: Vec<Vec<Option<u32>>> = expected["parallel_groups"]
        .as_array()
        .expect("groups")
        .iter()
        .map(|g| {
            g["members"]
                .as_array()
                .expect("members")
                .iter()
                .map(|m| group_of(m.as_str().expect("member")))
                .collect()
        })
        .collect();
    for g in &groups {
        assert!(g.iter().all(|x| x.is_some() && *x == g[0]), "group {g:?}");
    }
    let firsts: Vec<_> = groups.iter().map(|g| g[0]).collect();
    let mut unique = firsts.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), firsts.len(), "distinct groups {firsts:?}");
}
