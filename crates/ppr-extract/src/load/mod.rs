//! Loading a glTF level (`.glb`, or `.gltf` with external or embedded buffers) into a
//! flat list of world-space triangles.
//!
//! Required extensions this build reads: `KHR_mesh_quantization` (integer positions, any
//! normalization), `EXT_meshopt_compression` (decoded with meshoptimizer),
//! `EXT_mesh_gpu_instancing`, and every material or texture extension (they do not change
//! geometry). Any other entry of `extensionsRequired` is refused with its name.

mod accessor;
mod buffers;
mod container;
mod error;
mod materials;
mod meshopt_views;
mod scene;

use std::path::Path;

pub use error::LoadError;

use crate::level::Level;

/// Extensions that change how geometry is stored and that this build decodes.
const GEOMETRY_EXTENSIONS: &[&str] =
    &["KHR_mesh_quantization", "EXT_meshopt_compression", "EXT_mesh_gpu_instancing"];

/// Extensions that only concern shading, textures, lights or metadata: geometry reads the same.
const HARMLESS_EXTENSIONS: &[&str] = &[
    "KHR_texture_transform",
    "KHR_texture_basisu",
    "EXT_texture_webp",
    "EXT_texture_avif",
    "MSFT_texture_dds",
    "KHR_lights_punctual",
    "KHR_xmp_json_ld",
    "KHR_animation_pointer",
];

/// Whether this build can read a level that requires `name`.
pub fn can_read_extension(name: &str) -> bool {
    GEOMETRY_EXTENSIONS.contains(&name)
        || HARMLESS_EXTENSIONS.contains(&name)
        || name.starts_with("KHR_materials_")
}

/// Reads and flattens the level at `path`.
///
/// # Errors
/// A [`LoadError`] naming the file and what in it cannot be read: missing file, not glTF,
/// truncated `.glb`, invalid JSON fields, unsupported required extension, missing external
/// buffer, accessor or buffer view out of range, NaN positions, bad `extras.ppr`.
pub fn load_level(path: impl AsRef<Path>) -> Result<Level, LoadError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| LoadError::Read { path: path.to_owned(), source })?;
    let base_dir = path.parent().unwrap_or(Path::new("."));
    let mut level = load_level_from_bytes(path, &bytes, base_dir)?;
    level.hash = format!("blake3:{}", blake3::hash(&bytes).to_hex());
    Ok(level)
}

/// Reads a level from the bytes of a `.glb` or `.gltf` file; external buffers are read
/// relative to `base_dir`. `path` only names the file in errors and in the level.
///
/// # Errors
/// As [`load_level`].
pub fn load_level_from_bytes(path: &Path, bytes: &[u8], base_dir: &Path) -> Result<Level, LoadError> {
    let container = container::split_container(path, bytes)?;
    let root = parse_json(path, container.json)?;
    for ext in &root.extensions_required {
        if !can_read_extension(ext) {
            return Err(LoadError::UnsupportedExtension { path: path.to_owned(), extension: ext.clone() });
        }
    }
    validate(path, &root)?;
    let doc = gltf::Document::from_json_without_validation(root);
    let data = buffers::BufferData::load(path, &doc, container.bin, base_dir)?;
    let materials = materials::read_materials(path, &doc)?;
    let mut level = Level { path: path.display().to_string(), ..Level::default() };
    let default_material = (materials.len() - 1) as u32;
    level.materials = materials;
    scene::SceneReader { path, doc: &doc, data: &data, default_material }.flatten(&mut level)?;
    Ok(level)
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
