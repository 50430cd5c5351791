//! The `*.ppr.json` asset: a reflector set loaded, checked and hot-reloaded by Bevy's asset server.

use std::path::PathBuf;
use std::sync::Arc;

use bevy::asset::io::Reader;
use bevy::asset::{Asset, AssetLoader, LoadContext};
use bevy::reflect::TypePath;
use ppr_format::{FormatError, ReflectorSet};

/// A validated reflector set, as [`ReflectorSetLoader`] reads it from a `*.ppr.json` file.
///
/// The set is behind an [`Arc`] so that handing it to the render world each frame is a
/// pointer copy; a reload replaces the `Arc`, which is how the render world sees a change.
#[derive(Asset, TypePath, Debug, Clone)]
pub struct PprReflectorSet {
    /// The set, valid (`ReflectorSet::validate` passed when it was loaded).
    pub set: Arc<ReflectorSet>,
}

/// Loads `*.ppr.json` files into [`PprReflectorSet`]s.
#[derive(Default, TypePath)]
pub struct ReflectorSetLoader;

/// Why a `*.ppr.json` file did not load; Bevy reports it as the asset's load error.
#[derive(Debug, thiserror::Error)]
pub enum ReflectorSetLoadError {
    /// The asset reader failed.
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        /// The asset path.
        path: PathBuf,
        /// What the reader said.
        source: std::io::Error,
    },
    /// The file is not UTF-8 text.
    #[error("{}: not UTF-8 text: {source}", path.display())]
    NotText {
        /// The asset path.
        path: PathBuf,
        /// Where the text broke.
        source: std::str::Utf8Error,
    },
    /// The file is not a valid reflector set: the message names the reflector and field.
    #[error("{}: {source}", path.display())]
    Format {
        /// The asset path.
        path: PathBuf,
        /// `ppr-format`'s error, naming the field (`reflectors[3].roughness`, ...).
        source: FormatError,
    },
}

/// Parses and validates a set's text; `path` only names the file in the error.
///
/// # Errors
/// [`ReflectorSetLoadError::NotText`] or [`ReflectorSetLoadError::Format`].
pub fn parse_reflector_set(path: PathBuf, bytes: &[u8]) -> Result<ReflectorSet, ReflectorSetLoadError> {
    let text = match std::str::from_utf8(bytes) {
        Ok(text) => text,
        Err(source) => return Err(ReflectorSetLoadError::NotText { path, source }),
    };
    let checked = ReflectorSet::from_json_str(text).and_then(|set| set.validate().map(|()| set));
    checked.map_err(|source| ReflectorSetLoadError::Format { path, source })
}

impl AssetLoader for ReflectorSetLoader {
    type Asset = PprReflectorSet;
    type Settings = ();
    type Error = ReflectorSetLoadError;

    async fn load(
        &self,
        reader: &mut dyn Reader,
        _settings: &(),
        load_context: &mut LoadContext<'_>,
    ) -> Result<PprReflectorSet, ReflectorSetLoadError> {
        let path = load_context.path().path().to_path_buf();
        let mut bytes = Vec::new();
        if let Err(source) = reader.read_to_end(&mut bytes).await {
            return Err(ReflectorSetLoadError::Read { path, source });
        }
        let set = parse_reflector_set(path, &bytes)?;
        Ok(PprReflectorSet { set: Arc::new(set) })
    }

    fn extensions(&self) -> &[&str] {
        &["ppr.json"]
    }
}
