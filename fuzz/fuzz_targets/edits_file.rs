//! Fuzz target: any bytes as a `*.ppr.edits.json` manual-edits file through
//! `ppr-extract`'s reader, against a small set whose ids the edits may name.

#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use ppr_extract::edits_file::parse_edits;
use ppr_format::ReflectorSet;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let set = ReflectorSet::new("room.glb");
    let _ = parse_edits(Path::new("room.ppr.edits.json"), text, &set);
});
