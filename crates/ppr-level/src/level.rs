//! The level as the extractor reads it: world-space triangles with where each came from
//! and its material (and texture coordinates where roughness maps need them), flattened
//! from a [`Scene`].

use std::sync::Arc;

use glam::DVec3;

use crate::extras::ReflectorOverride;
use crate::{LoadError, MAX_LEVEL_TRIANGLES, Material, RoughnessMap, Scene};

/// The material properties the extractor reads: glTF factors for candidate selection, and
/// the roughness map for each reflector's roughness.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialInfo {
    /// Material name, or `#index` when it has none.
    pub name: String,
    /// `pbrMetallicRoughness.roughnessFactor` (glTF default 1).
    pub roughness: f64,
    /// `pbrMetallicRoughness.metallicFactor` (glTF default 1).
    pub metallic: f64,
    /// The metallic-roughness texture's green channel, which multiplies `roughness`
    /// (sampled with [`Level::uvs`]); `None` without one.
    pub roughness_map: Option<Arc<RoughnessMap>>,
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
            roughness_map: None,
            transmission: 0.0,
            clearcoat: 0.0,
            clearcoat_roughness: 0.0,
            extras: ReflectorOverride::default(),
            normal_map: false,
        }
    }
}

impl From<&Material> for MaterialInfo {
    fn from(m: &Material) -> Self {
        Self {
            name: m.name.clone(),
            roughness: f64::from(m.roughness),
            metallic: f64::from(m.metallic),
            roughness_map: m.roughness_map.clone(),
            transmission: f64::from(m.transmission),
            clearcoat: m.clearcoat,
            clearcoat_roughness: m.clearcoat_roughness,
            extras: m.ppr,
            normal_map: m.normal_map,
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
/// `materials`, every position is finite, and `uvs` is empty or one per triangle.
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
    /// UV set 0 of each triangle's corners (in the order of its `positions`), when a
    /// material has a roughness map; else empty (the extractor then reads factors only).
    /// `[0, 0]` for primitives without texture coordinates.
    pub uvs: Vec<[[f32; 2]; 3]>,
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
            uvs: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// Flattens `scene`: each instance's primitives in world space, node by node in the
    /// scene's order, the primitives of a node in order and, within one primitive, its
    /// `EXT_mesh_gpu_instancing` instances in order; winding flipped under mirroring
    /// transforms. One [`TriangleSource`] per node and primitive.
    ///
    /// # Errors
    /// [`LoadError::TooLarge`] past [`MAX_LEVEL_TRIANGLES`]; the position errors of
    /// [`Scene::world_positions`].
    pub fn from_scene(scene: &Scene) -> Result<Self, LoadError> {
        let total = scene.placed_triangles(MAX_LEVEL_TRIANGLES)?;
        let mut level = Level {
            path: scene.path.clone(),
            hash: scene.hash.clone(),
            triangles: Vec::with_capacity(total),
            sources: Vec::new(),
            materials: scene.materials.iter().map(MaterialInfo::from).collect(),
            uvs: Vec::new(),
            notes: scene.notes.clone(),
        };
        let with_uvs = level.materials.iter().any(|m| m.roughness_map.is_some());
        if with_uvs {
            level.uvs.reserve_exact(total);
        }
        let mut start = 0;
        while start < scene.instances.len() {
            // One node's instances: the first has `gpu_instance` 0.
            let end = (start + 1..scene.instances.len())
                .find(|&k| scene.instances[k].gpu_instance == 0)
                .unwrap_or(scene.instances.len());
            let group = &scene.instances[start..end];
            let first = &group[0];
            let mesh = &scene.meshes[first.mesh];
            let worlds: Vec<Vec<Vec<DVec3>>> =
                group.iter().map(|inst| scene.world_positions(inst)).collect::<Result<_, _>>()?;
            for (p, prim) in mesh.primitives.iter().enumerate() {
                let source = level.sources.len() as u32;
                level.sources.push(TriangleSource {
                    node: first.node_name.clone(),
                    mesh: mesh.name.clone(),
                    material: prim.material as u32,
                    node_extras: first.ppr,
                    mesh_extras: mesh.ppr,
                });
                for (inst, world) in group.iter().zip(&worlds) {
                    let flip = inst.world.determinant() < 0.0;
                    let world = &world[p];
                    level.triangles.extend(prim.indices.chunks_exact(3).map(|t| {
                        let [a, b, c] = [t[0], t[1], t[2]].map(|i| world[i as usize]);
                        LevelTriangle { positions: if flip { [a, c, b] } else { [a, b, c] }, source }
                    }));
                    if with_uvs {
                        let uv = |i: u32| prim.uvs.get(i as usize).map_or([0.0; 2], |v| v.to_array());
                        level.uvs.extend(prim.indices.chunks_exact(3).map(|t| {
                            let [a, b, c] = [t[0], t[1], t[2]].map(uv);
                            if flip { [a, c, b] } else { [a, b, c] }
                        }));
                    }
                }
            }
            start = end;
        }
        Ok(level)
    }

    /// Checks the invariants stated on the type.
    ///
    /// # Errors
    /// A message naming the first triangle or source that breaks one.
    pub fn validate(&self) -> Result<(), String> {
        if !self.uvs.is_empty() && self.uvs.len() != self.triangles.len() {
            return Err(format!("{} uvs for {} triangles", self.uvs.len(), self.triangles.len()));
        }
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
