//! Whether a set belongs to the level it is loaded with: `source.hash` against the level
//! file's hash (`blake3:<hex>` of its bytes, as the extractor records it).

use std::path::{Path, PathBuf};

use crate::ReflectorSet;

/// A set used with a level whose bytes differ from the ones it was extracted from.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "{} was extracted from a level whose content differs from {} (recorded hash {recorded}, the level's is \
     {found}): the reflectors may not match the level any more; re-extract it (ppr-extract {})",
    set.display(),
    level.display(),
    level.display()
)]
pub struct SourceMismatch {
    /// The set file.
    pub set: PathBuf,
    /// The level file.
    pub level: PathBuf,
    /// `source.hash` of the set.
    pub recorded: String,
    /// The level file's hash.
    pub found: String,
}

impl ReflectorSet {
    /// Checks that this set (read from `set_path`) was extracted from the level at
    /// `level_path`, whose hash is `level_hash`. A set or a level without a hash (built in
    /// code) cannot be checked and passes.
    ///
    /// # Errors
    /// [`SourceMismatch`] naming both files when the hashes differ.
    pub fn check_source(
        &self,
        set_path: &Path,
        level_path: &Path,
        level_hash: &str,
    ) -> Result<(), SourceMismatch> {
        if self.source.hash.is_empty() || level_hash.is_empty() || self.source.hash == level_hash {
            return Ok(());
        }
        Err(SourceMismatch {
            set: set_path.to_owned(),
            level: level_path.to_owned(),
            recorded: self.source.hash.clone(),
            found: level_hash.to_owned(),
        })
    }
}
