//! A glTF level as the testbed draws it: loaded by `ppr-level` (the loader every tool
//! shares) and converted to a [`Level`] — shared meshes as interleaved vertices, the
//! material numbers the G-buffer reads, base colour textures, perspective cameras.

use std::path::Path;

use ppr_level::{CameraProjection, LoadParams, Scene};

use crate::TestbedError;
use crate::level::{Level, LevelCamera, LevelTexture, Mesh, MeshInstance, MeshPrimitive};

impl Level {
    /// Loads the default scene (or the first) of a glTF file through `ppr-level`.
    ///
    /// Materials are `ppr-level`'s, whole; what the loader skipped (point
    /// and line primitives, textures that do not decode, orthographic cameras) is in
    /// [`Level::warnings`].
    ///
    /// # Errors
    /// [`TestbedError::Level`] when `ppr-level` refuses the file (it names the file and field).
    pub fn load_gltf(path: impl AsRef<Path>) -> Result<Self, TestbedError> {
        let scene = ppr_level::load_scene(path.as_ref(), &LoadParams::render())?;
        Self::from_scene(&scene)
    }

    /// The testbed's level for a loaded scene.
    ///
    /// # Errors
    /// [`TestbedError::InvalidGltf`] when the scene breaks the level's index invariants.
    pub fn from_scene(scene: &Scene) -> Result<Self, TestbedError> {
        let mut level = Level::new();
        level.source_hash = scene.hash.clone();
        for t in &scene.textures {
            level.add_texture(LevelTexture {
                name: t.name.clone(),
                width: t.width,
                height: t.height,
                rgba8: t.rgba8.clone(),
            });
        }
        for m in &scene.materials {
            level.add_material(m.clone());
        }
        for mesh in &scene.meshes {
            level.add_mesh(Mesh {
                name: mesh.name.clone(),
                primitives: mesh
                    .primitives
                    .iter()
                    .map(|p| MeshPrimitive {
                        vertices: p.vertices(),
                        indices: p.indices.clone(),
                        material: p.material,
                    })
                    .collect(),
            });
        }
        for inst in &scene.instances {
            let mesh_hint = scene.meshes.get(inst.mesh).and_then(|m| m.ppr.reflector);
            level.instances.push(MeshInstance {
                node_name: inst.node_name.clone(),
                mesh: inst.mesh,
                world: inst.world,
                reflector_hint: inst.ppr.reflector.or(mesh_hint),
            });
        }
        for cam in &scene.cameras {
            match cam.projection {
                CameraProjection::Perspective { yfov, znear, zfar } => {
                    level.cameras.push(LevelCamera {
                        name: cam.name.clone(),
                        world: cam.world,
                        yfov,
                        znear,
                        zfar,
                    });
                }
                CameraProjection::Orthographic { .. } => {
                    level.warnings.push(format!("camera {} is orthographic, ignored", cam.name));
                }
            }
        }
        level.warnings.extend(scene.notes.iter().cloned());
        level.validate().map_err(|reason| TestbedError::InvalidGltf {
            path: scene.path.clone().into(),
            field: "level".into(),
            reason,
        })?;
        Ok(level)
    }
}
