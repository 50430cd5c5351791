//! Materials as renderers and the extractor read them: glTF metallic-roughness factors,
//! the extensions that matter to reflections, the alpha mode and `extras.ppr`.

use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use crate::extras::{ReflectorOverride, display_name, read_override};
use crate::{LoadError, RoughnessMap};

/// How a material's alpha is used (glTF `alphaMode`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum AlphaMode {
    /// `OPAQUE`: alpha ignored.
    #[default]
    Opaque,
    /// `MASK`: fragments under `cutoff` are discarded.
    Mask {
        /// `alphaCutoff` (glTF default 0.5).
        cutoff: f32,
    },
    /// `BLEND`: composited over what is behind.
    Blend,
}

/// One material of a level. Of its textures, the base colour is decoded for renderers and
/// the metallic-roughness texture's green channel (roughness) for the extractor.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Name from the file, or `#index` when it has none.
    pub name: String,
    /// Linear base colour factor (RGBA).
    pub base_color: [f32; 4],
    /// Index into [`crate::Scene::textures`] of the sRGB base colour texture (UV set 0);
    /// `None` when absent, not decoded, or not decodable (a note says why).
    pub base_color_texture: Option<usize>,
    /// Linear emissive factor.
    pub emissive: [f32; 3],
    /// `pbrMetallicRoughness.roughnessFactor` (glTF default 1).
    pub roughness: f32,
    /// `pbrMetallicRoughness.metallicFactor` (glTF default 1).
    pub metallic: f32,
    /// The green channel of `pbrMetallicRoughness.metallicRoughnessTexture` (UV set 0),
    /// which multiplies `roughness`; `None` when absent, not decoded, or not decodable (a
    /// note says why).
    pub roughness_map: Option<Arc<RoughnessMap>>,
    /// `KHR_materials_transmission.transmissionFactor` (0 when absent).
    pub transmission: f32,
    /// `KHR_materials_clearcoat.clearcoatFactor` as written in the JSON (0 when absent).
    pub clearcoat: f64,
    /// `KHR_materials_clearcoat.clearcoatRoughnessFactor` as written (0 when absent).
    pub clearcoat_roughness: f64,
    /// `KHR_materials_unlit`.
    pub unlit: bool,
    /// `doubleSided`.
    pub double_sided: bool,
    /// `alphaMode` and `alphaCutoff`.
    pub alpha_mode: AlphaMode,
    /// The material has a normal texture.
    pub normal_map: bool,
    /// `extras.ppr` of the material.
    pub ppr: ReflectorOverride,
}

impl Material {
    /// glTF's default material (for primitives without one): white, metallic, fully rough.
    pub fn gltf_default() -> Self {
        Self {
            name: "(default material)".into(),
            base_color: [1.0; 4],
            base_color_texture: None,
            emissive: [0.0; 3],
            roughness: 1.0,
            metallic: 1.0,
            roughness_map: None,
            transmission: 0.0,
            clearcoat: 0.0,
            clearcoat_roughness: 0.0,
            unlit: false,
            double_sided: false,
            alpha_mode: AlphaMode::Opaque,
            normal_map: false,
            ppr: ReflectorOverride::default(),
        }
    }
}

/// Reads every material of the document and appends the glTF default material last.
/// `texture_of_image` maps an image index to its decoded texture, `roughness_maps` a
/// texture index to its decoded roughness map.
pub(crate) fn read_materials(
    path: &Path,
    doc: &gltf::Document,
    texture_of_image: &HashMap<usize, usize>,
    roughness_maps: &HashMap<usize, Arc<RoughnessMap>>,
) -> Result<Vec<Material>, LoadError> {
    let mut out = Vec::new();
    for m in doc.materials() {
        let index = m.index().unwrap_or(0);
        let name = display_name(m.name(), index);
        let pbr = m.pbr_metallic_roughness();
        let clearcoat = m.extension_value("KHR_materials_clearcoat");
        let number = |key: &str, default: f64| {
            clearcoat.and_then(|c| c.get(key)).and_then(serde_json::Value::as_f64).unwrap_or(default)
        };
        let owner = format!("materials[{index}] ({name:?})");
        out.push(Material {
            base_color: pbr.base_color_factor(),
            base_color_texture: pbr
                .base_color_texture()
                .and_then(|info| texture_of_image.get(&info.texture().source().index()).copied()),
            emissive: m.emissive_factor(),
            roughness: pbr.roughness_factor(),
            metallic: pbr.metallic_factor(),
            roughness_map: pbr
                .metallic_roughness_texture()
                .and_then(|info| roughness_maps.get(&info.texture().index()).cloned()),
            transmission: m.transmission().map_or(0.0, |t| t.transmission_factor()),
            clearcoat: number("clearcoatFactor", 0.0),
            clearcoat_roughness: number("clearcoatRoughnessFactor", 0.0),
            unlit: m.unlit(),
            double_sided: m.double_sided(),
            alpha_mode: match m.alpha_mode() {
                gltf::material::AlphaMode::Opaque => AlphaMode::Opaque,
                gltf::material::AlphaMode::Mask => {
                    AlphaMode::Mask { cutoff: m.alpha_cutoff().unwrap_or(0.5) }
                }
                gltf::material::AlphaMode::Blend => AlphaMode::Blend,
            },
            normal_map: m.normal_texture().is_some(),
            ppr: read_override(path, &owner, m.extras())?,
            name,
        });
    }
    out.push(Material::gltf_default());
    Ok(out)
}
