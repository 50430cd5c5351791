//! The subset of the glTF 2.0 JSON schema the level uses, as typed serde structs.
//!
//! Typed structs (rather than `serde_json::Value`) fix the key order, so the output stays
//! byte-identical even if another crate in the workspace turns on `preserve_order`.

use serde::Serialize;

/// `componentType` of 32-bit floats.
pub const COMPONENT_F32: u32 = 5126;
/// `componentType` of unsigned 16-bit integers.
pub const COMPONENT_U16: u32 = 5123;
/// `componentType` of unsigned 32-bit integers.
pub const COMPONENT_U32: u32 = 5125;
/// Buffer view target of vertex attributes.
pub const TARGET_ARRAY_BUFFER: u32 = 34962;
/// Buffer view target of indices.
pub const TARGET_ELEMENT_ARRAY_BUFFER: u32 = 34963;

#[derive(Serialize, Debug, Clone)]
#[serde(rename_all = "camelCase")]
pub struct Document {
    pub asset: Asset,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub extensions_used: Vec<&'static str>,
    pub scene: usize,
    pub scenes: Vec<Scene>,
    pub nodes: Vec<Node>,
    pub meshes: Vec<Mesh>,
    pub materials: Vec<Material>,
    pub cameras: Vec<Camera>,
    pub textures: Vec<Texture>,
    pub images: Vec<Image>,
    pub samplers: Vec<Sampler>,
    pub accessors: Vec<Accessor>,
    pub buffer_views: Vec<BufferView>,
    pub buffers: Vec<Buffer>,
}

#[derive(Serialize, Debug, Clone)]
pub struct Asset {
    pub version: &'static str,
    pub generator: &'static str,
    pub copyright: &'static str,
}

#[derive(Serialize, Debug, Clone)]
pub struct Scene {
    pub name: String,
    pub nodes: Vec<usize>,
}

#[derive(Serialize, Debug, Clone, Default)]
pub struct Node {
    pub name: String,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub children: Vec<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub camera: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub translation: Option<[f32; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rotation: Option<[f32; 4]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scale: Option<[f32; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extras: Option<PprExtras>,
}

/// `extras` understood by `ppr-extract`: `{"ppr": {"reflector": …, "kind": …}}`.
#[derive(Serialize, Debug, Clone, PartialEq, Eq)]
pub struct PprExtras {
    pub ppr: PprOverride,
}

#[derive(Serialize, Debug, Clone, PartialEq, Eq)]
pub struct PprOverride {
    pub reflector: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kind: Option<&'static str>,
}

#[derive(Serialize, Debug, Clone)]
pub struct Mesh {
    pub name: String,
    pub primitives: Vec<Primitive>,
}

#[derive(Serialize, Debug, Clone)]
pub struct Primitive {
    pub attributes: Attributes,
    pub indices: usize,
    pub material: usize,
}

#[derive(Serialize, Debug, Clone, Copy, PartialEq, Eq)]
pub struct Attributes {
    #[serde(rename = "POSITION")]
    pub position: usize,
    #[serde(rename = "NORMAL")]
    pub normal: usize,
    #[serde(rename = "TEXCOORD_0")]
    pub texcoord_0: usize,
}

#[derive(Serialize, Debug, Clone)]
#[serde(rename_all = "camelCase")]
pub struct Material {
    pub name: String,
    pub pbr_metallic_roughness: PbrMetallicRoughness,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub alpha_mode: Option<&'static str>,
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub double_sided: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extensions: Option<MaterialExtensions>,
}

#[derive(Serialize, Debug, Clone)]
#[serde(rename_all = "camelCase")]
pub struct PbrMetallicRoughness {
    pub base_color_factor: [f32; 4],
    #[serde(skip_serializing_if = "Option::is_none")]
    pub base_color_texture: Option<TextureInfo>,
    pub metallic_factor: f32,
    pub roughness_factor: f32,
}

#[derive(Serialize, Debug, Clone)]
pub struct TextureInfo {
    pub index: usize,
}

#[derive(Serialize, Debug, Clone)]
pub struct MaterialExtensions {
    #[serde(rename = "KHR_materials_transmission")]
    pub transmission: Transmission,
}

#[derive(Serialize, Debug, Clone)]
#[serde(rename_all = "camelCase")]
pub struct Transmission {
    pub transmission_factor: f32,
}

#[derive(Serialize, Debug, Clone)]
pub struct Camera {
    pub name: String,
    #[serde(rename = "type")]
    pub kind: &'static str,
    pub perspective: Perspective,
}

#[derive(Serialize, Debug, Clone)]
pub struct Perspective {
    pub yfov: f32,
    pub znear: f32,
    pub zfar: f32,
}

#[derive(Serialize, Debug, Clone)]
pub struct Texture {
    pub name: String,
    pub sampler: usize,
    pub source: usize,
}

#[derive(Serialize, Debug, Clone)]
#[serde(rename_all = "camelCase")]
pub struct Image {
    pub name: String,
    pub buffer_view: usize,
    pub mime_type: &'static str,
}

#[derive(Serialize, Debug, Clone)]
#[serde(rename_all = "camelCase")]
pub struct Sampler {
    pub name: String,
    pub mag_filter: u32,
    pub min_filter: u32,
    pub wrap_s: u32,
    pub wrap_t: u32,
}

#[derive(Serialize, Debug, Clone)]
#[serde(rename_all = "camelCase")]
pub struct Accessor {
    pub buffer_view: usize,
    pub component_type: u32,
    pub count: usize,
    #[serde(rename = "type")]
    pub kind: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min: Option<Vec<f32>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max: Option<Vec<f32>>,
}

#[derive(Serialize, Debug, Clone)]
#[serde(rename_all = "camelCase")]
pub struct BufferView {
    pub buffer: usize,
    pub byte_offset: usize,
    pub byte_length: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target: Option<u32>,
}

#[derive(Serialize, Debug, Clone)]
#[serde(rename_all = "camelCase")]
pub struct Buffer {
    pub byte_length: usize,
}
