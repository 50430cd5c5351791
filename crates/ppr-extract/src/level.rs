//! The level the extractor reads: `ppr-level`'s flattened world-space triangles, named
//! here so the stages write `crate::level::Level`.

#[cfg(test)]
pub use ppr_level::ReflectorOverride;
pub use ppr_level::{Level, MaterialInfo, TriangleSource};
