//! A glTF level loaded the way a game might: positions, normals, UVs, base colour factor and
//! texture, the few material numbers that decide reflectivity, and the file's cameras. The
//! file is read by `ppr-level` (standing in for a game's own asset loader; it is the loader
//! every tool of the workspace shares) and kept in the forward pass's terms.
//!
//! Everything stays on the CPU here (`LevelData`), so the GPU side can be rebuilt from it
//! after a device loss. World transforms are `f64`: each frame the camera position is
//! subtracted before anything is rounded to `f32`.

use std::path::Path;

use anyhow::Result;
use glam::{DMat4, DVec3, Vec3};
use ppr_level::{AlphaMode, CameraProjection, LoadParams};

/// One vertex as the forward pass reads it (32 bytes, interleaved): `ppr-level`'s.
pub use ppr_level::Vertex;

/// A triangle list with one material.
#[derive(Clone, Debug, Default)]
pub struct Primitive {
    pub vertices: Vec<Vertex>,
    /// Counter-clockwise front faces.
    pub indices: Vec<u32>,
    /// Index into [`LevelData::materials`].
    pub material: usize,
}

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

/// An RGBA8 image whose colour channels are sRGB encoded.
#[derive(Clone, Debug)]
pub struct Texture {
    pub width: u32,
    pub height: u32,
    pub rgba8: Vec<u8>,
}

/// A mesh placed in the world.
#[derive(Clone, Debug)]
pub struct Instance {
    pub node_name: String,
    /// Index into [`LevelData::meshes`].
    pub mesh: usize,
    /// World-from-object transform, `f64`.
    pub world: DMat4,
    /// `extras.ppr.reflector` of the node (or an ancestor) or of its mesh.
    pub reflector_hint: Option<bool>,
}

impl Instance {
    /// Whether the transform mirrors (negative determinant): the winding flips.
    pub fn flips_winding(&self) -> bool {
        self.world.determinant() < 0.0
    }
}

/// A perspective camera of the file.
#[derive(Clone, Debug)]
pub struct LevelCamera {
    pub name: String,
    /// World transform of the camera node (looks down its local -Z).
    pub world: DMat4,
    /// Vertical field of view, radians.
    pub yfov: f32,
    pub znear: f32,
    pub zfar: Option<f32>,
}

impl LevelCamera {
    /// The node's position and rotation, `f64` position kept.
    pub fn position_rotation(&self) -> (DVec3, glam::Quat) {
        let (_, rotation, translation) = self.world.to_scale_rotation_translation();
        (translation, rotation.as_quat().normalize())
    }
}

/// A level on the CPU.
#[derive(Clone, Debug, Default)]
pub struct LevelData {
    /// Each glTF mesh as its primitives.
    pub meshes: Vec<Vec<Primitive>>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    pub instances: Vec<Instance>,
    pub cameras: Vec<LevelCamera>,
    /// `blake3:<hex>` of the file's bytes (what a reflector set's `source.hash` records).
    pub source_hash: String,
    /// Things skipped while loading (non-triangle primitives, unsupported images).
    pub warnings: Vec<String>,
}

impl LevelData {
    /// Loads the default scene (or the first) of a `.glb` or `.gltf` file.
    ///
    /// # Errors
    /// When `ppr-level` refuses the file (the message names the file and the field).
    pub fn load(path: &Path) -> Result<Self> {
        let scene = ppr_level::load_scene(path, &LoadParams::render())?;
        let mut level = LevelData {
            textures: scene
                .textures
                .into_iter()
                .map(|t| Texture { width: t.width, height: t.height, rgba8: t.rgba8 })
                .collect(),
            warnings: scene.notes,
            source_hash: scene.hash,
            materials: scene.materials,
            ..LevelData::default()
        };
        level.instances = scene
            .instances
            .iter()
            .map(|inst| Instance {
                node_name: inst.node_name.clone(),
                mesh: inst.mesh,
                world: inst.world,
                reflector_hint: inst.ppr.reflector.or_else(|| scene.meshes.get(inst.mesh)?.ppr.reflector),
            })
            .collect();
        level.meshes = scene
            .meshes
            .iter()
            .map(|mesh| {
                mesh.primitives
                    .iter()
                    .map(|p| Primitive {
                        vertices: p.vertices(),
                        indices: p.indices.clone(),
                        material: p.material,
                    })
                    .collect()
            })
            .collect();
        for cam in scene.cameras {
            match cam.projection {
                CameraProjection::Perspective { yfov, znear, zfar } => {
                    level.cameras.push(LevelCamera { name: cam.name, world: cam.world, yfov, znear, zfar });
                }
                CameraProjection::Orthographic { .. } => {
                    level.warnings.push(format!("camera {} is orthographic, ignored", cam.name));
                }
            }
        }
        Ok(level)
    }

    /// World-space bounds of every instance, if there is any geometry.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for inst in &self.instances {
            for prim in &self.meshes[inst.mesh] {
                for v in &prim.vertices {
                    let p = inst.world.transform_point3(Vec3::from(v.position).as_dvec3());
                    lo = lo.min(p);
                    hi = hi.max(p);
                }
            }
        }
        lo.is_finite().then_some((lo, hi))
    }

    /// The camera of the file with this name.
    pub fn camera(&self, name: &str) -> Option<&LevelCamera> {
        self.cameras.iter().find(|c| c.name == name)
    }
}

#[cfg(test)]
mod tests {
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
