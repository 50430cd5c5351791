//! Reflector-set types and the versioned `*.ppr.json` file format.
//!
//! A [`ReflectorSet`] is what the extractor writes, the inspector edits and a game loads:
//! a list of analytical planar rectangles ([`Reflector`]) that enclose the reflective
//! areas of a level, each with the list of reflectors that may occlude it.
//!
//! Each reflector carries the perceptual roughness of its surface (glTF's definition:
//! 0 is a mirror, 1 fully rough), which a renderer may use to blur its reflection. Files
//! of version 1, written before roughness was recorded, still read: their reflectors get
//! roughness 0, and they are written back as version [`FORMAT_VERSION`].
//!
//! This crate knows nothing about glTF or wgpu. It owns the serde derives and the format
//! version; every other crate converts to and from these types.
//!
//! ```
//! use ppr_format::{Reflector, ReflectorKind, ReflectorSet};
//! use glam::{DVec2, DVec3};
//!
//! let mut set = ReflectorSet::new("level.glb");
//! set.reflectors.push(Reflector::new(
//!     0,
//!     "floor",
//!     ReflectorKind::Opaque,
//!     DVec3::ZERO,
//!     DVec3::Y, // the reflecting side
//!     DVec3::X,
//!     DVec2::new(5.0, 5.0),
//! ));
//! let json = set.to_json_string().unwrap();
//! let back = ReflectorSet::from_json_str(&json).unwrap();
//! assert_eq!(set, back);
//! ```

#[cfg(feature = "save")]
mod atomic_write;
#[cfg(feature = "save")]
pub use atomic_write::write_atomically;
pub mod edits;
mod error;
mod io;
mod reflector;
mod set;
mod source_check;
pub use source_check::SourceMismatch;
mod validate;
mod validated;

pub use error::{FormatError, InvalidField, ReflectorRef};
pub use reflector::{Reflector, ReflectorKind, ReflectorSource};
pub use set::{
    ExtractorInfo, FORMAT_NAME, FORMAT_VERSION, OLDEST_READABLE_VERSION, ReflectorSet, SourceInfo,
    reads_version,
};
pub use validate::{AXIS_TOLERANCE, MAX_COORDINATE, PARALLEL_GROUP_MAX_ANGLE_DEG, parallel_groups};
pub use validated::ValidatedSet;

/// The JSON Schema of the format, as published beside it in `schema/`.
pub const JSON_SCHEMA: &str = include_str!("../schema/ppr-reflector-set.schema.json");
