//! Base colour textures decoded to RGBA8 (PNG and JPEG; [`decode`] also reads the images of
//! `roughness_maps.rs`). A texture that cannot be read or
//! decoded is a note, not an error: it does not change geometry, so a level that one tool
//! opens without textures opens in every tool.

use std::collections::HashMap;
use std::io::Cursor;
use std::path::Path;

use crate::Texture;
use crate::buffers::BufferData;
use crate::extras::display_name;
use crate::uri::{self, UriTarget};

/// The largest image file read from beside the level.
const MAX_IMAGE_FILE_BYTES: u64 = 1 << 28;
/// The largest decoded image side, in texels (wgpu's common texture limit).
const MAX_IMAGE_SIDE: u32 = 16384;

/// Decodes every image used as a base colour texture; returns the textures and, per
/// image index, its texture index. Images that fail become `notes`.
pub(crate) fn read_base_color_textures(
    doc: &gltf::Document,
    data: &BufferData,
    base_dir: &Path,
    notes: &mut Vec<String>,
) -> (Vec<Texture>, HashMap<usize, usize>) {
    let mut textures = Vec::new();
    let mut texture_of_image = HashMap::new();
    let mut tried = std::collections::HashSet::new();
    for material in doc.materials() {
        let Some(info) = material.pbr_metallic_roughness().base_color_texture() else { continue };
        let material_name = display_name(material.name(), material.index().unwrap_or(0));
        if info.tex_coord() != 0 {
            notes.push(format!(
                "material {material_name}: base colour texture uses UV set {}, only set 0 is read",
                info.tex_coord()
            ));
        }
        let image = info.texture().source();
        let index = image.index();
        if !tried.insert(index) {
            continue;
        }
        let name = display_name(image.name(), index);
        match decode(doc, &image, data, base_dir) {
            Ok((width, height, rgba8)) => {
                textures.push(Texture { name, width, height, rgba8 });
                texture_of_image.insert(index, textures.len() - 1);
            }
            Err(reason) => notes.push(format!("image {name} (images[{index}]): {reason}; drawn without it")),
        }
    }
    (textures, texture_of_image)
}

/// Decodes `image` of `doc` to RGBA8: `(width, height, texels)`.
///
/// The image's JSON is read here rather than through `gltf::Image::source`, which panics on
/// an image with neither `uri` nor `bufferView`, or a `bufferView` without `mimeType` (the
/// format is guessed from the bytes, so `mimeType` is not needed).
pub(crate) fn decode(
    doc: &gltf::Document,
    image: &gltf::Image,
    data: &BufferData,
    base_dir: &Path,
) -> Result<(u32, u32, Vec<u8>), String> {
    let json = doc.as_json().images.get(image.index()).ok_or("the image does not exist")?;
    let owned;
    let bytes: &[u8] = match (json.buffer_view, json.uri.as_deref()) {
        (Some(view), _) => {
            let view = doc
                .views()
                .nth(view.value())
                .ok_or_else(|| format!("`bufferView` {} does not exist", view.value()))?;
            data.view(&view).map_err(|e| e.to_string())?.bytes
        }
        (None, None) => return Err("it has neither `uri` nor `bufferView`".to_owned()),
        (None, Some(uri)) => match uri::resolve(uri, base_dir)? {
            UriTarget::Data(b) => {
                owned = b;
                &owned
            }
            UriTarget::File(file) => {
                let len = std::fs::metadata(&file)
                    .map_err(|e| format!("cannot read {}: {e}", file.display()))?
                    .len();
                if len > MAX_IMAGE_FILE_BYTES {
                    return Err(format!(
                        "{} is {len} bytes, more than the {MAX_IMAGE_FILE_BYTES} read",
                        file.display()
                    ));
                }
                owned =
                    uri::read_prefix(&file, len).map_err(|_| format!("cannot read {}", file.display()))?;
                &owned
            }
        },
    };
    let mut reader = image::ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| format!("cannot tell the image format: {e}"))?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    reader.limits(limits);
    let decoded = reader.decode().map_err(|e| format!("does not decode: {e}"))?;
    let rgba = decoded.to_rgba8();
    Ok((rgba.width(), rgba.height(), rgba.into_raw()))
}
