//! A glTF level loaded the way a game might: positions, normals, UVs, base colour factor and
//! texture, the few material numbers that decide reflectivity, and the file's cameras.
//!
//! Everything stays on the CPU here (`LevelData`), so the GPU side can be rebuilt from it
//! after a device loss. World transforms are `f64`: each frame the camera position is
//! subtracted before anything is rounded to `f32`.

use std::collections::HashMap;
use std::path::Path;

use anyhow::{Context, Result, bail};
use glam::{DMat4, DQuat, DVec3, Vec3};

/// One vertex as the forward pass reads it (32 bytes, interleaved).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    /// Object-space position, metres.
    pub position: [f32; 3],
    /// Object-space normal.
    pub normal: [f32; 3],
    /// Texture coordinate set 0.
    pub uv: [f32; 2],
}

/// A triangle list with one material.
#[derive(Clone, Debug, Default)]
pub struct Primitive {
    pub vertices: Vec<Vertex>,
    /// Counter-clockwise front faces.
    pub indices: Vec<u32>,
    /// Index into [`LevelData::materials`].
    pub material: usize,
}

/// How a glTF material blends.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AlphaBlend {
    /// Opaque (`OPAQUE` and `MASK` are both drawn opaque here).
    #[default]
    Opaque,
    /// `BLEND`: drawn after the opaque surfaces, blended, without writing depth.
    Blend,
}

/// The material numbers the forward pass uses.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    /// Linear base colour factor (RGBA).
    pub base_color: [f32; 4],
    /// Index into [`LevelData::textures`] of the sRGB base colour texture.
    pub base_color_texture: Option<usize>,
    /// Linear emissive colour.
    pub emissive: [f32; 3],
    pub roughness: f32,
    pub metallic: f32,
    /// `KHR_materials_transmission` factor (0 when absent).
    pub transmission: f32,
    /// `KHR_materials_unlit`.
    pub unlit: bool,
    pub double_sided: bool,
    pub blend: AlphaBlend,
    /// `extras.ppr.reflector` of the material.
    pub reflector_hint: Option<bool>,
}

impl Default for Material {
    /// glTF's default material: white, metallic, fully rough.
    fn default() -> Self {
        Self {
            name: "default".into(),
            base_color: [1.0; 4],
            base_color_texture: None,
            emissive: [0.0; 3],
            roughness: 1.0,
            metallic: 1.0,
            transmission: 0.0,
            unlit: false,
            double_sided: false,
            blend: AlphaBlend::Opaque,
            reflector_hint: None,
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
    /// Things skipped while loading (non-triangle primitives, unsupported images).
    pub warnings: Vec<String>,
}

impl LevelData {
    /// Loads the default scene (or the first) of a `.glb` or `.gltf` file.
    ///
    /// # Errors
    /// When the file cannot be read or parsed, or a primitive is broken (no positions,
    /// indices out of range).
    pub fn load(path: &Path) -> Result<Self> {
        let (doc, buffers, images) =
            gltf::import(path).with_context(|| format!("{}: cannot load the glTF level", path.display()))?;
        let mut level = LevelData::default();
        let mut texture_of_image = HashMap::new();
        for material in doc.materials() {
            let texture = material.pbr_metallic_roughness().base_color_texture().and_then(|info| {
                let image = info.texture().source().index();
                if let Some(&t) = texture_of_image.get(&image) {
                    return Some(t);
                }
                let Some(rgba8) = images.get(image).and_then(to_rgba8) else {
                    level.warnings.push(format!("image {image}: pixel format not supported, ignored"));
                    return None;
                };
                let data = &images[image];
                level.textures.push(Texture { width: data.width, height: data.height, rgba8 });
                texture_of_image.insert(image, level.textures.len() - 1);
                Some(level.textures.len() - 1)
            });
            level.materials.push(read_material(&material, texture));
        }
        let default_material = level.materials.len();
        level.materials.push(Material::default());
        for mesh in doc.meshes() {
            let mut primitives = Vec::new();
            for (k, prim) in mesh.primitives().enumerate() {
                let what = format!("mesh {} primitive {k}", mesh.name().unwrap_or("?"));
                if prim.mode() != gltf::mesh::Mode::Triangles {
                    level.warnings.push(format!("{what}: not a triangle list, skipped"));
                    continue;
                }
                primitives.push(read_primitive(&prim, &buffers, default_material, &what)?);
            }
            level.meshes.push(primitives);
        }
        if let Some(scene) = doc.default_scene().or_else(|| doc.scenes().next()) {
            for node in scene.nodes() {
                level.visit(&node, DMat4::IDENTITY, None);
            }
        }
        Ok(level)
    }

    fn visit(&mut self, node: &gltf::Node, parent: DMat4, parent_hint: Option<bool>) {
        let world = parent * local_transform(node);
        let hint = reflector_hint(node.extras()).or(parent_hint);
        let name = node.name().map_or_else(|| format!("#{}", node.index()), str::to_owned);
        if let Some(mesh) = node.mesh() {
            let reflector_hint = hint.or_else(|| reflector_hint(mesh.extras()));
            self.instances.push(Instance {
                node_name: name.clone(),
                mesh: mesh.index(),
                world,
                reflector_hint,
            });
        }
        if let Some(camera) = node.camera()
            && let gltf::camera::Projection::Perspective(p) = camera.projection()
        {
            self.cameras.push(LevelCamera {
                name: camera.name().map_or_else(|| name.clone(), str::to_owned),
                world,
                yfov: p.yfov(),
                znear: p.znear(),
                zfar: p.zfar(),
            });
        }
        for child in node.children() {
            self.visit(&child, world, hint);
        }
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

fn read_primitive(
    prim: &gltf::Primitive,
    buffers: &[gltf::buffer::Data],
    default_material: usize,
    what: &str,
) -> Result<Primitive> {
    let reader = prim.reader(|b| buffers.get(b.index()).map(|d| d.0.as_slice()));
    let Some(positions) = reader.read_positions() else { bail!("{what}: no POSITION attribute") };
    let positions: Vec<[f32; 3]> = positions.collect();
    let count = positions.len();
    let mut indices: Vec<u32> = match reader.read_indices() {
        Some(ix) => ix.into_u32().collect(),
        None => (0..u32::try_from(count)?).collect(),
    };
    indices.truncate(indices.len() - indices.len() % 3);
    if indices.iter().any(|&i| i as usize >= count) {
        bail!("{what}: an index is out of range ({count} vertices)");
    }
    let normals: Vec<[f32; 3]> = match reader.read_normals() {
        Some(n) => n.collect(),
        None => flat_normals(&positions, &indices),
    };
    let uvs: Vec<[f32; 2]> = reader.read_tex_coords(0).map(|t| t.into_f32().collect()).unwrap_or_default();
    let vertices = (0..count)
        .map(|i| Vertex {
            position: positions[i],
            normal: normals.get(i).copied().unwrap_or([0.0, 1.0, 0.0]),
            uv: uvs.get(i).copied().unwrap_or_default(),
        })
        .collect();
    Ok(Primitive { vertices, indices, material: prim.material().index().unwrap_or(default_material) })
}

fn read_material(material: &gltf::Material, base_color_texture: Option<usize>) -> Material {
    let pbr = material.pbr_metallic_roughness();
    Material {
        name: material.name().unwrap_or("?").to_owned(),
        base_color: pbr.base_color_factor(),
        base_color_texture,
        emissive: material.emissive_factor(),
        roughness: pbr.roughness_factor(),
        metallic: pbr.metallic_factor(),
        transmission: material.transmission().map_or(0.0, |t| t.transmission_factor()),
        unlit: material.unlit(),
        double_sided: material.double_sided(),
        blend: match material.alpha_mode() {
            gltf::material::AlphaMode::Blend => AlphaBlend::Blend,
            _ => AlphaBlend::Opaque,
        },
        reflector_hint: reflector_hint(material.extras()),
    }
}

fn local_transform(node: &gltf::Node) -> DMat4 {
    match node.transform() {
        gltf::scene::Transform::Matrix { matrix } => {
            DMat4::from_cols_array_2d(&matrix.map(|c| c.map(f64::from)))
        }
        gltf::scene::Transform::Decomposed { translation, rotation, scale } => {
            let [x, y, z, w] = rotation.map(f64::from);
            DMat4::from_scale_rotation_translation(
                DVec3::from(scale.map(f64::from)),
                DQuat::from_xyzw(x, y, z, w).normalize(),
                DVec3::from(translation.map(f64::from)),
            )
        }
    }
}

/// `extras.ppr.reflector` as a bool, if present.
fn reflector_hint(extras: &gltf::json::Extras) -> Option<bool> {
    let value: serde_json::Value = serde_json::from_str(extras.as_ref()?.get()).ok()?;
    value.get("ppr")?.get("reflector")?.as_bool()
}

/// Face normals for a primitive that has none (each vertex takes its last triangle's).
fn flat_normals(positions: &[[f32; 3]], indices: &[u32]) -> Vec<[f32; 3]> {
    let mut normals = vec![[0.0, 1.0, 0.0]; positions.len()];
    for t in indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| Vec3::from(positions[i as usize]));
        let n = (b - a).cross(c - a).try_normalize().unwrap_or(Vec3::Y);
        for &i in t {
            normals[i as usize] = n.to_array();
        }
    }
    normals
}

fn to_rgba8(data: &gltf::image::Data) -> Option<Vec<u8>> {
    use gltf::image::Format;
    let px = &data.pixels;
    Some(match data.format {
        Format::R8G8B8A8 => px.clone(),
        Format::R8G8B8 => px.chunks_exact(3).flat_map(|c| [c[0], c[1], c[2], 255]).collect(),
        Format::R8G8 => px.chunks_exact(2).flat_map(|c| [c[0], c[0], c[0], c[1]]).collect(),
        Format::R8 => px.iter().flat_map(|&v| [v, v, v, 255]).collect(),
        _ => return None,
    })
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
        assert_eq!(glass.blend, AlphaBlend::Blend);
        assert!(glass.transmission > 0.5);
        let (lo, hi) = level.bounds().expect("bounds");
        assert!(lo.x < -7.9 && hi.x > 7.9, "{lo} {hi}");
    }
}
