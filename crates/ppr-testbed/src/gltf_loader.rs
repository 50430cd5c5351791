//! Loading a glTF level (`.glb`, or `.gltf` with external or embedded buffers) into a [`Level`].
//!
//! The node hierarchy of the default scene is flattened into `f64` world transforms; every
//! node with a mesh becomes a [`crate::level::MeshInstance`] (instancing is kept: meshes are
//! shared) and every node with a perspective camera a [`LevelCamera`].

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{DMat4, DQuat, DVec3, Vec3};

use crate::TestbedError;
use crate::level::{Level, LevelCamera, LevelTexture, Material, Mesh, MeshInstance, MeshPrimitive, Vertex};

/// Extensions the loader refuses with a clear error rather than rendering garbage.
const REFUSED_EXTENSIONS: [(&str, &str); 3] = [
    ("EXT_meshopt_compression", "meshopt-compressed buffers are not decoded yet (see ppr-extract's decoder)"),
    ("KHR_draco_mesh_compression", "Draco-compressed meshes are not supported"),
    ("KHR_mesh_quantization", "quantized vertex attributes are not supported"),
];

impl Level {
    /// Loads the default scene (or the first) of a glTF file.
    ///
    /// Materials keep base colour factor and texture, roughness, metallic, transmission,
    /// unlit, double-sidedness and `extras.ppr.reflector`; primitives that are not
    /// triangles are skipped with a warning in [`Level::warnings`].
    ///
    /// # Errors
    /// [`TestbedError::Gltf`] when the file cannot be read or parsed,
    /// [`TestbedError::UnsupportedGltf`] for compressed levels, and
    /// [`TestbedError::InvalidGltf`] for a primitive without positions.
    pub fn load_gltf(path: impl AsRef<Path>) -> Result<Self, TestbedError> {
        let path = path.as_ref();
        let gltf_err = |source| TestbedError::Gltf { path: path.to_owned(), source };
        let bytes = std::fs::read(path).map_err(|e| gltf_err(gltf::Error::Io(e)))?;
        let unchecked = gltf::Gltf::from_slice_without_validation(&bytes).map_err(gltf_err)?;
        for used in unchecked.extensions_used().chain(unchecked.extensions_required()) {
            if let Some((_, why)) = REFUSED_EXTENSIONS.iter().find(|(name, _)| *name == used) {
                return Err(TestbedError::UnsupportedGltf {
                    path: path.to_owned(),
                    what: format!("uses {used}: {why}"),
                });
            }
        }
        drop(unchecked);
        let gltf = gltf::Gltf::from_slice(&bytes).map_err(gltf_err)?;
        let base = path.parent().unwrap_or(Path::new("."));
        let buffers =
            gltf::import_buffers(&gltf.document, Some(base), gltf.blob.clone()).map_err(gltf_err)?;
        let images = gltf::import_images(&gltf.document, Some(base), &buffers).map_err(gltf_err)?;
        GltfReader { path: path.to_owned(), buffers: &buffers, images: &images, level: Level::new() }
            .read(&gltf.document)
    }
}

struct GltfReader<'a> {
    path: PathBuf,
    buffers: &'a [gltf::buffer::Data],
    images: &'a [gltf::image::Data],
    level: Level,
}

impl GltfReader<'_> {
    fn read(mut self, doc: &gltf::Document) -> Result<Level, TestbedError> {
        let textures = self.read_textures(doc);
        for material in doc.materials() {
            let m = read_material(&material, &textures);
            self.level.materials.push(m);
        }
        let default_material = self.level.materials.len();
        self.level.materials.push(Material::default());
        for mesh in doc.meshes() {
            let m = self.read_mesh(&mesh, default_material)?;
            self.level.meshes.push(m);
        }
        let scene = doc.default_scene().or_else(|| doc.scenes().next());
        if let Some(scene) = scene {
            for node in scene.nodes() {
                self.visit(&node, DMat4::IDENTITY, None);
            }
        }
        if let Err(reason) = self.level.validate() {
            return Err(TestbedError::InvalidGltf { path: self.path, field: "level".into(), reason });
        }
        Ok(self.level)
    }

    /// Converts the images used as base colour textures to RGBA8; returns image index -> texture.
    fn read_textures(&mut self, doc: &gltf::Document) -> HashMap<usize, usize> {
        let mut map = HashMap::new();
        for material in doc.materials() {
            let Some(info) = material.pbr_metallic_roughness().base_color_texture() else { continue };
            if info.tex_coord() != 0 {
                self.level.warnings.push(format!(
                    "material {}: base colour texture uses UV set {}, only set 0 is read",
                    name_or_index(material.name(), material.index().unwrap_or(0)),
                    info.tex_coord()
                ));
            }
            let image = info.texture().source();
            let index = image.index();
            if map.contains_key(&index) {
                continue;
            }
            let Some(data) = self.images.get(index) else { continue };
            match to_rgba8(data) {
                Some(rgba8) => {
                    let texture = LevelTexture {
                        name: name_or_index(image.name(), index),
                        width: data.width,
                        height: data.height,
                        rgba8,
                    };
                    map.insert(index, self.level.add_texture(texture));
                }
                None => self.level.warnings.push(format!(
                    "image {}: pixel format {:?} is not supported as base colour, ignored",
                    name_or_index(image.name(), index),
                    data.format
                )),
            }
        }
        map
    }

    fn read_mesh(&mut self, mesh: &gltf::Mesh, default_material: usize) -> Result<Mesh, TestbedError> {
        let name = name_or_index(mesh.name(), mesh.index());
        let mut primitives = Vec::new();
        for (k, prim) in mesh.primitives().enumerate() {
            let reader = prim.reader(|b| self.buffers.get(b.index()).map(|d| d.0.as_slice()));
            let Some(positions) = reader.read_positions() else {
                return Err(TestbedError::InvalidGltf {
                    path: self.path.clone(),
                    field: format!("meshes[{}] ({name}).primitives[{k}]", mesh.index()),
                    reason: "no POSITION attribute".into(),
                });
            };
            let positions: Vec<[f32; 3]> = positions.collect();
            let count = positions.len();
            let raw_indices: Vec<u32> = match reader.read_indices() {
                Some(ix) => ix.into_u32().collect(),
                None => (0..u32::try_from(count).unwrap_or(u32::MAX)).collect(),
            };
            let Some(indices) = triangle_list(prim.mode(), &raw_indices) else {
                self.level.warnings.push(format!(
                    "mesh {name} primitive {k}: mode {:?} is not triangles, skipped",
                    prim.mode()
                ));
                continue;
            };
            if indices.iter().any(|&i| i as usize >= count) {
                return Err(TestbedError::InvalidGltf {
                    path: self.path.clone(),
                    field: format!("meshes[{}] ({name}).primitives[{k}].indices", mesh.index()),
                    reason: format!("an index is out of range ({count} vertices)"),
                });
            }
            let normals: Vec<[f32; 3]> = match reader.read_normals() {
                Some(n) => n.collect(),
                None => smooth_normals(&positions, &indices),
            };
            let uvs: Vec<[f32; 2]> =
                reader.read_tex_coords(0).map(|t| t.into_f32().collect()).unwrap_or_default();
            let vertices = (0..count)
                .map(|i| Vertex {
                    position: positions[i],
                    normal: normals.get(i).copied().unwrap_or([0.0, 1.0, 0.0]),
                    uv: uvs.get(i).copied().unwrap_or([0.0, 0.0]),
                })
                .collect();
            let material = prim.material().index().unwrap_or(default_material);
            primitives.push(MeshPrimitive { vertices, indices, material });
        }
        Ok(Mesh { name, primitives })
    }

    fn visit(&mut self, node: &gltf::Node, parent: DMat4, parent_hint: Option<bool>) {
        let world = parent * local_transform(node);
        let hint = ppr_reflector_hint(node.extras()).or(parent_hint);
        let name = name_or_index(node.name(), node.index());
        if let Some(mesh) = node.mesh() {
            let hint = hint.or_else(|| ppr_reflector_hint(mesh.extras()));
            self.level.instances.push(MeshInstance {
                node_name: name.clone(),
                mesh: mesh.index(),
                world,
                reflector_hint: hint,
            });
        }
        if let Some(camera) = node.camera() {
            match camera.projection() {
                gltf::camera::Projection::Perspective(p) => self.level.cameras.push(LevelCamera {
                    name: camera.name().map_or_else(|| name.clone(), str::to_owned),
                    world,
                    yfov: p.yfov(),
                    znear: p.znear(),
                    zfar: p.zfar(),
                }),
                gltf::camera::Projection::Orthographic(_) => {
                    self.level.warnings.push(format!("camera on node {name} is orthographic, ignored"));
                }
            }
        }
        for child in node.children() {
            self.visit(&child, world, hint);
        }
    }
}

/// The node's local transform in f64 (decomposed form is converted without going through f32 matrices).
fn local_transform(node: &gltf::Node) -> DMat4 {
    match node.transform() {
        gltf::scene::Transform::Matrix { matrix } => {
            let cols = matrix.map(|c| c.map(f64::from));
            DMat4::from_cols_array_2d(&cols)
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

fn read_material(material: &gltf::Material, textures: &HashMap<usize, usize>) -> Material {
    let pbr = material.pbr_metallic_roughness();
    Material {
        name: name_or_index(material.name(), material.index().unwrap_or(0)),
        base_color: pbr.base_color_factor(),
        base_color_texture: pbr
            .base_color_texture()
            .and_then(|info| textures.get(&info.texture().source().index()).copied()),
        emissive: material.emissive_factor(),
        roughness: pbr.roughness_factor(),
        metallic: pbr.metallic_factor(),
        transmission: material.transmission().map_or(0.0, |t| t.transmission_factor()),
        unlit: material.unlit(),
        double_sided: material.double_sided(),
        reflector_hint: ppr_reflector_hint(material.extras()),
    }
}

/// `extras.ppr.reflector` as a bool, if present.
fn ppr_reflector_hint(extras: &gltf::json::Extras) -> Option<bool> {
    let raw = extras.as_ref()?;
    let value: serde_json::Value = serde_json::from_str(raw.get()).ok()?;
    value.get("ppr")?.get("reflector")?.as_bool()
}

/// Indices as a triangle list (strips and fans converted); `None` for points and lines.
fn triangle_list(mode: gltf::mesh::Mode, ix: &[u32]) -> Option<Vec<u32>> {
    use gltf::mesh::Mode;
    match mode {
        Mode::Triangles => Some(ix[..ix.len() - ix.len() % 3].to_vec()),
        Mode::TriangleStrip => Some(
            (2..ix.len())
                .flat_map(|i| {
                    if i % 2 == 0 { [ix[i - 2], ix[i - 1], ix[i]] } else { [ix[i - 1], ix[i - 2], ix[i]] }
                })
                .collect(),
        ),
        Mode::TriangleFan => Some((2..ix.len()).flat_map(|i| [ix[0], ix[i - 1], ix[i]]).collect()),
        _ => None,
    }
}

/// Area-weighted vertex normals for a primitive that has none.
fn smooth_normals(positions: &[[f32; 3]], indices: &[u32]) -> Vec<[f32; 3]> {
    let mut acc = vec![Vec3::ZERO; positions.len()];
    for t in indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| Vec3::from(positions[i as usize]));
        let n = (b - a).cross(c - a);
        for &i in t {
            acc[i as usize] += n;
        }
    }
    acc.into_iter().map(|n| n.try_normalize().unwrap_or(Vec3::Y).to_array()).collect()
}

/// Decoded image pixels as RGBA8, for the 8-bit formats; `None` for the others.
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

fn name_or_index(name: Option<&str>, index: usize) -> String {
    name.map_or_else(|| format!("#{index}"), str::to_owned)
}
