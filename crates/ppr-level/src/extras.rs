//! `extras.ppr` of nodes, meshes and materials: the one reader of the workspace.

use std::path::Path;

use ppr_format::ReflectorKind;

use crate::LoadError;

/// Per node, mesh or material override read from glTF `extras` (`{"ppr": {...}}`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ReflectorOverride {
    /// `"reflector": true|false`: force the triangles in or out of the candidate set.
    pub reflector: Option<bool>,
    /// `"kind": "opaque"|"transparent"|"water"`: force the reflector kind.
    pub kind: Option<ReflectorKind>,
}

impl ReflectorOverride {
    /// This override where it says something, else `fallback`.
    pub fn or(self, fallback: ReflectorOverride) -> ReflectorOverride {
        ReflectorOverride {
            reflector: self.reflector.or(fallback.reflector),
            kind: self.kind.or(fallback.kind),
        }
    }
}

/// Reads `{"ppr": {"reflector": bool, "kind": "..."}}` from a glTF `extras` value.
/// `owner` names the object for error messages, e.g. `materials[2] ("Glass")`.
pub(crate) fn read_override(
    path: &Path,
    owner: &str,
    extras: &gltf::json::Extras,
) -> Result<ReflectorOverride, LoadError> {
    let Some(raw) = extras else { return Ok(ReflectorOverride::default()) };
    let bad =
        |reason: String| LoadError::BadExtras { path: path.to_owned(), owner: owner.to_owned(), reason };
    let value: serde_json::Value =
        serde_json::from_str(raw.get()).map_err(|e| bad(format!("extras are not JSON: {e}")))?;
    let Some(ppr) = value.get("ppr") else { return Ok(ReflectorOverride::default()) };
    let obj = ppr.as_object().ok_or_else(|| bad("must be an object".into()))?;
    let mut out = ReflectorOverride::default();
    for (key, v) in obj {
        match key.as_str() {
            "reflector" => {
                out.reflector = Some(
                    v.as_bool().ok_or_else(|| bad(format!("`reflector` must be true or false, not {v}")))?,
                )
            }
            "kind" => {
                let s = v.as_str().ok_or_else(|| bad(format!("`kind` must be a string, not {v}")))?;
                out.kind = Some(s.parse::<ReflectorKind>().map_err(bad)?);
            }
            other => return Err(bad(format!("unknown key `{other}` (expected `reflector` or `kind`)"))),
        }
    }
    Ok(out)
}

/// `name` or `#index` when the object has no name.
pub(crate) fn display_name(name: Option<&str>, index: usize) -> String {
    match name {
        Some(n) if !n.is_empty() => n.to_owned(),
        _ => format!("#{index}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(extras: &str, expected: Result<ReflectorOverride, &str>) {
        let raw = Some(serde_json::value::RawValue::from_string(extras.to_owned()).unwrap());
        let got = read_override(Path::new("l.gltf"), "nodes[0]", &raw);
        match (got, expected) {
            (Ok(g), Ok(e)) => assert_eq!(g, e),
            (Err(g), Err(e)) => assert!(g.to_string().contains(e), "{g}"),
            (g, e) => panic!("{extras}: got {g:?}, expected {e:?}"),
        }
    }

    #[test]
    fn reads_overrides() {
        let none = ReflectorOverride::default();
        check("{}", Ok(none));
        check(r#"{"other": 1}"#, Ok(none));
        check(
            r#"{"ppr": {"reflector": false}}"#,
            Ok(ReflectorOverride { reflector: Some(false), kind: None }),
        );
        check(
            r#"{"ppr": {"reflector": true, "kind": "water"}}"#,
            Ok(ReflectorOverride { reflector: Some(true), kind: Some(ReflectorKind::Water) }),
        );
        check(r#"{"ppr": {"kind": "lava"}}"#, Err("unknown reflector kind `lava`"));
        check(r#"{"ppr": {"reflector": "yes"}}"#, Err("`reflector` must be true or false"));
        check(r#"{"ppr": {"refletcor": true}}"#, Err("unknown key `refletcor`"));
        check(r#"{"ppr": 3}"#, Err("must be an object"));
    }
}
