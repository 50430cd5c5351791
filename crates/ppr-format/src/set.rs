//! The reflector set: a versioned document holding every reflector of one level.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::Reflector;

/// Value of the `format` field of every reflector-set file.
pub const FORMAT_NAME: &str = "ppr-reflector-set";
/// The format version this build writes (and reads, with every version from
/// [`OLDEST_READABLE_VERSION`] on).
///
/// Version 2 added each reflector's `roughness` (perceptual, as glTF defines it); a
/// version-1 file reads with every `roughness` at 0 (the perfect mirrors it described).
pub const FORMAT_VERSION: u32 = 2;
/// The oldest format version this build reads; older versions' files are read as
/// [`FORMAT_VERSION`] (absent fields take their documented defaults).
pub const OLDEST_READABLE_VERSION: u32 = 1;

/// Whether this build reads files of `version`.
pub fn reads_version(version: u64) -> bool {
    (u64::from(OLDEST_READABLE_VERSION)..=u64::from(FORMAT_VERSION)).contains(&version)
}

/// Reads `version`, turning every version this build reads into [`FORMAT_VERSION`]: a
/// loaded set is always of the current version, and is written as such.
fn upgrade_version<'de, D: serde::Deserializer<'de>>(d: D) -> Result<u32, D::Error> {
    let version = u32::deserialize(d)?;
    Ok(if reads_version(u64::from(version)) { FORMAT_VERSION } else { version })
}

/// The level a set was extracted from.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SourceInfo {
    /// Path of the glTF file as given to the extractor.
    pub path: String,
    /// Content hash of that file (`"blake3:<hex>"`), empty when unknown.
    #[serde(default)]
    pub hash: String,
}

/// The program and the parameters that produced a set.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtractorInfo {
    /// Program name, e.g. `ppr-extract`.
    pub name: String,
    /// Program version.
    pub version: String,
    /// Parameters as the program chose to record them.
    #[serde(default)]
    pub params: BTreeMap<String, serde_json::Value>,
}

impl Default for ExtractorInfo {
    fn default() -> Self {
        Self { name: "manual".into(), version: String::new(), params: BTreeMap::new() }
    }
}

/// A level's reflectors: what `ppr-extract` writes and `ppr-runtime` renders.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReflectorSet {
    /// Always [`FORMAT_NAME`].
    pub format: String,
    /// Always [`FORMAT_VERSION`] once loaded (older versions are upgraded on reading).
    #[serde(deserialize_with = "upgrade_version")]
    pub version: u32,
    /// The level this set belongs to.
    pub source: SourceInfo,
    /// Who made it and how.
    #[serde(default)]
    pub extractor: ExtractorInfo,
    /// The reflectors; occluder lists index into this list.
    pub reflectors: Vec<Reflector>,
}

impl ReflectorSet {
    /// An empty set for the level at `source_path`.
    pub fn new(source_path: impl Into<String>) -> Self {
        Self {
            format: FORMAT_NAME.to_owned(),
            version: FORMAT_VERSION,
            source: SourceInfo { path: source_path.into(), hash: String::new() },
            extractor: ExtractorInfo::default(),
            reflectors: Vec::new(),
        }
    }

    /// The reflector with the given stable id.
    pub fn by_id(&self, id: u32) -> Option<&Reflector> {
        self.reflectors.iter().find(|r| r.id == id)
    }

    /// One more than the largest id in use (0 for an empty set).
    pub fn next_id(&self) -> u32 {
        self.reflectors.iter().map(|r| r.id + 1).max().unwrap_or(0)
    }
}
