//! Hot reload without a window: a set is written, loaded, overwritten with a changed set
//! (picked up within a second), overwritten with a broken file (reported, the last good set
//! kept), and mended again.

use std::path::Path;
use std::time::{Duration, Instant};

use glam::{DVec2, DVec3};
use ppr_format::{Reflector, ReflectorKind, ReflectorSet};
use ppr_walkthrough::hot_reload::{ReflectorSetState, ReflectorSetWatcher, ReloadEvent, SetStatus};

use crate::common::gpu_lock;

/// A valid set of `n` floor mirrors side by side.
fn floor_set(n: usize) -> ReflectorSet {
    let mut set = ReflectorSet::new("test.glb");
    for k in 0..n {
        let id = set.next_id();
        set.reflectors.push(Reflector::new(
            id,
            format!("floor {k}"),
            ReflectorKind::Opaque,
            DVec3::new(3.0 * k as f64, 0.0, 0.0),
            DVec3::Y,
            DVec3::X,
            DVec2::new(1.0, 1.0),
        ));
    }
    set.validate().expect("valid test set");
    set
}

/// Waits for the watcher's next event, up to `limit`; returns it and how long it took.
fn next_event(watcher: &ReflectorSetWatcher, limit: Duration) -> (ReloadEvent, Duration) {
    let start = Instant::now();
    let event = watcher.wait(limit).unwrap_or_else(|| panic!("no event within {limit:?}"));
    (event, start.elapsed())
}

fn reflectors(state: &ReflectorSetState) -> Option<usize> {
    state.set().map(|s| s.reflectors.len())
}

#[test]
fn a_changed_set_is_picked_up_within_a_second_and_a_broken_one_is_refused() {
    let _alone = gpu_lock();
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("level.ppr.json");
    floor_set(2).save(&path).expect("first set saved");

    let watcher = ReflectorSetWatcher::start(&path);
    let mut state = ReflectorSetState::new("starting");
    let (event, _) = next_event(&watcher, Duration::from_secs(2));
    assert!(state.apply(event).is_some(), "the first set is handed to the renderer");
    assert_eq!(reflectors(&state), Some(2));

    // An artist saves a changed set in the inspector (atomic write: temp file + rename).
    let saved_at = Instant::now();
    floor_set(5).save(&path).expect("changed set saved");
    let (event, _) = next_event(&watcher, Duration::from_secs(2));
    let latency = saved_at.elapsed();
    assert!(state.apply(event).is_some());
    assert_eq!(reflectors(&state), Some(5));
    eprintln!("[hot reload] changed set picked up after {latency:.0?}");
    assert!(latency < Duration::from_secs(1), "picked up after {latency:?}, more than a second");

    // A broken file: valid JSON, but a negative half extent. Reported, and the 5 stay.
    let mut doc: serde_json::Value =
        serde_json::from_str(&floor_set(1).to_json_string().expect("json")).expect("parses");
    doc["reflectors"][0]["half_extents"][0] = serde_json::json!(-1.0);
    std::fs::write(&path, doc.to_string()).expect("broken file written");
    let (event, _) = next_event(&watcher, Duration::from_secs(2));
    let ReloadEvent::Refused(message) = &event else { panic!("expected a refusal, got {event:?}") };
    assert!(message.contains("half_extents"), "the message names the field: {message}");
    assert!(state.apply(event).is_none(), "nothing new for the renderer");
    assert_eq!(reflectors(&state), Some(5), "the last good set stays in use");
    assert!(matches!(state.status(), SetStatus::Refused { keeping: Some(5), .. }), "{:?}", state.status());

    // Not JSON at all (a save cut short), written in place rather than renamed.
    std::fs::write(&path, "{\"format\": \"ppr-reflector-set\", \"vers").expect("truncated file written");
    let (event, _) = next_event(&watcher, Duration::from_secs(2));
    assert!(matches!(event, ReloadEvent::Refused(_)), "{event:?}");
    state.apply(event);
    assert_eq!(reflectors(&state), Some(5));

    // Mended: taken again.
    floor_set(3).save(&path).expect("mended set saved");
    let (event, _) = next_event(&watcher, Duration::from_secs(2));
    assert!(state.apply(event).is_some());
    assert_eq!(reflectors(&state), Some(3));
    assert!(
        matches!(state.status(), SetStatus::Current { reflectors: 3, reloads: 3, .. }),
        "{:?}",
        state.status()
    );
}

#[test]
fn a_missing_file_is_waited_for() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("not_yet.ppr.json");
    let watcher = ReflectorSetWatcher::start(&path);
    let mut state = ReflectorSetState::new("starting");
    let (event, _) = next_event(&watcher, Duration::from_secs(2));
    assert!(matches!(event, ReloadEvent::Unreadable(_)), "{event:?}");
    state.apply(event);
    assert!(matches!(state.status(), SetStatus::Waiting(_)));
    floor_set(1).save(&path).expect("set saved");
    let (event, _) = next_event(&watcher, Duration::from_secs(2));
    assert!(state.apply(event).is_some());
    assert_eq!(reflectors(&state), Some(1));
}

/// The render loop never waits for parsing: `poll` only takes finished results. A large set
/// (20 000 reflectors, several MB) is parsed on the watcher's thread while the loop polls.
#[test]
fn polling_never_stalls_the_render_loop() {
    let _alone = gpu_lock();
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("big.ppr.json");
    floor_set(1).save(&path).expect("small set saved");
    let watcher = ReflectorSetWatcher::start(&path);
    let mut state = ReflectorSetState::new("starting");
    let (event, _) = next_event(&watcher, Duration::from_secs(2));
    state.apply(event);

    write_big_set(&path, 20_000);
    let start = Instant::now();
    let mut longest_poll = Duration::ZERO;
    while reflectors(&state) != Some(20_000) {
        assert!(start.elapsed() < Duration::from_secs(10), "the big set never arrived");
        let polled = Instant::now();
        let events = watcher.poll();
        longest_poll = longest_poll.max(polled.elapsed());
        for event in events {
            state.apply(event);
        }
        std::thread::sleep(Duration::from_millis(2));
    }
    eprintln!(
        "[hot reload] 20 000 reflectors arrived after {:.0?}; longest poll {longest_poll:?}",
        start.elapsed()
    );
    // Parsing and validating 20 000 reflectors takes a few hundred milliseconds here; a
    // poll that did any of it would take that long. 50 ms leaves room for a loaded machine
    // descheduling the test thread.
    assert!(longest_poll < Duration::from_millis(50), "a poll took {longest_poll:?}");
}

fn write_big_set(path: &Path, n: usize) {
    let text = floor_set(n).to_json_string().expect("json");
    ppr_format::write_atomically(path, text.as_bytes()).expect("big set written");
}
