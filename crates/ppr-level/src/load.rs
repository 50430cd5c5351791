//! Reading a `.glb`, or a `.gltf` with external or embedded buffers, into a [`Scene`] or
//! a [`Level`]: the container, the required extensions, glTF's validation, then buffers,
//! materials, textures and nodes.

use std::collections::HashMap;
use std::path::Path;

use crate::buffers::BufferData;
use crate::scene_reader::SceneReader;
use crate::{Level, LoadError, MAX_LEVEL_TRIANGLES, Scene, container, images, materials, roughness_maps};

/// Extensions that change how geometry is stored and that this crate decodes.
const GEOMETRY_EXTENSIONS: &[&str] =
    &["KHR_mesh_quantization", "EXT_meshopt_compression", "EXT_mesh_gpu_instancing"];

/// Extensions that only concern shading, textures, lights or metadata: geometry reads the
/// same without them (`KHR_materials_*` too, matched by prefix).
const HARMLESS_EXTENSIONS: &[&str] = &[
    "KHR_texture_transform",
    "KHR_texture_basisu",
    "EXT_texture_webp",
    "EXT_texture_avif",
    "MSFT_texture_dds",
    "KHR_lights_punctual",
    "EXT_lights_image_based",
    "EXT_lights_ies",
    "KHR_xmp_json_ld",
    "KHR_animation_pointer",
];

/// Whether a level that lists `name` in `extensionsRequired` can be read.
pub fn can_read_extension(name: &str) -> bool {
    GEOMETRY_EXTENSIONS.contains(&name)
        || HARMLESS_EXTENSIONS.contains(&name)
        || name.starts_with("KHR_materials_")
}

/// Whether textures are decoded. What is accepted does not change: an image that fails is
/// only ever a note.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TextureLoading {
    /// Decode base colour textures and roughness maps (renderers).
    #[default]
    Decode,
    /// Decode only the roughness maps ([`crate::Material::roughness_map`]), leave
    /// [`Scene::textures`] empty (the extractor: geometry, factors and roughness).
    RoughnessOnly,
    /// Decode nothing.
    Skip,
}

/// How a level is loaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LoadParams {
    /// Whether textures are decoded.
    pub textures: TextureLoading,
    /// The most triangles the scene's instances may place in all (and three times as many
    /// vertices), checked before any instance is transformed: [`MAX_LEVEL_TRIANGLES`] by
    /// default (a [`Level`] of that size takes about 1.3 GB). A tool that must stay in less
    /// memory (the fuzzer) sets less.
    pub max_triangles: usize,
}

impl Default for LoadParams {
    fn default() -> Self {
        Self { textures: TextureLoading::default(), max_triangles: MAX_LEVEL_TRIANGLES }
    }
}

impl LoadParams {
    /// Everything a renderer draws, textures included.
    pub fn render() -> Self {
        Self { textures: TextureLoading::Decode, ..Self::default() }
    }

    /// Geometry, material factors and roughness maps: what the extractor reads, so that
    /// its reflectors' roughness does not depend on which tool extracted them.
    pub fn geometry() -> Self {
        Self { textures: TextureLoading::RoughnessOnly, ..Self::default() }
    }
}

/// Reads the level at `path` as a [`Scene`]; [`Scene::hash`] is the file's.
///
/// # Errors
/// A [`LoadError`] naming the file and what in it cannot be read: missing file, not glTF,
/// truncated `.glb`, invalid JSON fields, unsupported required extension, unsafe or
/// missing external buffer, accessor or buffer view out of range, node cycles or depth,
/// NaN or out-of-range positions, bad `extras.ppr`.
pub fn load_scene(path: impl AsRef<Path>, params: &LoadParams) -> Result<Scene, LoadError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| LoadError::Read { path: path.to_owned(), source })?;
    let base_dir = path.parent().unwrap_or(Path::new("."));
    let mut scene = load_scene_from_bytes(path, &bytes, base_dir, params)?;
    scene.hash = format!("blake3:{}", blake3::hash(&bytes).to_hex());
    Ok(scene)
}

/// Reads a [`Scene`] from the bytes of a `.glb` or `.gltf` file; external buffers and
/// images are read relative to `base_dir`. `path` only names the file in errors and in
/// the scene.
///
/// # Errors
/// As [`load_scene`].
pub fn load_scene_from_bytes(
    path: &Path,
    bytes: &[u8],
    base_dir: &Path,
    params: &LoadParams,
) -> Result<Scene, LoadError> {
    let container = container::split_container(path, bytes)?;
    let root = parse_json(path, container.json)?;
    for ext in &root.extensions_required {
        if !can_read_extension(ext) {
            return Err(LoadError::UnsupportedExtension { path: path.to_owned(), extension: ext.clone() });
        }
    }
    validate(path, &root)?;
    let doc = gltf::Document::from_json_without_validation(root);
    let data = BufferData::load(path, &doc, container.bin, base_dir)?;
    let mut scene = Scene { path: path.display().to_string(), ..Scene::default() };
    let texture_of_image = match params.textures {
        TextureLoading::Decode => {
            let (textures, map) = images::read_base_color_textures(&doc, &data, base_dir, &mut scene.notes);
            scene.textures = textures;
            map
        }
        TextureLoading::RoughnessOnly | TextureLoading::Skip => HashMap::new(),
    };
    let roughness_maps = match params.textures {
        TextureLoading::Decode | TextureLoading::RoughnessOnly => {
            roughness_maps::read_roughness_maps(&doc, &data, base_dir, &mut scene.notes)
        }
        TextureLoading::Skip => HashMap::new(),
    };
    scene.materials = materials::read_materials(path, &doc, &texture_of_image, &roughness_maps)?;
    let default_material = scene.materials.len() - 1;
    let max_triangles = params.max_triangles.min(MAX_LEVEL_TRIANGLES);
    SceneReader { path, doc: &doc, data: &data, default_material, max_triangles }.read(&mut scene)?;
    scene.check_world_positions()?;
    Ok(scene)
}

/// Reads and flattens the level at `path` (geometry, material factors and roughness maps;
/// no base colour textures).
///
/// # Errors
/// As [`load_scene`], and [`Level::from_scene`]'s size limit.
pub fn load_level(path: impl AsRef<Path>) -> Result<Level, LoadError> {
    Level::from_scene(&load_scene(path, &LoadParams::geometry())?)
}

/// Reads and flattens a level from the bytes of a `.glb` or `.gltf` file.
///
/// # Errors
/// As [`load_level`].
pub fn load_level_from_bytes(path: &Path, bytes: &[u8], base_dir: &Path) -> Result<Level, LoadError> {
    Level::from_scene(&load_scene_from_bytes(path, bytes, base_dir, &LoadParams::geometry())?)
}

fn parse_json(path: &Path, json: &[u8]) -> Result<gltf::json::Root, LoadError> {
    gltf::json::deserialize::from_slice::<gltf::json::Root>(json).map_err(|e| {
        use serde_json::error::Category;
        match e.classify() {
            Category::Syntax | Category::Eof | Category::Io => {
                LoadError::NotGltf { path: path.to_owned(), reason: format!("the JSON does not parse: {e}") }
            }
            Category::Data => LoadError::Invalid {
                path: path.to_owned(),
                field: "(document)".into(),
                reason: e.to_string(),
            },
        }
    })
}

/// glTF's own validation, less its refusal of extensions (checked by us, with a name).
fn validate(path: &Path, root: &gltf::json::Root) -> Result<(), LoadError> {
    use gltf::json::validation::{Error, Validate};
    // The validator indexes POSITION accessors without a bounds check; check them first.
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            for (semantic, index) in &prim.attributes {
                if index.value() >= root.accessors.len() {
                    let name = match semantic {
                        gltf::json::validation::Checked::Valid(s) => s.to_string(),
                        gltf::json::validation::Checked::Invalid => "?".into(),
                    };
                    return Err(LoadError::Invalid {
                        path: path.to_owned(),
                        field: format!("meshes[{m}].primitives[{p}].attributes.{name}"),
                        reason: format!(
                            "accessor {} does not exist ({} accessors)",
                            index.value(),
                            root.accessors.len()
                        ),
                    });
                }
            }
        }
    }
    let mut first: Option<(String, Error)> = None;
    root.validate(root, gltf::json::Path::new, &mut |p, e| {
        if first.is_none() && e != Error::Unsupported {
            first = Some((p().to_string(), e));
        }
    });
    match first {
        None => Ok(()),
        Some((field, e)) => {
            Err(LoadError::Invalid { path: path.to_owned(), field, reason: e.to_string().to_lowercase() })
        }
    }
}
