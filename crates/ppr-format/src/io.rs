//! Reading and writing reflector sets as JSON text and files (writes are atomic).

use std::path::Path;

use crate::{FORMAT_NAME, FormatError, ReflectorSet};

impl ReflectorSet {
    /// Parses and validates a set from JSON text.
    ///
    /// The `format` and `version` fields are checked before anything else, so a file of
    /// another version is refused as such rather than with a field error.
    ///
    /// # Errors
    /// Any [`FormatError`] but `Read`, `Write` and `InFile`.
    pub fn from_json_str(text: &str) -> Result<Self, FormatError> {
        let value: serde_json::Value = serde_json::from_str(text)?;
        check_header(&value)?;
        let set: ReflectorSet = serde_path_to_error::deserialize(value)
            .map_err(|e| FormatError::Shape { path: e.path().to_string(), source: e.into_inner() })?;
        set.validate()?;
        Ok(set)
    }

    /// Validates the set and writes it as pretty-printed JSON.
    ///
    /// # Errors
    /// [`FormatError::Invalid`] (and friends) when the set breaks an invariant.
    pub fn to_json_string(&self) -> Result<String, FormatError> {
        self.validate()?;
        let mut text = serde_json::to_string_pretty(self)?;
        text.push('\n');
        Ok(text)
    }

    /// Reads, parses and validates the set at `path`.
    ///
    /// # Errors
    /// [`FormatError::Read`], or any parse or validation error wrapped in
    /// [`FormatError::InFile`] naming the path.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, FormatError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path)
            .map_err(|source| FormatError::Read { path: path.to_owned(), source })?;
        Self::from_json_str(&text).map_err(|e| e.in_file(path))
    }

    /// Validates the set and writes it to `path` atomically ([`crate::write_atomically`]): the
    /// text goes to a temporary file beside the file (beside a symlink's target, so the link
    /// stays), which gets the old file's permissions and is renamed over it. On failure
    /// `path` is left as it was and no temporary file remains.
    ///
    /// # Errors
    /// Validation errors (nothing is written) or [`FormatError::Write`].
    #[cfg(feature = "save")]
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), FormatError> {
        let path = path.as_ref();
        let text = self.to_json_string().map_err(|e| e.in_file(path))?;
        crate::write_atomically(path, text.as_bytes())
            .map_err(|source| FormatError::Write { path: path.to_owned(), source })
    }
}

fn check_header(value: &serde_json::Value) -> Result<(), FormatError> {
    let found = |key: &str| value.get(key).map_or_else(|| "missing".to_owned(), |v| v.to_string());
    if value.get("format").and_then(|v| v.as_str()) != Some(FORMAT_NAME) {
        return Err(FormatError::WrongFormat { found: found("format") });
    }
    if !value.get("version").and_then(|v| v.as_u64()).is_some_and(crate::set::reads_version) {
        return Err(FormatError::UnknownVersion { found: found("version") });
    }
    Ok(())
}
