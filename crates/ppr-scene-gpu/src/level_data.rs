//! A level on the CPU, what the GPU meshes are made from: meshes, materials, textures,
//! placed instances and cameras.
//!
//! A [`LevelData`] comes from a `ppr-level` scene ([`LevelData::from_scene`],
//! `scene_import.rs`) or is built in code ([`LevelData::add_mesh`],
//! [`LevelData::add_instance`], ...) for synthetic test scenes. World transforms are `f64`
//! so that a level far from the origin keeps its precision until the per-frame
//! camera-relative matrices are computed.

use glam::{DMat4, DVec3, Vec3};

pub use crate::level_camera::LevelCamera;

/// A material as `ppr-level` reads it (the raster passes use its base colour and texture,
/// emissive, roughness, metallic, transmission, unlit, double-sidedness and `extras.ppr`).
pub use ppr_level::Material;
/// One vertex as the raster passes read it (32 bytes, interleaved): `ppr-level`'s.
pub use ppr_level::Vertex;

/// A triangle list with one material.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshPrimitive {
    /// The vertices.
    pub vertices: Vec<Vertex>,
    /// Triangle list indices into `vertices`, counter-clockwise front faces.
    pub indices: Vec<u32>,
    /// Index into [`LevelData::materials`].
    pub material: usize,
}

/// A mesh: the primitives one glTF mesh is made of.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Name from the file (or `#index`).
    pub name: String,
    /// The primitives.
    pub primitives: Vec<MeshPrimitive>,
}

impl Mesh {
    /// Its primitives, in order.
    pub fn iter(&self) -> std::slice::Iter<'_, MeshPrimitive> {
        self.primitives.iter()
    }
}

impl<'a> IntoIterator for &'a Mesh {
    type Item = &'a MeshPrimitive;
    type IntoIter = std::slice::Iter<'a, MeshPrimitive>;

    fn into_iter(self) -> Self::IntoIter {
        self.primitives.iter()
    }
}

/// An RGBA8 texture whose colour channels are sRGB encoded (a glTF base colour texture).
#[derive(Clone, Debug, PartialEq)]
pub struct LevelTexture {
    /// Name from the file (or `#index`).
    pub name: String,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// `width * height * 4` bytes, rows top to bottom.
    pub rgba8: Vec<u8>,
}

/// A mesh placed in the world by a node.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshInstance {
    /// Name of the node that placed it (or `#index`).
    pub node_name: String,
    /// Index into [`LevelData::meshes`].
    pub mesh: usize,
    /// World-from-object transform (the node hierarchy flattened), `f64`.
    pub world: DMat4,
    /// `extras.ppr.reflector` of the node or its mesh, if set: overrides the material's.
    pub reflector_hint: Option<bool>,
}

impl MeshInstance {
    /// Whether the transform mirrors (negative determinant): its triangles' winding flips.
    pub fn flips_winding(&self) -> bool {
        self.world.determinant() < 0.0
    }
}

/// A level: everything the testbed and the walkthrough draw.
///
/// Invariants: every `material` index is into `materials`, every `mesh` index into
/// `meshes`, every texture index into `textures`, and every index of a primitive is
/// within its vertex list; [`LevelData::validate`] checks them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LevelData {
    /// The meshes (shared by instances).
    pub meshes: Vec<Mesh>,
    /// The materials.
    pub materials: Vec<Material>,
    /// The base colour textures.
    pub textures: Vec<LevelTexture>,
    /// The meshes as placed in the world.
    pub instances: Vec<MeshInstance>,
    /// The cameras of the file, in node order.
    pub cameras: Vec<LevelCamera>,
    /// Things that were skipped while loading (unsupported primitive modes, ...).
    pub warnings: Vec<String>,
    /// `blake3:<hex>` of the file's bytes (empty for levels built in code), compared with
    /// a set's `source.hash` ([`ppr_format::ReflectorSet::check_source`]).
    pub source_hash: String,
}

impl LevelData {
    /// An empty level.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a material and returns its index.
    pub fn add_material(&mut self, material: Material) -> usize {
        self.materials.push(material);
        self.materials.len() - 1
    }

    /// Adds a texture and returns its index.
    pub fn add_texture(&mut self, texture: LevelTexture) -> usize {
        self.textures.push(texture);
        self.textures.len() - 1
    }

    /// Adds a mesh and returns its index.
    pub fn add_mesh(&mut self, mesh: Mesh) -> usize {
        self.meshes.push(mesh);
        self.meshes.len() - 1
    }

    /// Places mesh `mesh` with the world transform `world`.
    pub fn add_instance(&mut self, node_name: impl Into<String>, mesh: usize, world: DMat4) {
        self.instances.push(MeshInstance { node_name: node_name.into(), mesh, world, reflector_hint: None });
    }

    /// The camera with the given name.
    pub fn camera(&self, name: &str) -> Option<&LevelCamera> {
        self.cameras.iter().find(|c| c.name == name)
    }

    /// World-space bounding box of every placed vertex (`None` for an empty level).
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for inst in &self.instances {
            for prim in &self.meshes[inst.mesh].primitives {
                for v in &prim.vertices {
                    let p = inst.world.transform_point3(Vec3::from(v.position).as_dvec3());
                    lo = lo.min(p);
                    hi = hi.max(p);
                }
            }
        }
        (lo.x <= hi.x).then_some((lo, hi))
    }

    /// The same level moved by `offset` (instances and cameras), for precision tests.
    pub fn translated(&self, offset: DVec3) -> Self {
        let shift = DMat4::from_translation(offset);
        let mut level = self.clone();
        for inst in &mut level.instances {
            inst.world = shift * inst.world;
        }
        for cam in &mut level.cameras {
            cam.world = shift * cam.world;
        }
        level
    }

    /// Total number of triangles drawn (instances times their meshes' triangles).
    pub fn triangle_count(&self) -> usize {
        self.instances
            .iter()
            .map(|i| self.meshes[i.mesh].primitives.iter().map(|p| p.indices.len() / 3).sum::<usize>())
            .sum()
    }

    /// Checks the index invariants.
    ///
    /// # Errors
    /// A message naming the first instance, primitive or material that breaks one.
    pub fn validate(&self) -> Result<(), String> {
        for (i, inst) in self.instances.iter().enumerate() {
            if inst.mesh >= self.meshes.len() {
                return Err(format!("instances[{i}] ({}): mesh {} out of range", inst.node_name, inst.mesh));
            }
        }
        for mesh in &self.meshes {
            for (k, prim) in mesh.primitives.iter().enumerate() {
                if prim.material >= self.materials.len() {
                    return Err(format!(
                        "mesh {} primitive {k}: material {} out of range",
                        mesh.name, prim.material
                    ));
                }
                if prim.indices.len() % 3 != 0 {
                    return Err(format!(
                        "mesh {} primitive {k}: index count is not a multiple of 3",
                        mesh.name
                    ));
                }
                if let Some(&bad) = prim.indices.iter().find(|&&ix| ix as usize >= prim.vertices.len()) {
                    return Err(format!("mesh {} primitive {k}: index {bad} out of range", mesh.name));
                }
            }
        }
        for m in &self.materials {
            if let Some(t) = m.base_color_texture.filter(|&t| t >= self.textures.len()) {
                return Err(format!("material {}: texture {t} out of range", m.name));
            }
        }
        for t in &self.textures {
            if t.rgba8.len() != (t.width as usize) * (t.height as usize) * 4 {
                return Err(format!(
                    "texture {}: {} bytes for {}x{}",
                    t.name,
                    t.rgba8.len(),
                    t.width,
                    t.height
                ));
            }
        }
        Ok(())
    }
}
