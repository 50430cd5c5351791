//! Fuzz target: any bytes as a `*.ppr.json` reflector set through `ppr-format`'s parse and
//! validation, then written back (a set that loads must save).

#![no_main]

use libfuzzer_sys::fuzz_target;
use ppr_format::ReflectorSet;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(set) = ReflectorSet::from_json_str(text) {
        set.to_json_string().expect("a set that parsed and validated writes back");
    }
});
