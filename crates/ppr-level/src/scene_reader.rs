//! Builds the [`Scene`] from a glTF document: the default scene's nodes in depth-first
//! order, their meshes (read once, shared by instances), `EXT_mesh_gpu_instancing`,
//! skins baked at rest pose, and cameras.

use std::collections::HashMap;
use std::path::Path;

use glam::{DMat3, DMat4, DQuat, DVec3};

use crate::accessor::read_accessor;
use crate::buffers::BufferData;
use crate::extras::{display_name, read_override};
use crate::node_tree::{scene_order, world_matrices};
use crate::primitive_reader::{PrimitiveGeometry, PrimitiveReader};
use crate::{Camera, CameraProjection, Instance, LoadError, Mesh, Primitive, Scene};

/// Everything needed to read the document's nodes and meshes.
pub(crate) struct SceneReader<'a> {
    pub path: &'a Path,
    pub doc: &'a gltf::Document,
    pub data: &'a BufferData,
    /// Index of the glTF default material in the scene's material list.
    pub default_material: usize,
    /// [`crate::LoadParams::max_triangles`].
    pub max_triangles: usize,
}

/// What the instances placed so far add up to: each node visit and each of its
/// `EXT_mesh_gpu_instancing` instances is one instance carrying its mesh's triangles and
/// vertices, and its own memory (its node's name is copied into each). Checked before each
/// node's instances are made, so that the work and memory of a scene stay within
/// `max_triangles` (and the bytes of that many [`crate::LevelTriangle`]s) however its nodes
/// multiply.
#[derive(Default)]
struct Placed {
    instances: usize,
    triangles: usize,
    vertices: usize,
    bytes: usize,
}

impl Placed {
    fn add(
        &mut self,
        reader: &SceneReader,
        mesh: &Mesh,
        (copies, name_len): (usize, usize),
        node: usize,
    ) -> Result<(), LoadError> {
        let (triangles, vertices) = mesh.primitives.iter().fold((0usize, 0usize), |(t, v), p| {
            (t.saturating_add(p.indices.len() / 3), v.saturating_add(p.positions.len()))
        });
        self.instances = self.instances.saturating_add(copies);
        self.triangles = self.triangles.saturating_add(triangles.saturating_mul(copies));
        self.vertices = self.vertices.saturating_add(vertices.saturating_mul(copies));
        let one = size_of::<Instance>().saturating_add(name_len);
        self.bytes = self.bytes.saturating_add(one.saturating_mul(copies));
        let max = reader.max_triangles;
        let max_bytes = max.saturating_mul(size_of::<crate::LevelTriangle>());
        if self.instances > max
            || self.triangles > max
            || self.vertices > max.saturating_mul(3)
            || self.bytes > max_bytes
        {
            return Err(LoadError::TooLarge {
                path: reader.path.to_owned(),
                field: format!("nodes[{node}]"),
                reason: format!(
                    "with this node the scene places {} instances ({} bytes), {} triangles and {} vertices: more than the {max} instances and triangles, {} vertices and {max_bytes} bytes a level may hold",
                    self.instances,
                    self.bytes,
                    self.triangles,
                    self.vertices,
                    max.saturating_mul(3)
                ),
            });
        }
        Ok(())
    }
}

/// A glTF mesh read once: its triangle primitives and where it lives in the scene.
struct ReadMesh {
    scene_mesh: usize,
    geometry: Vec<PrimitiveGeometry>,
}

impl SceneReader<'_> {
    /// Appends the default scene's meshes, instances, cameras and notes to `scene`.
    pub(crate) fn read(&self, scene: &mut Scene) -> Result<(), LoadError> {
        let worlds = world_matrices(self.path, self.doc)?;
        let order = scene_order(self.path, self.doc)?;
        let nodes: Vec<gltf::Node> = self.doc.nodes().collect();
        let primitives =
            PrimitiveReader { path: self.path, data: self.data, default_material: self.default_material };
        let mut meshes: HashMap<usize, ReadMesh> = HashMap::new();
        let mut skipped_primitives = 0usize;
        let mut placed = Placed::default();
        for i in order {
            let node = &nodes[i];
            let node_name = display_name(node.name(), i);
            if let Some(camera) = node.camera() {
                scene.cameras.push(Camera {
                    name: camera.name().map_or_else(|| node_name.clone(), str::to_owned),
                    world: worlds[i],
                    projection: match camera.projection() {
                        gltf::camera::Projection::Perspective(p) => {
                            CameraProjection::Perspective { yfov: p.yfov(), znear: p.znear(), zfar: p.zfar() }
                        }
                        gltf::camera::Projection::Orthographic(o) => CameraProjection::Orthographic {
                            xmag: o.xmag(),
                            ymag: o.ymag(),
                            znear: o.znear(),
                            zfar: o.zfar(),
                        },
                    },
                });
            }
            let Some(mesh) = node.mesh() else { continue };
            let ppr = read_override(self.path, &format!("nodes[{i}] ({node_name:?})"), node.extras())?;
            if let std::collections::hash_map::Entry::Vacant(slot) = meshes.entry(mesh.index()) {
                let mut geometry = Vec::new();
                for prim in mesh.primitives() {
                    match primitives.read(&mesh, &prim)? {
                        Some(g) => geometry.push(g),
                        None => skipped_primitives += 1,
                    }
                }
                let name = display_name(mesh.name(), mesh.index());
                let mesh_ppr =
                    read_override(self.path, &format!("meshes[{}] ({name:?})", mesh.index()), mesh.extras())?;
                scene.meshes.push(Mesh {
                    name,
                    ppr: mesh_ppr,
                    primitives: geometry.iter().map(plain_primitive).collect(),
                });
                slot.insert(ReadMesh { scene_mesh: scene.meshes.len() - 1, geometry });
            }
            let read = &meshes[&mesh.index()];
            let instance = |mesh: usize, world: DMat4, gpu_instance: usize| Instance {
                node: i,
                node_name: node_name.clone(),
                ppr,
                mesh,
                world,
                gpu_instance,
            };
            match node.skin() {
                Some(skin) if read.geometry.iter().any(|g| g.skin.is_some()) => {
                    placed.add(self, &scene.meshes[read.scene_mesh], (1, node_name.len()), i)?;
                    let joints = self.joint_matrices(&skin, &worlds)?;
                    let baked = self.bake_skinned(&read.geometry, &joints, worlds[i], i)?;
                    let source = &scene.meshes[read.scene_mesh];
                    scene.meshes.push(Mesh { name: source.name.clone(), ppr: source.ppr, primitives: baked });
                    scene.instances.push(instance(scene.meshes.len() - 1, DMat4::IDENTITY, 0));
                }
                _ => {
                    let worlds = self.gpu_instances(node, worlds[i])?;
                    placed.add(self, &scene.meshes[read.scene_mesh], (worlds.len(), node_name.len()), i)?;
                    for (k, world) in worlds.into_iter().enumerate() {
                        scene.instances.push(instance(read.scene_mesh, world, k));
                    }
                }
            }
        }
        if skipped_primitives > 0 {
            scene.notes.push(format!("{skipped_primitives} point or line primitives skipped"));
        }
        Ok(())
    }

    fn invalid(&self, field: String, reason: String) -> LoadError {
        LoadError::Invalid { path: self.path.to_owned(), field, reason }
    }

    /// The node's world matrix, once per `EXT_mesh_gpu_instancing` instance if it has any.
    fn gpu_instances(&self, node: &gltf::Node, world: DMat4) -> Result<Vec<DMat4>, LoadError> {
        let Some(ext) = node.extension_value("EXT_mesh_gpu_instancing") else { return Ok(vec![world]) };
        let attrs = ext.get("attributes").and_then(|a| a.as_object());
        let read = |name: &str, comps: usize| -> Result<Option<Vec<Vec<f64>>>, LoadError> {
            let Some(index) = attrs.and_then(|a| a.get(name)).and_then(serde_json::Value::as_u64) else {
                return Ok(None);
            };
            let accessor =
                usize::try_from(index).ok().and_then(|i| self.doc.accessors().nth(i)).ok_or_else(|| {
                    self.invalid(
                        format!(
                            "nodes[{}].extensions.EXT_mesh_gpu_instancing.attributes.{name}",
                            node.index()
                        ),
                        format!("accessor {index} does not exist"),
                    )
                })?;
            let values = read_accessor(self.path, self.data, &accessor)?;
            if values.components != comps {
                return Err(LoadError::BadAccessor {
                    path: self.path.to_owned(),
                    field: format!("accessors[{index}]"),
                    reason: format!("instance {name} needs {comps} components"),
                });
            }
            Ok(Some((0..values.len()).map(|k| values.get(k).to_vec()).collect()))
        };
        let t = read("TRANSLATION", 3)?;
        let r = read("ROTATION", 4)?;
        let s = read("SCALE", 3)?;
        let count = [&t, &r, &s].iter().filter_map(|v| v.as_ref().map(Vec::len)).max().unwrap_or(0);
        let mut out = Vec::with_capacity(count);
        for k in 0..count {
            let tr = t.as_ref().and_then(|v| v.get(k)).map_or(DVec3::ZERO, |v| DVec3::new(v[0], v[1], v[2]));
            let rot = r
                .as_ref()
                .and_then(|v| v.get(k))
                .map_or(DQuat::IDENTITY, |v| DQuat::from_xyzw(v[0], v[1], v[2], v[3]).normalize());
            let sc = s.as_ref().and_then(|v| v.get(k)).map_or(DVec3::ONE, |v| DVec3::new(v[0], v[1], v[2]));
            out.push(world * DMat4::from_scale_rotation_translation(sc, rot, tr));
        }
        Ok(out)
    }

    fn joint_matrices(&self, skin: &gltf::Skin, worlds: &[DMat4]) -> Result<Vec<DMat4>, LoadError> {
        let inverse_binds = match skin.inverse_bind_matrices() {
            Some(acc) => {
                let v = read_accessor(self.path, self.data, &acc)?;
                if v.components != 16 {
                    return Err(LoadError::BadAccessor {
                        path: self.path.to_owned(),
                        field: format!("accessors[{}]", acc.index()),
                        reason: "inverseBindMatrices must be MAT4".into(),
                    });
                }
                (0..v.len()).map(|k| DMat4::from_cols_slice(v.get(k))).collect()
            }
            None => Vec::new(),
        };
        Ok(skin
            .joints()
            .enumerate()
            .map(|(k, j)| worlds[j.index()] * inverse_binds.get(k).copied().unwrap_or(DMat4::IDENTITY))
            .collect())
    }

    /// A skinned node's primitives in world space at rest pose (its unskinned primitives
    /// placed by the node's world matrix); a triangle whose first corner's matrix mirrors
    /// has its winding flipped.
    fn bake_skinned(
        &self,
        geometry: &[PrimitiveGeometry],
        joints: &[DMat4],
        node_world: DMat4,
        node: usize,
    ) -> Result<Vec<Primitive>, LoadError> {
        let mut out = Vec::with_capacity(geometry.len());
        for g in geometry {
            let mut matrices = Vec::with_capacity(g.positions.len());
            for k in 0..g.positions.len() {
                let Some(weights) = &g.skin else {
                    matrices.push(node_world);
                    continue;
                };
                let mut m = DMat4::ZERO;
                for &(j, w) in &weights[k] {
                    let joint = joints.get(j).ok_or_else(|| {
                        self.invalid(
                            format!("nodes[{node}].skin"),
                            format!("vertex {k} uses joint {j}, which the skin does not have"),
                        )
                    })?;
                    m += *joint * w;
                }
                matrices.push(m);
            }
            let mut p = plain_primitive(g);
            for (k, m) in matrices.iter().enumerate() {
                p.positions[k] = m.transform_point3(p.positions[k]);
                let normal_matrix = DMat3::from_mat4(*m).inverse().transpose();
                let n = (normal_matrix * p.normals[k].as_dvec3()).normalize_or_zero();
                if n.is_finite() && n != DVec3::ZERO {
                    p.normals[k] = n.as_vec3();
                }
            }
            for t in p.indices.chunks_exact_mut(3) {
                if matrices[t[0] as usize].determinant() < 0.0 {
                    t.swap(1, 2);
                }
            }
            out.push(p);
        }
        Ok(out)
    }
}

fn plain_primitive(g: &PrimitiveGeometry) -> Primitive {
    Primitive {
        positions: g.positions.clone(),
        normals: g.normals.clone(),
        uvs: g.uvs.clone(),
        indices: g.indices.clone(),
        material: g.material,
    }
}
