//! The `extras.ppr` a node of the demo level carries (`{"ppr": {"reflector": …, "kind": …}}`,
//! read by `ppr-level`'s `extras.rs`): our own data inside a glTF field, so our own type.

use serde::Serialize;

/// `extras` understood by `ppr-extract`: `{"ppr": {"reflector": …, "kind": …}}`.
#[derive(Serialize, Debug, Clone, PartialEq, Eq)]
pub struct PprExtras {
    pub ppr: PprOverride,
}

/// The override itself.
#[derive(Serialize, Debug, Clone, PartialEq, Eq)]
pub struct PprOverride {
    pub reflector: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kind: Option<&'static str>,
}

impl PprExtras {
    /// The JSON text of glTF's `extras` field.
    pub fn to_raw(&self) -> Box<serde_json::value::RawValue> {
        serde_json::value::to_raw_value(self).expect("two plain fields always serialise")
    }
}
