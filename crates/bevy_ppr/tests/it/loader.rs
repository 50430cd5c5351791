//! The `*.ppr.json` loader through Bevy's asset server: a broken file's load error names the
//! file and the field; a changed file reloads through the asset watcher.

use std::path::Path;
use std::time::{Duration, Instant};

use bevy::asset::{AssetServer, Assets, LoadState};
use bevy::prelude::*;
use bevy_ppr::{PprReflectorSet, parse_reflector_set};

use crate::app::{asset_app, run_until};

/// A valid one-reflector set from the analytic-scene harness, as JSON.
fn set_json() -> String {
    let mut scene = ppr_tests::scene::AnalyticScene::default();
    scene.mirror("mirror", glam::DVec3::ZERO, glam::DVec3::X, glam::DVec3::NEG_Z, [1.0, 1.0]);
    scene.reflector_set().to_json_string().expect("set serialises")
}

#[test]
fn parse_errors_name_the_file_and_the_field() {
    let broken = set_json().replacen("\"roughness\": 0.0", "\"roughness\": \"smooth\"", 1);
    assert_ne!(broken, set_json(), "the test must break the set");
    let error =
        parse_reflector_set("levels/hall.ppr.json".into(), broken.as_bytes()).unwrap_err().to_string();
    assert!(error.contains("levels/hall.ppr.json"), "{error}");
    assert!(error.contains("roughness"), "{error}");
    let error = parse_reflector_set("x.ppr.json".into(), &[0xff, 0xfe]).unwrap_err().to_string();
    assert!(error.contains("x.ppr.json") && error.contains("UTF-8"), "{error}");
}

#[test]
fn a_broken_set_fails_to_load_naming_file_and_field() {
    let dir = tempfile::tempdir().expect("temp dir");
    let broken = set_json().replacen("\"roughness\": 0.0", "\"roughness\": -3.0", 1);
    std::fs::write(dir.path().join("broken.ppr.json"), broken).expect("write");
    let mut app = asset_app(dir.path(), false);
    let handle: Handle<PprReflectorSet> = app.world().resource::<AssetServer>().load("broken.ppr.json");
    let mut error = None;
    run_until(&mut app, 600, |app| {
        if let LoadState::Failed(e) = app.world().resource::<AssetServer>().load_state(&handle) {
            error = Some(e.to_string());
        }
        error.is_some()
    });
    let error = error.expect("the load must fail");
    assert!(
        error.contains("broken.ppr.json") && error.contains("roughness"),
        "names file and field: {error}"
    );
}

#[test]
fn a_changed_set_reloads_through_the_asset_watcher() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("hall.ppr.json");
    std::fs::write(&path, set_json()).expect("write");
    let mut app = asset_app(dir.path(), true);
    let handle: Handle<PprReflectorSet> = app.world().resource::<AssetServer>().load("hall.ppr.json");
    let loaded =
        |app: &mut App| app.world().resource::<Assets<PprReflectorSet>>().get(&handle).map(|a| a.set.clone());
    let mut first = None;
    assert!(
        run_until(&mut app, 600, |app| {
            first = loaded(app);
            first.is_some()
        }),
        "the set must load"
    );
    let first = first.expect("loaded");
    assert_eq!(first.reflectors[0].name, "mirror");

    let renamed = set_json().replacen("\"name\": \"mirror\"", "\"name\": \"renamed\"", 1);
    assert_ne!(renamed, set_json(), "the test must change the set");
    write_later(&path, &renamed);
    let deadline = Instant::now() + Duration::from_secs(30);
    let mut reloaded = false;
    while !reloaded && Instant::now() < deadline {
        app.update();
        std::thread::sleep(Duration::from_millis(20));
        reloaded = loaded(&mut app).is_some_and(|s| s.reflectors[0].name == "renamed");
    }
    assert!(reloaded, "the watcher must reload the changed set within 30 s");
}

/// Writes after a pause, so that the watcher has started.
fn write_later(path: &Path, text: &str) {
    std::thread::sleep(Duration::from_millis(500));
    std::fs::write(path, text).expect("write");
}
