//! A glTF level as the testbed draws it: loaded by `ppr-level` (the loader every tool
//! shares), converted by `ppr-scene-gpu` and checked against the level's invariants.

use std::path::Path;

use ppr_level::{LoadParams, Scene};
use ppr_scene_gpu::LevelData;

use crate::TestbedError;
use crate::level::Level;

impl Level {
    /// Loads the default scene (or the first) of a glTF file through `ppr-level`.
    ///
    /// Materials are `ppr-level`'s, whole; what the loader skipped (point
    /// and line primitives, textures that do not decode, orthographic cameras) is in
    /// [`LevelData::warnings`].
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
        let level = LevelData::from_scene(scene);
        level.validate().map_err(|reason| TestbedError::InvalidGltf {
            path: scene.path.clone().into(),
            field: "level".into(),
            reason,
        })?;
        Ok(Self(level))
    }
}
