//! The testbed's level: `ppr-scene-gpu`'s [`LevelData`] (meshes, materials, textures,
//! placed instances and cameras on the CPU) with the testbed's loading errors, and the
//! testbed's rule for which surfaces reflect.
//!
//! A [`Level`] comes from a glTF file ([`Level::load_gltf`], `gltf_loader.rs`) or is built
//! in code ([`LevelData::add_mesh`], [`LevelData::add_instance`], ...) for synthetic test
//! scenes.

use std::ops::{Deref, DerefMut};

use glam::DVec3;

pub use ppr_scene_gpu::level_data::{
    LevelCamera, LevelData, LevelTexture, Material, Mesh, MeshInstance, MeshPrimitive, Vertex,
};

/// Roughness below which a material counts as a mirror-like reflector.
pub const REFLECTIVE_ROUGHNESS: f32 = 0.5;

/// Whether surfaces of `material` reflect in the testbed (its G-buffer's reflector mask):
/// `extras.ppr.reflector` if set, otherwise roughness below [`REFLECTIVE_ROUGHNESS`],
/// metallic ≥ 0.5 or any transmission.
pub fn is_reflective(material: &Material) -> bool {
    material.ppr.reflector.unwrap_or(
        material.roughness < REFLECTIVE_ROUGHNESS || material.metallic >= 0.5 || material.transmission > 0.0,
    )
}

/// A level: everything the testbed renders (a [`LevelData`], which it derefs to).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Level(pub LevelData);

impl Level {
    /// An empty level.
    pub fn new() -> Self {
        Self::default()
    }

    /// The same level moved by `offset` (instances and cameras), for precision tests.
    pub fn translated(&self, offset: DVec3) -> Self {
        Self(self.0.translated(offset))
    }
}

impl Deref for Level {
    type Target = LevelData;

    fn deref(&self) -> &LevelData {
        &self.0
    }
}

impl DerefMut for Level {
    fn deref_mut(&mut self) -> &mut LevelData {
        &mut self.0
    }
}
