//! The demo level and documents made from it.

use std::path::PathBuf;

use ppr_extract::ExtractParams;
use ppr_inspector::document::Document;

/// `assets/demo_room.glb`.
pub fn demo_level_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/demo_room.glb")
}

/// The demo level extracted with `params`, as a document.
pub fn demo_document(params: &ExtractParams) -> Document {
    let level = ppr_extract::load_level(demo_level_path()).expect("demo level loads");
    Document::from_extraction(&ppr_extract::extract(&level, params, &|_, _| {}))
}

/// Id of the first reflector whose name starts with `prefix`.
pub fn id_named(doc: &Document, prefix: &str) -> u32 {
    doc.set
        .reflectors
        .iter()
        .find(|r| r.name.starts_with(prefix))
        .unwrap_or_else(|| panic!("no reflector named {prefix}..."))
        .id
}
