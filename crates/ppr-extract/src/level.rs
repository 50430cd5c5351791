//! A loaded level: world-space triangles with where each came from and its material.

use glam::DVec3;
use ppr_format::ReflectorKind;

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

/// The material properties candidate selection looks at (glTF factors, textures ignored).
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialInfo {
    /// Material name, or `#index` when it has none.
    pub name: String,
    /// `pbrMetallicRoughness.roughnessFactor` (glTF default 1).
    pub roughness: f64,
    /// `pbrMetallicRoughness.metallicFactor` (glTF default 1).
    pub metallic: f64,
    /// `KHR_materials_transmission.transmissionFactor` (0 when absent).
    pub transmission: f64,
    /// `KHR_materials_clearcoat.clearcoatFactor` (0 when absent).
    pub clearcoat: f64,
    /// `KHR_materials_clearcoat.clearcoatRoughnessFactor` (0 when absent).
    pub clearcoat_roughness: f64,
    /// Override from the material's extras.
    pub extras: ReflectorOverride,
    /// The material has a normal texture (reflectors fitted to it get `normal_map`).
    pub normal_map: bool,
}

impl MaterialInfo {
    /// The glTF default material (used by primitives without one).
    pub fn gltf_default() -> Self {
        Self {
            name: "(default material)".into(),
            roughness: 1.0,
            metallic: 1.0,
            transmission: 0.0,
            clearcoat: 0.0,
            clearcoat_roughness: 0.0,
            extras: ReflectorOverride::default(),
            normal_map: false,
        }
    }
}

/// Where a group of triangles came from: one primitive of one mesh instanced by one node.
#[derive(Clone, Debug, PartialEq)]
pub struct TriangleSource {
    /// Node name, or `#index`.
    pub node: String,
    /// Mesh name, or `#index`.
    pub mesh: String,
    /// Index into [`Level::materials`].
    pub material: u32,
    /// Override from the node's extras.
    pub node_extras: ReflectorOverride,
    /// Override from the mesh's extras.
    pub mesh_extras: ReflectorOverride,
}

/// One world-space triangle. Its front face is counter-clockwise: `(b - a) × (c - a)`
/// points to the side it faces (winding already flipped for mirroring transforms).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelTriangle {
    /// Corners in world space, metres.
    pub positions: [DVec3; 3],
    /// Index into [`Level::sources`].
    pub source: u32,
}

impl LevelTriangle {
    /// `(b - a) × (c - a)`: twice the area, along the front-facing normal.
    pub fn cross(&self) -> DVec3 {
        let [a, b, c] = self.positions;
        (b - a).cross(c - a)
    }
}

/// A flattened level: every triangle of the scene in world space.
///
/// Invariants: every `source` indexes `sources`, every source's `material` indexes
/// `materials`, and every position is finite.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Level {
    /// The file it was read from, as given.
    pub path: String,
    /// `blake3:<hex>` of the file's bytes (empty for levels built in memory).
    pub hash: String,
    /// Every triangle of the default scene, instanced and transformed.
    pub triangles: Vec<LevelTriangle>,
    /// Where the triangles came from.
    pub sources: Vec<TriangleSource>,
    /// The materials the sources refer to.
    pub materials: Vec<MaterialInfo>,
    /// Things the loader skipped that are not errors (point and line primitives, ...).
    pub notes: Vec<String>,
}

impl Level {
    /// A level from a triangle soup, all triangles from one node `"soup"` with `material`.
    pub fn from_triangles(path: &str, triangles: &[[DVec3; 3]], material: MaterialInfo) -> Self {
        Self {
            path: path.to_owned(),
            hash: String::new(),
            triangles: triangles.iter().map(|&positions| LevelTriangle { positions, source: 0 }).collect(),
            sources: vec![TriangleSource {
                node: "soup".into(),
                mesh: "soup".into(),
                material: 0,
                node_extras: ReflectorOverride::default(),
                mesh_extras: ReflectorOverride::default(),
            }],
            materials: vec![material],
            notes: Vec::new(),
        }
    }

    /// Checks the invariants stated on the type.
    ///
    /// # Errors
    /// A message naming the first triangle or source that breaks one.
    pub fn validate(&self) -> Result<(), String> {
        for (i, s) in self.sources.iter().enumerate() {
            if s.material as usize >= self.materials.len() {
                return Err(format!("sources[{i}].material {} is out of range", s.material));
            }
        }
        for (i, t) in self.triangles.iter().enumerate() {
            if t.source as usize >= self.sources.len() {
                return Err(format!("triangles[{i}].source {} is out of range", t.source));
            }
            if !t.positions.iter().all(|p| p.is_finite()) {
                return Err(format!("triangles[{i}] has a non-finite position"));
            }
        }
        Ok(())
    }

    /// Axis-aligned bounds of every triangle: `(min, max)`, or `None` for an empty level.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let mut it = self.triangles.iter().flat_map(|t| t.positions);
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }
}
