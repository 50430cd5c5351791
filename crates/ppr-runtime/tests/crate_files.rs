//! The publishable crates (`ppr-runtime`, `ppr-format`) read no file from outside their
//! own directory: every `include_str!` resolves inside the crate, so `cargo package`
//! takes what it needs (the WGSL lives in `shaders/` of the crate).

use std::path::{Path, PathBuf};

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("readable source directory") {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The paths of the `include_str!("...")` calls in `text`.
fn included(text: &str) -> Vec<String> {
    text.match_indices("include_str!(\"")
        .filter_map(|(at, m)| {
            let rest = &text[at + m.len()..];
            rest.find('"').map(|end| rest[..end].to_owned())
        })
        .collect()
}

#[test]
fn every_included_file_lies_inside_its_crate() {
    let runtime = Path::new(env!("CARGO_MANIFEST_DIR"));
    let format = runtime.join("../ppr-format");
    let mut checked = 0;
    for krate in [runtime.to_path_buf(), format] {
        let root = krate.canonicalize().expect("crate directory");
        let mut files = Vec::new();
        rust_files(&root.join("src"), &mut files);
        for file in files {
            let text = std::fs::read_to_string(&file).expect("readable source");
            for rel in included(&text) {
                let target = file.parent().expect("file in a directory").join(&rel);
                let resolved = target.canonicalize().unwrap_or_else(|e| {
                    panic!("{}: include_str!(\"{rel}\") does not resolve: {e}", file.display())
                });
                assert!(
                    resolved.starts_with(&root),
                    "{}: include_str!(\"{rel}\") reads {} outside {}",
                    file.display(),
                    resolved.display(),
                    root.display()
                );
                checked += 1;
            }
        }
    }
    assert!(checked >= 10, "the runtime's WGSL files must be found: {checked}");
}
