//! A level as renderers draw it: shared meshes placed by instances, materials, decoded
//! base colour textures and the file's cameras.

use std::path::Path;

use glam::{DMat4, DVec3, Vec2, Vec3};

use crate::extras::ReflectorOverride;
use crate::{LoadError, Material};

/// One vertex as the renderers' raster passes read it (32 bytes, interleaved).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    /// Object-space position, metres.
    pub position: [f32; 3],
    /// Object-space unit normal.
    pub normal: [f32; 3],
    /// Texture coordinate set 0.
    pub uv: [f32; 2],
}

/// A triangle list with one material, in its mesh's space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Primitive {
    /// Positions as read (`f64`, so quantized positions keep their exact value).
    pub positions: Vec<DVec3>,
    /// One unit normal per position: the file's, or flat (the triangles were unwelded).
    pub normals: Vec<Vec3>,
    /// Texture coordinate set 0, one per position, or empty when the file has none.
    pub uvs: Vec<Vec2>,
    /// Triangle list (strips and fans converted), counter-clockwise front faces; every
    /// index is below `positions.len()`.
    pub indices: Vec<u32>,
    /// Index into [`Scene::materials`].
    pub material: usize,
}

impl Primitive {
    /// The interleaved `f32` vertices a renderer uploads (UV 0 where the file has none).
    pub fn vertices(&self) -> Vec<Vertex> {
        (0..self.positions.len())
            .map(|i| Vertex {
                position: self.positions[i].as_vec3().to_array(),
                normal: self.normals.get(i).copied().unwrap_or(Vec3::Y).to_array(),
                uv: self.uvs.get(i).copied().unwrap_or(Vec2::ZERO).to_array(),
            })
            .collect()
    }
}

/// A glTF mesh: its triangle primitives (points and lines are skipped with a note).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Name from the file, or `#index`.
    pub name: String,
    /// `extras.ppr` of the mesh.
    pub ppr: ReflectorOverride,
    /// The primitives.
    pub primitives: Vec<Primitive>,
}

/// A mesh placed in the world by a node.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// Index of the node in the file.
    pub node: usize,
    /// The node's name, or `#index`.
    pub node_name: String,
    /// `extras.ppr` of the node.
    pub ppr: ReflectorOverride,
    /// Index into [`Scene::meshes`].
    pub mesh: usize,
    /// World-from-object transform, `f64` (identity for a skinned mesh, whose vertices
    /// are already in world space at rest pose).
    pub world: DMat4,
    /// Which of the node's `EXT_mesh_gpu_instancing` instances this is (0 for a node
    /// without the extension): a 0 starts a new node visit.
    pub gpu_instance: usize,
}

impl Instance {
    /// Whether the transform mirrors (negative determinant): the winding flips.
    pub fn flips_winding(&self) -> bool {
        self.world.determinant() < 0.0
    }
}

/// How a camera of the file projects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraProjection {
    /// Perspective.
    Perspective {
        /// Vertical field of view, radians.
        yfov: f32,
        /// Near plane, metres.
        znear: f32,
        /// Far plane, metres; `None` for infinite.
        zfar: Option<f32>,
    },
    /// Orthographic.
    Orthographic {
        /// Half width, metres.
        xmag: f32,
        /// Half height, metres.
        ymag: f32,
        /// Near plane, metres.
        znear: f32,
        /// Far plane, metres.
        zfar: f32,
    },
}

/// A camera of the file, placed by its node.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// The camera's name, or its node's when it has none.
    pub name: String,
    /// World transform of the camera node (looks down its local -Z, +Y up).
    pub world: DMat4,
    /// Its projection.
    pub projection: CameraProjection,
}

/// A decoded base colour texture: RGBA8 with sRGB-encoded colour channels.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// The image's name, or `#index`.
    pub name: String,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// `width * height * 4` bytes, rows top to bottom.
    pub rgba8: Vec<u8>,
}

/// A level on the CPU, as renderers draw it.
///
/// Invariants (as loaded): every `mesh`, `material` and texture index is in range, every
/// primitive's indices are below its vertex count and its normals (and UVs, when present)
/// are one per position, and every instanced vertex lies at a finite world position within
/// `ppr_format::MAX_COORDINATE` metres of the origin ([`Scene::world_positions`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// The file it was read from, as given.
    pub path: String,
    /// `blake3:<hex>` of the file's bytes (empty when loaded from bytes).
    pub hash: String,
    /// The meshes (shared by instances); a skinned node gets its own, baked at rest pose.
    pub meshes: Vec<Mesh>,
    /// The materials; the glTF default material is last.
    pub materials: Vec<Material>,
    /// The decoded base colour textures.
    pub textures: Vec<Texture>,
    /// The meshes as placed by the default scene's nodes, depth first in child order.
    pub instances: Vec<Instance>,
    /// The cameras of the default scene, in the same order.
    pub cameras: Vec<Camera>,
    /// What was skipped without being an error (point and line primitives, textures that
    /// do not decode, UV sets other than 0, ...).
    pub notes: Vec<String>,
}

impl Scene {
    /// The camera with this name.
    pub fn camera(&self, name: &str) -> Option<&Camera> {
        self.cameras.iter().find(|c| c.name == name)
    }

    /// The world positions of `instance`'s vertices, per primitive of its mesh.
    ///
    /// # Errors
    /// [`LoadError::NonFinitePosition`] or [`LoadError::PositionOutOfRange`] naming the
    /// node, for a vertex that lands at NaN, at infinity, or farther than
    /// `ppr_format::MAX_COORDINATE` from the origin; [`LoadError::Invalid`] for an
    /// instance whose mesh does not exist.
    pub fn world_positions(&self, instance: &Instance) -> Result<Vec<Vec<DVec3>>, LoadError> {
        let mesh = self.meshes.get(instance.mesh).ok_or_else(|| {
            self.broken(format!("instance of node {} names mesh {}", instance.node, instance.mesh))
        })?;
        let limit = ppr_format::MAX_COORDINATE;
        let mut vertex = 0;
        let mut out = Vec::with_capacity(mesh.primitives.len());
        for prim in &mesh.primitives {
            let mut world = Vec::with_capacity(prim.positions.len());
            for &p in &prim.positions {
                let w = instance.world.transform_point3(p);
                if !w.is_finite() {
                    return Err(LoadError::NonFinitePosition {
                        path: Path::new(&self.path).to_owned(),
                        field: format!("nodes[{}]", instance.node),
                        detail: format!("vertex {vertex} after the world transform"),
                    });
                }
                if w.abs().max_element() > limit {
                    return Err(LoadError::PositionOutOfRange {
                        path: Path::new(&self.path).to_owned(),
                        node: instance.node,
                        name: instance.node_name.clone(),
                        vertex,
                        position: w.to_array(),
                        limit,
                    });
                }
                world.push(w);
                vertex += 1;
            }
            out.push(world);
        }
        Ok(out)
    }

    /// Checks that every instanced vertex has a usable world position.
    ///
    /// # Errors
    /// As [`Scene::world_positions`], for the first instance that fails.
    pub fn check_world_positions(&self) -> Result<(), LoadError> {
        for instance in &self.instances {
            self.world_positions(instance)?;
        }
        Ok(())
    }

    /// World-space bounds of every instanced vertex: `(min, max)`, `None` without geometry.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for inst in &self.instances {
            for prim in self.meshes.get(inst.mesh).map_or(&[][..], |m| &m.primitives) {
                for &p in &prim.positions {
                    let w = inst.world.transform_point3(p);
                    lo = lo.min(w);
                    hi = hi.max(w);
                }
            }
        }
        (lo.x <= hi.x).then_some((lo, hi))
    }

    /// The triangles the instances place in all (each instance counts its mesh's
    /// triangles), checked against `max_triangles`, as are the vertices they place
    /// (`3 × max_triangles`), so that neither a node hierarchy that lists a node under many
    /// parents nor GPU instancing makes a small file place more than that.
    ///
    /// # Errors
    /// [`LoadError::TooLarge`] naming `nodes` and the count; [`LoadError::Invalid`] for an
    /// instance whose mesh does not exist.
    pub(crate) fn placed_triangles(&self, max_triangles: usize) -> Result<usize, LoadError> {
        let (mut triangles, mut vertices) = (0usize, 0usize);
        for inst in &self.instances {
            let mesh = self.meshes.get(inst.mesh).ok_or_else(|| {
                self.broken(format!("instance of node {} names mesh {}", inst.node, inst.mesh))
            })?;
            for prim in &mesh.primitives {
                triangles = triangles.saturating_add(prim.indices.len() / 3);
                vertices = vertices.saturating_add(prim.positions.len());
            }
            if triangles > max_triangles || vertices > max_triangles.saturating_mul(3) {
                return Err(LoadError::TooLarge {
                    path: Path::new(&self.path).to_owned(),
                    field: "nodes".into(),
                    reason: format!(
                        "the scene places more than {max_triangles} triangles or {} vertices, the most a level may hold",
                        max_triangles.saturating_mul(3)
                    ),
                });
            }
        }
        Ok(triangles)
    }

    pub(crate) fn broken(&self, reason: String) -> LoadError {
        LoadError::Invalid { path: Path::new(&self.path).to_owned(), field: "(scene)".into(), reason }
    }
}
