//! Finding the levels in a folder (`.glb` and `.gltf`, one folder level down too), for
//! tools and tests that open every level of a collection such as `../shared/scenes/`.

use std::path::{Path, PathBuf};

/// Every `.glb` and `.gltf` file in `dir` and its direct subfolders, sorted by path.
/// An unreadable folder gives no files.
pub fn level_files(dir: &Path) -> Vec<PathBuf> {
    let is_level = |p: &Path| {
        p.is_file()
            && p.extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| e.eq_ignore_ascii_case("glb") || e.eq_ignore_ascii_case("gltf"))
    };
    let entries = |d: &Path| -> Vec<PathBuf> {
        std::fs::read_dir(d)
            .map(|rd| rd.filter_map(|e| e.ok().map(|e| e.path())).collect())
            .unwrap_or_default()
    };
    let mut out = Vec::new();
    for entry in entries(dir) {
        if entry.is_dir() {
            out.extend(entries(&entry).into_iter().filter(|p| is_level(p)));
        } else if is_level(&entry) {
            out.push(entry);
        }
    }
    out.sort();
    out
}

/// The shared third-party scenes (`shared/scenes/` beside the repository, as CI has it) as
/// a crate of the workspace finds them from its manifest folder
/// (`env!("CARGO_MANIFEST_DIR")`, two levels below the repository).
///
/// # Errors
/// When the folder holds fewer than `at_least` levels (missing, or not checked out), a
/// message naming the folder and what was found.
pub fn shared_scene_files(crate_dir: &Path, at_least: usize) -> Result<Vec<PathBuf>, String> {
    let dir = crate_dir.join("../../../shared/scenes");
    let files = level_files(&dir);
    if files.len() < at_least {
        return Err(format!(
            "the shared scenes are missing from {} (found {files:?}, want at least {at_least})",
            dir.display()
        ));
    }
    Ok(files)
}
