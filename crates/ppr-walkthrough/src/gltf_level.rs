//! A glTF level loaded the way a game might: positions, normals, UVs, base colour factor and
//! texture, the few material numbers that decide reflectivity, and the file's cameras. The
//! file is read by `ppr-level` (standing in for a game's own asset loader; it is the loader
//! every tool of the workspace shares) into `ppr-scene-gpu`'s [`LevelData`], the level the
//! testbed draws too.
//!
//! Everything stays on the CPU here (`LevelData`), so the GPU side can be rebuilt from it
//! after a device loss. World transforms are `f64`: each frame the camera position is
//! subtracted before anything is rounded to `f32`.

use ppr_level::AlphaMode;

/// The level on the CPU and its cameras: `ppr-scene-gpu`'s.
pub use ppr_scene_gpu::{LevelCamera, LevelData};

/// A material as `ppr-level` reads it: the forward pass uses its base colour and
/// texture, emissive, roughness, metallic, transmission, unlit, double-sidedness, alpha mode
/// ([`AlphaBlend::of`]) and `extras.ppr`.
pub use ppr_level::Material;

/// How the forward pass draws a material.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AlphaBlend {
    /// Opaque (`OPAQUE` and `MASK` are both drawn opaque here).
    #[default]
    Opaque,
    /// `BLEND`: drawn after the opaque surfaces, blended, without writing depth.
    Blend,
}

impl AlphaBlend {
    /// How `material` is drawn, from its glTF alpha mode.
    pub fn of(material: &Material) -> Self {
        match material.alpha_mode {
            AlphaMode::Blend => Self::Blend,
            AlphaMode::Opaque | AlphaMode::Mask { .. } => Self::Opaque,
        }
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use ppr_level::LoadParams;

    use super::*;

    #[test]
    fn demo_level_loads() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/demo_room.glb");
        let level = LevelData::load(&path).expect("demo level");
        assert!(level.camera("cam_mirror").is_some());
        assert!(!level.textures.is_empty());
        let table = level.instances.iter().find(|i| i.node_name == "table_top").expect("table_top");
        assert_eq!(table.reflector_hint, Some(false));
        let glass = level.materials.iter().find(|m| m.name == "glass").expect("glass");
        assert_eq!(AlphaBlend::of(glass), AlphaBlend::Blend);
        assert!(glass.transmission > 0.5);
        let (lo, hi) = level.bounds().expect("bounds");
        assert!(lo.x < -7.9 && hi.x > 7.9, "{lo} {hi}");
    }

    /// The walkthrough draws `ppr-level`'s materials themselves: nothing the loader read
    /// (alpha cutoff, clearcoat, normal map, `extras.ppr`) is dropped on the way.
    #[test]
    fn the_levels_materials_are_the_loaders_whole() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/demo_room.glb");
        let scene = ppr_level::load_scene(&path, &LoadParams::render()).expect("demo scene");
        let level = LevelData::load(&path).expect("demo level");
        assert_eq!(level.materials, scene.materials);
    }
}
