//! A `ppr-level` scene as a [`LevelData`]: shared meshes as interleaved vertices, the
//! materials whole, base colour textures, perspective cameras (orthographic ones are
//! warnings), each instance's `extras.ppr.reflector` hint (its node's, else its mesh's).

use std::path::Path;

use ppr_level::{CameraProjection, LoadError, LoadParams, Scene};

use crate::level_data::{LevelCamera, LevelData, LevelTexture, Mesh, MeshInstance, MeshPrimitive};

impl LevelData {
    /// Loads the default scene (or the first) of a glTF file through `ppr-level`, with
    /// textures ([`LoadParams::render`]).
    ///
    /// # Errors
    /// When `ppr-level` refuses the file (the error names the file and the field).
    pub fn load(path: &Path) -> Result<Self, LoadError> {
        Ok(Self::from_scene(&ppr_level::load_scene(path, &LoadParams::render())?))
    }

    /// The level of a loaded scene; what the loader skipped is in [`LevelData::warnings`]
    /// (orthographic cameras added). The index invariants are not checked here
    /// ([`LevelData::validate`]).
    pub fn from_scene(scene: &Scene) -> Self {
        let mut level = LevelData::new();
        level.source_hash = scene.hash.clone();
        level.textures = scene.textures.iter().map(level_texture).collect();
        level.materials = scene.materials.clone();
        level.meshes = scene.meshes.iter().map(level_mesh).collect();
        level.instances = scene.instances.iter().map(|inst| mesh_instance(scene, inst)).collect();
        for cam in &scene.cameras {
            match cam.projection {
                CameraProjection::Perspective { yfov, znear, zfar } => {
                    let name = cam.name.clone();
                    level.cameras.push(LevelCamera { name, world: cam.world, yfov, znear, zfar });
                }
                CameraProjection::Orthographic { .. } => {
                    level.warnings.push(format!("camera {} is orthographic, ignored", cam.name));
                }
            }
        }
        level.warnings.extend(scene.notes.iter().cloned());
        level
    }
}

fn level_texture(t: &ppr_level::Texture) -> LevelTexture {
    LevelTexture { name: t.name.clone(), width: t.width, height: t.height, rgba8: t.rgba8.clone() }
}

fn level_mesh(mesh: &ppr_level::Mesh) -> Mesh {
    let primitive = |p: &ppr_level::Primitive| MeshPrimitive {
        vertices: p.vertices(),
        indices: p.indices.clone(),
        material: p.material,
    };
    Mesh { name: mesh.name.clone(), primitives: mesh.primitives.iter().map(primitive).collect() }
}

/// The instance with its `extras.ppr.reflector` hint: its node's, else its mesh's.
fn mesh_instance(scene: &Scene, inst: &ppr_level::Instance) -> MeshInstance {
    MeshInstance {
        node_name: inst.node_name.clone(),
        mesh: inst.mesh,
        world: inst.world,
        reflector_hint: inst.ppr.reflector.or_else(|| scene.meshes.get(inst.mesh)?.ppr.reflector),
    }
}
