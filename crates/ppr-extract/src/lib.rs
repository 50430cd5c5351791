//! glTF level → reflector set: the library behind the `ppr-extract` command.
//!
//! ```text
//! load_level ─► select ─► cluster (weld, connect, grow coplanar regions, merge near-planar)
//!            ─► regions (plane fit, polygons) ─► fit (min-area rectangles, splits, budget)
//!            ─► parallel groups, stable ids, occluder lists ─► ReflectorSet
//! ```
//!
//! - [`load_level`] (from `ppr-level`, the loader every tool shares) reads `.glb` /
//!   `.gltf` (external, embedded or meshopt-compressed buffers, quantized positions, skins
//!   at rest pose, GPU instancing) into world-space triangles with their source node, mesh
//!   and material ([`Level`]).
//! - [`extract`] turns a level into an [`Extraction`]: the [`ppr_format::ReflectorSet`],
//!   each reflector's region vertices, warnings and stage timings. Candidate selection is
//!   documented in [`select`]; near-planar merging in [`near_planar`]; splitting in
//!   [`split`]; the density budget in [`budget`]; the occluder rule and its cap in
//!   [`occluders`]; each reflector's roughness (the area-weighted mean of its surface's
//!   glTF roughness, texture included) in [`roughness`].
//!
//! Defaults ([`ExtractParams::default`], measured on the shared scenes and generated
//! levels in `docs/perf/extract.md`): vertices within 5 mm of their plane, gaps up to
//! 5 mm bridged, 1° between a triangle and its plane, regions under 0.01 m² dropped,
//! touching regions within 2° merged when the reflection error at 1 m stays under 8 cm,
//! at most 128 rectangles per 10 m cube, occluders anywhere in front, at most 64 per list.
//! Every stage is linear in the triangles; the fit and occluder stages use every core
//! ([`ExtractParams::threads`]) without changing the output.
//!
//! Tolerances and sizes are physical (metres, square metres, degrees: glTF's units; see
//! [`ExtractParams`]), never fractions of the level's size, so the same room gives the same
//! rectangles alone or inside a large level. Geometry is computed in `f64` around a local
//! origin, so levels 100 km from the origin extract like levels at it; levels modelled in
//! other units convert the parameters ([`ExtractParams::in_level_units`]). Extraction is
//! deterministic.
//!
//! ```
//! use glam::DVec3;
//! use ppr_extract::{ExtractParams, Level, MaterialInfo, extract};
//!
//! // A 4 m × 2 m mirror-like floor made of two triangles.
//! let (a, b, c, d) = (DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), DVec3::new(4.0, 0.0, -2.0), DVec3::new(0.0, 0.0, -2.0));
//! let floor = MaterialInfo { roughness: 0.05, ..MaterialInfo::gltf_default() };
//! let level = Level::from_triangles("floor", &[[a, b, c], [a, c, d]], floor);
//! let out = extract(&level, &ExtractParams::default(), &|_, _| {});
//! assert_eq!(out.set.reflectors.len(), 1);
//! let r = &out.set.reflectors[0];
//! assert!((r.area() - 8.0).abs() < 1e-9 && r.normal.y > 0.999);
//! assert_eq!(r.roughness, 0.05);
//! ```

// `!(x > 0.0)` is deliberate throughout: unlike `x <= 0.0` it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod budget;
pub mod cluster;
mod connectivity;
pub mod edits_file;
mod extract;
mod extraction;
pub mod fit;
pub mod generated_levels;
pub mod hull;
mod int_hash;
mod level;
pub mod manual_edits;
pub mod near_planar;
mod occluder_geometry;
pub mod occluders;
pub mod parallel;
mod parallel_map;
mod params;
pub mod plane;
mod point_hierarchy;
pub mod polygon;
pub mod rect_fit;
pub mod roughness;
mod scale;
pub mod select;
pub mod split;
pub mod stable_id;
pub mod summary;

pub use extract::extract;
pub use extraction::{Extraction, ExtractionStats, Stage, Warning};
pub use params::{CandidateRule, ExtractParams};
pub use ppr_level::{
    Level, LevelTriangle, LoadError, MaterialInfo, ReflectorOverride, TriangleSource, can_read_extension,
    load_level, load_level_from_bytes,
};
pub use scale::SceneScale;
