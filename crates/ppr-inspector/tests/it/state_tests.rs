//! `InspectorState` and the edit logic, without a GPU: undo/redo, refusals, split, merge,
//! re-fit, re-extraction keeping edits, saving and loading, the unsaved-changes guard.

use std::time::Duration;

use glam::DVec2;
use ppr_extract::ExtractParams;
use ppr_format::{ReflectorKind, ReflectorSet};
use ppr_inspector::commands::EditCommand;
use ppr_inspector::document::Document;
use ppr_inspector::error::EditError;
use ppr_inspector::manual_edits::carry_edits;
use ppr_inspector::messages::Severity;
use ppr_inspector::reflector_geometry::{Placement, SplitAxis, placement_of};
use ppr_inspector::state::{InspectorState, PendingAction};

use crate::demo::{demo_document, demo_level_path, id_named};

fn state_with(doc: Document) -> InspectorState {
    let mut state = InspectorState::default();
    state.doc = Some(doc);
    state
}

fn placement(state: &InspectorState, id: u32) -> Placement {
    placement_of(state.set().and_then(|s| s.by_id(id)).expect("reflector"))
}

#[test]
fn edits_undo_and_redo_step_by_step() {
    let original = demo_document(&ExtractParams::default());
    let mirror = id_named(&original, "mirror on mirror_wall");
    let mut state = state_with(original.clone());
    assert!(state.apply(EditCommand::Rename { id: mirror, name: "big mirror".into() }));
    assert!(state.apply(EditCommand::SetKind { id: mirror, kind: ReflectorKind::Water }));
    let mut p = placement(&state, mirror);
    p.half_extents.x = 2.0;
    p.angle_deg += 10.0;
    assert!(state.apply(EditCommand::Place { id: mirror, placement: p }));
    assert!(state.apply(EditCommand::SetEnabled { id: mirror, enabled: false }));
    let edited = state.set().cloned().expect("set");
    let r = edited.by_id(mirror).expect("mirror");
    assert_eq!((r.name.as_str(), r.kind, r.enabled), ("big mirror", ReflectorKind::Water, false));
    assert!((r.half_extents.x - 2.0).abs() < 1e-12);
    assert!(edited.validate().is_ok());
    assert_eq!(state.history.undo_len(), 4);

    for _ in 0..4 {
        state.undo();
    }
    assert_eq!(state.set(), Some(&original.set), "four undos give the extraction back");
    assert_eq!(state.revision(), original.revision);
    state.undo(); // nothing left: a message, no change
    assert_eq!(state.set(), Some(&original.set));
    for _ in 0..4 {
        state.redo();
    }
    assert_eq!(state.set(), Some(&edited));
    // A new edit after an undo drops the redo stack.
    state.undo();
    assert!(state.apply(EditCommand::Rename { id: mirror, name: "other".into() }));
    assert!(state.history.redo_label().is_none());
}

#[test]
fn roughness_is_edited_undone_and_refused_outside_zero_to_one() {
    let original = demo_document(&ExtractParams::default());
    let mirror = id_named(&original, "mirror on mirror_wall");
    let before = original.set.by_id(mirror).expect("mirror").roughness;
    let mut state = state_with(original.clone());
    assert!(state.apply(EditCommand::SetRoughness { id: mirror, roughness: 0.35 }));
    let r = state.set().and_then(|s| s.by_id(mirror)).expect("mirror");
    assert_eq!(r.roughness, 0.35);
    assert!(state.doc.as_ref().is_some_and(|d| d.edits.edited.contains(&mirror)), "recorded as an edit");
    assert_eq!(state.history.undo_label(), Some("set the roughness of \"mirror on mirror_wall\" to 0.350"));
    state.undo();
    assert_eq!(state.set().and_then(|s| s.by_id(mirror)).map(|r| r.roughness), Some(before));
    state.redo();
    assert_eq!(state.set().and_then(|s| s.by_id(mirror)).map(|r| r.roughness), Some(0.35));
    for bad in [1.5, -0.1, f64::NAN] {
        assert!(!state.apply(EditCommand::SetRoughness { id: mirror, roughness: bad }), "{bad}");
        let message = state.messages.latest_error().expect("an error").text.clone();
        assert!(message.contains("roughness") && message.contains("mirror on mirror_wall"), "{message}");
    }
    assert_eq!(state.history.undo_len(), 1);
}

#[test]
fn one_gesture_is_one_undo_step() {
    let original = demo_document(&ExtractParams::default());
    let mirror = id_named(&original, "mirror on mirror_wall");
    let mut state = state_with(original.clone());
    let gesture = state.new_gesture();
    for k in 1..=5 {
        let mut p = placement(&state, mirror);
        p.half_extents.y = 1.5 + 0.1 * f64::from(k);
        assert!(state.apply_in_gesture(EditCommand::Place { id: mirror, placement: p }, Some(gesture)));
    }
    assert_eq!(state.history.undo_len(), 1);
    assert!((placement(&state, mirror).half_extents.y - 2.0).abs() < 1e-12);
    state.undo();
    assert_eq!(state.set(), Some(&original.set));
}

#[test]
fn refused_edits_change_nothing_and_name_the_field() {
    let original = demo_document(&ExtractParams::default());
    let mirror = id_named(&original, "mirror on mirror_wall");
    let mut state = state_with(original.clone());
    let mut p = placement(&state, mirror);
    p.half_extents.x = 0.0;
    assert!(!state.apply(EditCommand::Place { id: mirror, placement: p }));
    let message = state.messages.latest_error().expect("an error").text.clone();
    assert!(message.contains("half_extents") && message.contains("refused"), "{message}");
    assert_eq!(state.set(), Some(&original.set));
    assert_eq!(state.history.undo_len(), 0);

    match (EditCommand::Place {
        id: mirror,
        placement: Placement { half_extents: DVec2::new(f64::NAN, 1.0), ..p },
    })
    .apply(&original)
    {
        Err(EditError::Invalid(field)) => assert_eq!(field.field, "half_extents"),
        other => panic!("expected a refusal naming half_extents, got {other:?}"),
    }
    assert!(matches!(EditCommand::Refit { id: 12345 }.apply(&original), Err(EditError::UnknownId(12345))));
    let loaded = Document::from_set(original.set.clone());
    assert!(matches!(EditCommand::Refit { id: mirror }.apply(&loaded), Err(EditError::NoRegion { .. })));
}

#[test]
fn merge_split_and_refit_on_the_demo_level() {
    let doc = demo_document(&ExtractParams::default());
    let (a, b) = (
        id_named(&doc, "polished_marble on polished_floor [1/2]"),
        id_named(&doc, "polished_marble on polished_floor [2/2]"),
    );
    let (ra, rb) = (doc.set.by_id(a).expect("a").clone(), doc.set.by_id(b).expect("b").clone());
    let count = doc.set.reflectors.len();

    // Merge the two floor parts: one rectangle enclosing both, summed reflective area.
    let merged = EditCommand::Merge { id: a, other: b }.apply(&doc).expect("coplanar parts merge");
    let m = merged.doc.set.by_id(merged.select.expect("selects the result")).expect("merged").clone();
    assert_eq!(merged.doc.set.reflectors.len(), count - 1);
    for corner in ra.corners().into_iter().chain(rb.corners()) {
        assert!(m.contains_projection(corner, 1e-6), "merged rectangle encloses {corner}");
    }
    let reflective = ra.coverage * ra.area() + rb.coverage * rb.area();
    assert!(
        (m.coverage - reflective / m.area()).abs() < 1e-9,
        "coverage {} for area {}",
        m.coverage,
        m.area()
    );
    assert!(merged.doc.set.validate().is_ok());
    assert_eq!(merged.doc.edits.replacements.len(), 1);

    // Merging with a wall is refused.
    let wall = id_named(&doc, "mirror on mirror_wall");
    assert!(matches!(
        EditCommand::Merge { id: a, other: wall }.apply(&doc),
        Err(EditError::NotMergeable { .. })
    ));

    // Split the merged floor back across its long side: two parts, each within it.
    let split =
        EditCommand::Split { id: m.id, axis: SplitAxis::U, at: 0.5 }.apply(&merged.doc).expect("split");
    assert_eq!(split.doc.set.reflectors.len(), count);
    let parts: Vec<_> = split.doc.edits.replacements[1].created.iter().map(|(r, _)| r.clone()).collect();
    assert_eq!(parts.len(), 2);
    for part in &parts {
        assert!(part.area() <= m.area() * 0.5 + 1e-9 && part.coverage > 0.0 && part.coverage <= 1.0);
        assert!(split.doc.regions.contains_key(&part.id), "parts keep their share of the region");
    }

    // Re-fit: a moved and enlarged mirror goes back to its extracted rectangle.
    let mut p = placement_of(doc.set.by_id(wall).expect("wall"));
    let original_wall = doc.set.by_id(wall).expect("wall").clone();
    p.half_extents *= 1.5;
    p.center.x += 0.3;
    let moved = EditCommand::Place { id: wall, placement: p }.apply(&doc).expect("placed");
    assert!(moved.doc.set.by_id(wall).expect("wall").coverage < 0.5);
    let refit = EditCommand::Refit { id: wall }.apply(&moved.doc).expect("refit");
    let fitted = refit.doc.set.by_id(wall).expect("wall");
    assert!(
        (fitted.area() - original_wall.area()).abs() < 1e-6,
        "{} vs {}",
        fitted.area(),
        original_wall.area()
    );
    assert!((fitted.center - original_wall.center).length() < 1e-6);
    assert!((fitted.coverage - original_wall.coverage).abs() < 1e-9);
}

#[test]
fn reextraction_keeps_edits_whose_ids_are_still_produced() {
    let doc = demo_document(&ExtractParams::default());
    let mirror = id_named(&doc, "mirror on mirror_wall");
    let puddle = id_named(&doc, "puddle on puddle_a");
    let water = id_named(&doc, "water on water_surface");
    let floor_part = id_named(&doc, "polished_marble on polished_floor [1/2]");
    let mut state = state_with(doc);
    assert!(state.apply(EditCommand::Rename { id: mirror, name: "hero mirror".into() }));
    assert!(state.apply(EditCommand::SetEnabled { id: puddle, enabled: false }));
    assert!(state.apply(EditCommand::Rename { id: floor_part, name: "floor left".into() }));
    assert!(state.apply(EditCommand::Split { id: water, axis: SplitAxis::V, at: 0.5 }));
    let current = state.doc.clone().expect("doc");

    // Without splitting, the floor is one rectangle with another id: that edit no longer applies.
    let fresh = demo_document(&ExtractParams::no_split());
    assert!(fresh.set.by_id(floor_part).is_none());
    let (carried, report) = carry_edits(&current, fresh).expect("carried");
    let set = &carried.set;
    assert_eq!(set.by_id(mirror).map(|r| r.name.as_str()), Some("hero mirror"));
    assert_eq!(set.by_id(puddle).map(|r| r.enabled), Some(false));
    assert!(set.by_id(water).is_none(), "the split water is replaced by its parts");
    assert_eq!(set.reflectors.iter().filter(|r| r.name.starts_with("water on water_surface [")).count(), 2);
    assert_eq!(report.not_applicable.len(), 1, "{report:?}");
    assert!(report.not_applicable[0].contains("floor left"), "{report:?}");
    assert_eq!(report.kept.len(), 3, "{report:?}");
    assert!(set.validate().is_ok());

    // Re-extracting with the same parameters keeps everything.
    let (same, report) = carry_edits(&current, demo_document(&ExtractParams::default())).expect("carried");
    assert!(report.not_applicable.is_empty(), "{report:?}");
    let names = |s: &ReflectorSet| {
        let mut v: Vec<(u32, String, bool)> =
            s.reflectors.iter().map(|r| (r.id, r.name.clone(), r.enabled)).collect();
        v.sort();
        v
    };
    assert_eq!(names(&same.set), names(&current.set));
}

#[test]
fn background_open_and_reextract_through_the_state() {
    let mut state = InspectorState::default();
    state.open_level(&demo_level_path(), None);
    assert!(state.job.is_some());
    assert!(state.wait_for_job(Duration::from_secs(120)), "extraction finished");
    let level = state.level.as_ref().expect("level");
    assert!(level.render.is_some() && level.extract.is_some());
    let count = state.set().expect("extracted").reflectors.len();
    assert_eq!(count, 16);
    assert!(state.is_dirty(), "a fresh extraction is not saved yet");

    let mirror = id_named(state.doc.as_ref().expect("doc"), "mirror on mirror_wall");
    assert!(state.apply(EditCommand::Rename { id: mirror, name: "kept".into() }));
    state.params = ExtractParams::no_split();
    state.reextract().expect("starts");
    assert!(state.reextract().is_err(), "one job at a time");
    assert!(state.wait_for_job(Duration::from_secs(120)));
    let set = state.set().expect("set");
    assert_eq!(set.reflectors.len(), 15, "no split: the floor is one rectangle");
    assert_eq!(set.by_id(mirror).map(|r| r.name.as_str()), Some("kept"));
    state.undo();
    assert_eq!(state.set().expect("set").reflectors.len(), 16, "re-extraction is one undo step");

    // Bad parameters are refused before anything starts.
    state.params.distance_tolerance_m = -1.0;
    let e = state.reextract().expect_err("refused");
    assert!(e.to_string().contains("distance_tolerance"), "{e}");

    // Cancelling drops the job.
    state.params = ExtractParams::default();
    state.reextract().expect("starts");
    state.cancel_job();
    assert!(state.job.is_none());
    assert_eq!(state.messages.latest().map(|m| m.severity), Some(Severity::Warning));
}

#[test]
fn a_missing_level_is_an_error_message() {
    let mut state = InspectorState::default();
    state.open_level(std::path::Path::new("/nonexistent/level.glb"), None);
    assert!(state.wait_for_job(Duration::from_secs(30)));
    let e = state.messages.latest_error().expect("error").text.clone();
    assert!(e.contains("/nonexistent/level.glb"), "{e}");
    assert!(state.doc.is_none());
}

#[test]
fn save_reload_and_broken_files() {
    let dir = tempfile::tempdir().expect("tempdir");
    let doc = demo_document(&ExtractParams::default());
    let mirror = id_named(&doc, "mirror on mirror_wall");
    let mut state = state_with(doc);
    assert!(state.is_dirty());
    assert!(state.save().is_err(), "no level and no file: nowhere to save");
    assert!(state.apply(EditCommand::SetKind { id: mirror, kind: ReflectorKind::Transparent }));
    let path = dir.path().join("room.ppr.json");
    state.save_as(&path).expect("saved");
    assert!(!state.is_dirty());
    let saved = ReflectorSet::load(&path).expect("reloads");
    let text = std::fs::read_to_string(&path).expect("read");
    assert_eq!(state.set().map(|s| s.to_json_string().expect("valid")), Some(text), "the file is the set");
    assert_same(&saved, state.set().expect("set"));
    state.undo();
    assert!(state.is_dirty(), "undo after saving is a change");
    state.redo();
    assert!(!state.is_dirty(), "and redo is back to the saved state");

    // Unsaved-changes guard: opening asks first.
    assert!(state.apply(EditCommand::SetEnabled { id: mirror, enabled: false }));
    state.request(PendingAction::OpenSet(path.clone()));
    assert_eq!(state.pending, Some(PendingAction::OpenSet(path.clone())));
    state.cancel_pending();
    assert_eq!(state.set().and_then(|s| s.by_id(mirror)).map(|r| r.enabled), Some(false));
    state.request(PendingAction::OpenSet(path.clone()));
    state.confirm_pending();
    assert_eq!(state.set(), Some(&saved), "reloaded from the file");
    assert!(!state.is_dirty());

    // Quitting with unsaved changes asks too.
    assert!(state.apply(EditCommand::SetEnabled { id: mirror, enabled: false }));
    state.request(PendingAction::Quit);
    assert!(!state.quit_confirmed && state.pending == Some(PendingAction::Quit));
    state.confirm_pending();
    assert!(state.quit_confirmed);
    state.undo();

    // A broken set: the message names the file and the field.
    let text =
        std::fs::read_to_string(&path).expect("read").replacen("\"coverage\": 1.0", "\"coverage\": 2.5", 1);
    let broken = dir.path().join("broken.ppr.json");
    std::fs::write(&broken, text).expect("write");
    state.open_set(&broken);
    let e = state.messages.latest_error().expect("error").text.clone();
    assert!(e.contains("broken.ppr.json") && e.contains("coverage"), "{e}");
    assert_eq!(state.set(), Some(&saved), "the set in memory is untouched");
}

/// The two sets are equal up to the last bit of a float: reading JSON back may round the
/// last digit (serde_json without its `float_roundtrip` feature).
pub fn assert_same(a: &ReflectorSet, b: &ReflectorSet) {
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1.0);
    assert_eq!(a.reflectors.len(), b.reflectors.len());
    for (ra, rb) in a.reflectors.iter().zip(&b.reflectors) {
        assert_eq!((ra.id, &ra.name, ra.kind, ra.enabled), (rb.id, &rb.name, rb.kind, rb.enabled));
        assert_eq!(
            (&ra.occluders, ra.parallel_group, &ra.source),
            (&rb.occluders, rb.parallel_group, &rb.source)
        );
        let (fa, fb) = (float_fields(ra), float_fields(rb));
        assert!(fa.iter().zip(&fb).all(|(x, y)| close(*x, *y)), "{} differs: {fa:?} vs {fb:?}", ra.name);
    }
}

fn float_fields(r: &ppr_format::Reflector) -> Vec<f64> {
    [r.center, r.axis_u, r.axis_v, r.normal]
        .iter()
        .flat_map(|v| v.to_array())
        .chain(r.half_extents.to_array())
        .chain([r.coverage, r.roughness])
        .collect()
}

#[test]
fn opening_a_level_with_a_saved_set_skips_extraction() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("room.ppr.json");
    let doc = demo_document(&ExtractParams::no_split());
    doc.set.save(&path).expect("saved");
    let mut state = InspectorState::default();
    state.open_level(&demo_level_path(), Some(&path));
    assert_eq!(state.set().map(|s| s.reflectors.len()), Some(15), "the set is the file's");
    assert!(!state.is_dirty());
    assert!(state.wait_for_job(Duration::from_secs(120)));
    assert!(state.level.as_ref().is_some_and(|l| l.render.is_some() && l.extract.is_some()));
    assert_eq!(state.set().map(|s| s.reflectors.len()), Some(15), "no extraction replaced it");
    assert_eq!(state.default_set_path(), Some(path));
}

#[test]
fn manual_edits_survive_save_reopen_and_reextraction() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("room.ppr.json");
    let edits_path = ppr_inspector::edits_file::edits_path(&path);
    assert_eq!(edits_path, dir.path().join("room.ppr.edits.json"));

    let doc = demo_document(&ExtractParams::default());
    let mirror = id_named(&doc, "mirror on mirror_wall");
    let puddle = id_named(&doc, "puddle on puddle_a");
    let water = id_named(&doc, "water on water_surface");
    let mut state = state_with(doc);
    assert!(state.apply(EditCommand::Rename { id: mirror, name: "hero mirror".into() }));
    assert!(state.apply(EditCommand::SetEnabled { id: puddle, enabled: false }));
    assert!(state.apply(EditCommand::SetRoughness { id: mirror, roughness: 0.4 }));
    assert!(state.apply(EditCommand::Split { id: water, axis: SplitAxis::V, at: 0.5 }));
    state.save_as(&path).expect("saved");
    assert!(edits_path.exists(), "the edits are saved beside the set");
    let record = std::fs::read_to_string(&edits_path).expect("read");
    let record = ppr_format::edits::EditsFile::from_json_str(&record).expect("an edits file");
    assert!(record.edited.contains(&mirror), "the roughness edit is recorded: {record:?}");
    let saved = state.set().expect("set").clone();

    // Reopen (a new session): the set is the file's, and re-extraction keeps the edits.
    let mut reopened = InspectorState::default();
    reopened.open_level(&demo_level_path(), Some(&path));
    assert!(reopened.wait_for_job(Duration::from_secs(120)));
    assert_eq!(reopened.set(), Some(&saved));
    let loaded = reopened.messages.entries().iter().any(|m| m.text.contains("3 manual edit(s)"));
    assert!(loaded, "{:?}", reopened.messages.entries());
    reopened.reextract().expect("starts");
    assert!(reopened.wait_for_job(Duration::from_secs(120)));
    let set = reopened.set().expect("set");
    assert_eq!(set.by_id(mirror).map(|r| r.name.as_str()), Some("hero mirror"));
    assert_eq!(set.by_id(mirror).map(|r| r.roughness), Some(0.4), "re-extraction keeps the roughness");
    assert_eq!(set.by_id(puddle).map(|r| r.enabled), Some(false));
    assert!(set.by_id(water).is_none(), "the split water stays split");
    assert_eq!(set.reflectors.iter().filter(|r| r.name.starts_with("water on water_surface [")).count(), 2);

    // Saving a set without edits removes the stale record.
    let mut fresh = state_with(demo_document(&ExtractParams::default()));
    fresh.save_as(&path).expect("saved");
    assert!(!edits_path.exists(), "no edits, no record");

    // A broken record is a warning that names the file; the set still opens.
    std::fs::write(&edits_path, "{ not json").expect("written");
    let mut broken = InspectorState::default();
    broken.open_set(&path);
    assert!(broken.set().is_some());
    let warning =
        broken.messages.entries().iter().find(|m| m.severity == Severity::Warning).expect("a warning");
    assert!(warning.text.contains("room.ppr.edits.json"), "{}", warning.text);
}

#[test]
fn a_set_of_another_level_opens_with_a_warning_naming_both_files() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("other.ppr.json");
    let mut doc = demo_document(&ExtractParams::no_split());
    doc.set.source.hash = format!("blake3:{}", "0".repeat(64));
    doc.set.save(&path).expect("saved");
    let mismatch_warnings = |state: &InspectorState| {
        let warnings = state.messages.entries().iter().filter(|m| m.severity == Severity::Warning);
        warnings.filter(|m| m.text.contains("other.ppr.json") && m.text.contains("demo_room.glb")).count()
    };

    // The set first, the level loading in the background: the warning comes once it is loaded.
    let mut state = InspectorState::default();
    state.open_level(&demo_level_path(), Some(&path));
    assert!(state.wait_for_job(Duration::from_secs(120)));
    assert_eq!(mismatch_warnings(&state), 1, "{:?}", state.messages.entries());
    assert_eq!(state.set().map(|s| s.reflectors.len()), Some(15), "the artist may go on");

    // The level loaded, then the set opened: warned at once.
    state.open_set(&path);
    assert_eq!(mismatch_warnings(&state), 2, "{:?}", state.messages.entries());

    // The set of this very level: no warning.
    let matching = dir.path().join("room.ppr.json");
    demo_document(&ExtractParams::no_split()).set.save(&matching).expect("saved");
    let mut state = InspectorState::default();
    state.open_level(&demo_level_path(), Some(&matching));
    assert!(state.wait_for_job(Duration::from_secs(120)));
    assert!(
        state.messages.entries().iter().all(|m| !m.text.contains("differs")),
        "{:?}",
        state.messages.entries()
    );
}

/// Saving keeps a symlinked set a link (its target is written) and keeps the modes of the
/// set and of its edits file (the atomic save used to leave plain 0600 files).
#[cfg(unix)]
#[test]
fn saving_keeps_symlinks_and_file_modes() {
    use std::os::unix::fs::{PermissionsExt, symlink};
    let mode = |p: &std::path::Path| std::fs::metadata(p).expect("metadata").permissions().mode() & 0o777;
    let dir = tempfile::tempdir().expect("tempdir");
    let shared = dir.path().join("shared");
    std::fs::create_dir(&shared).expect("folder");
    let target = shared.join("room.ppr.json");
    let doc = demo_document(&ExtractParams::default());
    doc.set.save(&target).expect("saved");
    std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o664)).expect("chmod");
    let link = dir.path().join("room.ppr.json");
    symlink("shared/room.ppr.json", &link).expect("link");

    let mirror = id_named(&doc, "mirror on mirror_wall");
    let mut state = state_with(doc);
    assert!(state.apply(EditCommand::Rename { id: mirror, name: "hero mirror".into() }));
    state.save_as(&link).expect("saved");
    assert!(std::fs::symlink_metadata(&link).expect("lstat").file_type().is_symlink(), "still a link");
    assert_eq!(mode(&target), 0o664);
    let saved = ReflectorSet::load(&target).expect("the target holds the set");
    assert_eq!(saved.by_id(mirror).map(|r| r.name.as_str()), Some("hero mirror"));

    let edits = ppr_inspector::edits_file::edits_path(&link);
    std::fs::set_permissions(&edits, std::fs::Permissions::from_mode(0o640)).expect("chmod");
    assert!(state.apply(EditCommand::Rename { id: mirror, name: "villain mirror".into() }));
    state.save().expect("saved again");
    assert_eq!(mode(&edits), 0o640, "the edits file keeps its mode");
    assert_eq!(mode(&target), 0o664);
}
