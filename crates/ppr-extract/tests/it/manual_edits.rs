//! Re-running `ppr-extract` over a set an artist edited: the edits beside it
//! (`*.ppr.edits.json`, written by the inspector through `ppr_extract::edits_file`) are
//! re-applied by stable id, what no longer matches is named, `--ignore-edits` drops them
//! explicitly and keeps the previous set.

use std::path::{Path, PathBuf};
use std::process::Command;

use ppr_extract::edits_file::save_edits;
use ppr_extract::manual_edits::ManualEdits;
use ppr_format::ReflectorSet;
use ppr_format::edits::edits_path;

fn extract(args: &[&Path]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_ppr-extract"))
        .args(args)
        .arg("--quiet")
        .output()
        .expect("run ppr-extract");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// The demo room copied into a fresh folder, extracted once: (folder, level, set).
fn extracted_demo_room() -> (tempfile::TempDir, PathBuf, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let level = dir.path().join("demo_room.glb");
    std::fs::copy(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/demo_room.glb"), &level).unwrap();
    let (code, err) = extract(&[&level]);
    assert_eq!(code, 0, "{err}");
    let set = dir.path().join("demo_room.ppr.json");
    (dir, level, set)
}

/// Edits the set as the inspector does: the reflector with `id` renamed, disabled, made
/// rough and shrunk, the set saved, its id recorded in the edits file beside it.
fn edit_as_the_inspector_does(set_path: &Path, set: &mut ReflectorSet, id: u32, edits: &mut ManualEdits) {
    let r = set.reflectors.iter_mut().find(|r| r.id == id).unwrap();
    r.name = format!("artist fix {id}");
    r.enabled = false;
    r.roughness = 0.42;
    r.half_extents *= 0.5;
    edits.edited.insert(id);
    set.save(set_path).unwrap();
    save_edits(set_path, edits).unwrap();
}

#[test]
fn an_edit_survives_re_extraction_and_a_stale_one_is_named() {
    let (_dir, level, set_path) = extracted_demo_room();
    let fresh = ReflectorSet::load(&set_path).unwrap();
    assert!(fresh.reflectors.len() >= 2);
    let kept_id = fresh.reflectors[0].id;
    let mut set = fresh.clone();
    let mut edits = ManualEdits::default();
    edit_as_the_inspector_does(&set_path, &mut set, kept_id, &mut edits);
    // A reflector the extractor no longer produces (its id changed since): edited too.
    let stale_id = ppr_extract::manual_edits::fresh_ids(&set, 1)[0];
    set.reflectors[1].id = stale_id;
    set.reflectors[1].name = "gone floor".into();
    edit_as_the_inspector_does(&set_path, &mut set, stale_id, &mut edits);
    let edited = std::fs::read(&set_path).unwrap();

    let (code, err) = extract(&[&level]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains(&format!("re-applied: edit of \"artist fix {kept_id}\" (id {kept_id})")), "{err}");
    assert!(
        err.contains(&format!("edit of \"artist fix {stale_id}\" (id {stale_id}) no longer applies")),
        "{err}"
    );

    let after = ReflectorSet::load(&set_path).unwrap();
    assert_eq!(after.reflectors.len(), fresh.reflectors.len());
    let r = after.by_id(kept_id).expect("the edited reflector keeps its id");
    assert_eq!(r.name, format!("artist fix {kept_id}"));
    assert!(!r.enabled);
    assert_eq!(r.roughness, 0.42, "the artist's roughness beats the material's");
    assert_eq!(r.half_extents, fresh.reflectors[0].half_extents * 0.5);
    // The extractor's own reflector is back where the stale edit was.
    let back = after.by_id(fresh.reflectors[1].id).expect("the extractor's reflector is back");
    assert_eq!(back.name, fresh.reflectors[1].name);
    assert!(after.by_id(stale_id).is_none());
    // The edits file now describes the new set; the previous set is kept whole.
    let text = std::fs::read_to_string(edits_path(&set_path)).unwrap();
    let file = ppr_format::edits::EditsFile::from_json_str(&text).unwrap();
    assert_eq!(file.edited, vec![kept_id]);
    let previous = set_path.with_file_name("demo_room.ppr.previous.json");
    assert!(err.contains(&previous.display().to_string()), "{err}");
    assert_eq!(std::fs::read(&previous).unwrap(), edited);
    assert!(edits_path(&previous).exists());

    // Re-extracting again keeps the edit again (now with nothing stale).
    let (code, err) = extract(&[&level]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("no longer applies"), "{err}");
    assert_eq!(ReflectorSet::load(&set_path).unwrap().by_id(kept_id), Some(r));
}

#[test]
fn ignore_edits_writes_the_fresh_set_and_keeps_the_previous_one() {
    let (_dir, level, set_path) = extracted_demo_room();
    let fresh = ReflectorSet::load(&set_path).unwrap();
    let mut set = fresh.clone();
    let id = set.reflectors[0].id;
    edit_as_the_inspector_does(&set_path, &mut set, id, &mut ManualEdits::default());
    let edited = std::fs::read(&set_path).unwrap();

    let (code, err) = extract(&[&level, Path::new("--ignore-edits")]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("--ignore-edits"), "{err}");
    assert_eq!(ReflectorSet::load(&set_path).unwrap(), fresh);
    assert!(!edits_path(&set_path).exists());
    let previous = set_path.with_file_name("demo_room.ppr.previous.json");
    assert_eq!(std::fs::read(&previous).unwrap(), edited);
    assert!(edits_path(&previous).exists());
}

#[test]
fn edits_without_their_set_refuse_to_overwrite() {
    let (_dir, level, set_path) = extracted_demo_room();
    let mut set = ReflectorSet::load(&set_path).unwrap();
    let id = set.reflectors[0].id;
    edit_as_the_inspector_does(&set_path, &mut set, id, &mut ManualEdits::default());
    std::fs::write(&set_path, b"{ not json").unwrap();
    let (code, err) = extract(&[&level]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("demo_room.ppr.edits.json") && err.contains("--ignore-edits"), "{err}");
    assert_eq!(std::fs::read(&set_path).unwrap(), b"{ not json", "nothing was written");
}
