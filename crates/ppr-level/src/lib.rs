//! glTF file → CPU level: the one loader every tool of the workspace reads levels through
//! (the extractor, the testbed and `ppr-render`, the inspector, the walkthrough and the
//! bench), so whatever one tool accepts, all accept.
//!
//! ```text
//! bytes ─► container (.glb chunks | JSON) ─► extensionsRequired ─► glTF validation
//!       ─► buffers (BIN chunk, data: URIs, relative files; EXT_meshopt_compression views)
//!       ─► Scene: materials, base colour textures, meshes (positions f64, normals,
//!          UV set 0, triangle lists), instances (f64 world, EXT_mesh_gpu_instancing,
//!          skins baked at rest pose), cameras ─► Level: world-space triangles
//! ```
//!
//! - [`load_scene`] gives a [`Scene`], what renderers draw: shared meshes placed by
//!   [`Instance`]s, [`Material`]s (base colour, alpha mode, roughness, metallic,
//!   transmission, clearcoat, unlit, double-sidedness, `extras.ppr`, the green channel of
//!   the metallic-roughness texture as a [`RoughnessMap`]), decoded base colour
//!   [`Texture`]s and the file's [`Camera`]s.
//! - [`load_level`] gives a [`Level`], what the extractor reads: every triangle in world
//!   space with the node, mesh and material it came from, and its UV set 0 where a
//!   material has a roughness map ([`Level::from_scene`]).
//! - `extras.ppr` (`{"ppr": {"reflector": bool, "kind": "opaque|transparent|water"}}` on a
//!   node, mesh or material) is read in one place into a [`ReflectorOverride`]; a
//!   malformed one is an error that names its owner.
//!
//! Decoded: `KHR_mesh_quantization` (any integer or normalized component type),
//! `EXT_meshopt_compression` (meshoptimizer's decoders and filters),
//! `EXT_mesh_gpu_instancing`, sparse accessors, strips and fans, skins (at rest pose),
//! mirroring transforms (winding flipped). Tolerated when required, since they do not
//! change geometry: lights, texture and material extensions ([`can_read_extension`]). Any
//! other required extension is refused by name.
//!
//! Safety: every count, offset and stride is checked (with overflow-checked arithmetic)
//! against the bytes it reads before anything is allocated; an accessor without a buffer
//! view (sparse only) may not describe more bytes than the file's buffers hold; buffer
//! URIs must be relative paths inside the level's folder (no absolute path, no `..`, no
//! scheme) to regular files, and only `byteLength` bytes are read; the node tree is walked
//! without recursion, refusing cycles and trees deeper than [`MAX_NODE_DEPTH`]; what the
//! nodes place (instances, triangles, vertices) is counted as they are read, against
//! [`LoadParams::max_triangles`]. Every error names the file and the field ([`LoadError`]).
//!
//! Normals: a primitive without `NORMAL` gets flat normals, as the glTF specification
//! asks (§3.7.2.1): its triangles are unwelded so each corner carries its face's normal.
//! Flat is also what reflections need: a planar reflector's pixels get its exact plane
//! normal, where smooth normals would bend it towards the walls it shares vertices with.

// `!(x > 0.0)` is deliberate: unlike `x <= 0.0` it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod accessor;
mod buffers;
mod container;
mod error;
mod extras;
pub mod gltf_builder;
mod images;
mod level;
mod level_files;
mod load;
mod materials;
mod meshopt_views;
mod node_tree;
mod primitive_reader;
mod roughness_maps;
mod scene;
mod scene_reader;
mod uri;

pub use error::LoadError;
pub use extras::ReflectorOverride;
pub use level::{Level, LevelTriangle, MaterialInfo, TriangleSource};
pub use level_files::{level_files, shared_scene_files};
pub use load::{
    LoadParams, TextureLoading, can_read_extension, load_level, load_level_from_bytes, load_scene,
    load_scene_from_bytes,
};
pub use materials::{AlphaMode, Material};
pub use roughness_maps::{RoughnessMap, Wrap};
pub use scene::{Camera, CameraProjection, Instance, Mesh, Primitive, Scene, Texture, Vertex};

/// The deepest node hierarchy read: a node more than this many levels below a root is an
/// error that names it (real levels nest a few dozen levels at most).
pub const MAX_NODE_DEPTH: usize = 1024;

/// The most node visits of one scene walk (a node listed as the child of several parents
/// is visited once per path): beyond it the level is refused.
pub const MAX_NODE_VISITS: usize = 1_000_000;

/// The most world-space triangles a [`Level`] may hold, and a loaded [`Scene`] may place
/// (instancing and nodes listed under several parents multiply a file's triangles: a file
/// of a few kilobytes can ask for billions); beyond it the level is refused before any
/// instance is transformed or any triangle allocated. 2^24, about 17 million: 17 times the
/// largest level the extractor is measured on, and about 1.3 GB of [`LevelTriangle`]s.
pub const MAX_LEVEL_TRIANGLES: usize = 1 << 24;
