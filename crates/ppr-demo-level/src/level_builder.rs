//! `LevelBuilder`: collects textures, materials, meshes, nodes and cameras, packs the binary buffer and writes the glTF document (`gltf::json`'s types, serialised by serde).

use std::collections::BTreeMap;

use glam::{DMat4, DQuat, DVec3};
use gltf::json;
use gltf::json::validation::{Checked, USize64};

use crate::exact_trig::look_at_rotation;
use crate::mesh_data::MeshData;
use crate::png_encoder::{RgbImage, png_bytes};
use crate::ppr_extras::PprExtras;

/// Index of a texture of the level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureId(usize);
/// Index of a material of the level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MaterialId(usize);
/// Index of a vertex/index accessor set; several meshes may share one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GeometryId(usize);
/// Index of a mesh of the level; several nodes may instance one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MeshId(usize);
/// Index of a node of the level.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct NodeId(pub usize);

/// A metallic-roughness material.
#[derive(Clone, Debug)]
pub struct MaterialSpec {
    pub name: &'static str,
    /// Linear RGBA.
    pub base_color: [f32; 4],
    pub base_color_texture: Option<TextureId>,
    pub metallic: f32,
    pub roughness: f32,
    /// `KHR_materials_transmission`'s `transmissionFactor`, if any.
    pub transmission: Option<f32>,
    /// glTF `alphaMode`.
    pub alpha_mode: json::material::AlphaMode,
    pub double_sided: bool,
}

impl MaterialSpec {
    /// An opaque, single-sided, untextured material.
    pub fn opaque(name: &'static str, base_color: [f32; 3], metallic: f32, roughness: f32) -> Self {
        Self {
            name,
            base_color: [base_color[0], base_color[1], base_color[2], 1.0],
            base_color_texture: None,
            metallic,
            roughness,
            transmission: None,
            alpha_mode: json::material::AlphaMode::Opaque,
            double_sided: false,
        }
    }
}

/// Local transform of a node; stored in the file as `f32`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeTransform {
    pub translation: DVec3,
    pub rotation: DQuat,
    pub scale: DVec3,
}

impl NodeTransform {
    pub const IDENTITY: Self =
        Self { translation: DVec3::ZERO, rotation: DQuat::IDENTITY, scale: DVec3::ONE };

    pub fn at(translation: DVec3) -> Self {
        Self { translation, ..Self::IDENTITY }
    }

    pub fn with_rotation(self, rotation: DQuat) -> Self {
        Self { rotation, ..self }
    }

    pub fn with_scale(self, scale: DVec3) -> Self {
        Self { scale, ..self }
    }

    /// The transform exactly as a reader of the file sees it: every value rounded to
    /// `f32`, then composed in `f64`.
    pub fn stored_matrix(&self) -> DMat4 {
        let t = round_f32(self.translation.to_array());
        let r = round_f32(self.rotation.to_array());
        let s = round_f32(self.scale.to_array());
        DMat4::from_scale_rotation_translation(
            DVec3::from_array(s.map(f64::from)),
            DQuat::from_array(r.map(f64::from)),
            DVec3::from_array(t.map(f64::from)),
        )
    }
}

/// One node to add.
#[derive(Clone, Debug)]
pub struct NodeSpec {
    pub name: &'static str,
    pub parent: Option<NodeId>,
    pub mesh: Option<MeshId>,
    pub transform: NodeTransform,
    pub extras: Option<PprExtras>,
}

impl NodeSpec {
    /// A node without mesh (a group), at the root or under `parent`.
    pub fn group(name: &'static str, parent: Option<NodeId>, transform: NodeTransform) -> Self {
        Self { name, parent, mesh: None, transform, extras: None }
    }

    /// A node instancing `mesh`.
    pub fn instance(
        name: &'static str,
        parent: Option<NodeId>,
        mesh: MeshId,
        transform: NodeTransform,
    ) -> Self {
        Self { name, parent, mesh: Some(mesh), transform, extras: None }
    }

    pub fn with_extras(self, extras: PprExtras) -> Self {
        Self { extras: Some(extras), ..self }
    }
}

struct StoredNode {
    spec: NodeSpec,
    children: Vec<usize>,
    camera: Option<usize>,
}

struct StoredMesh {
    name: &'static str,
    primitives: Vec<(GeometryId, MaterialId)>,
}

/// Geometry as stored in the file (`f32`), for ground-truth computations.
pub struct StoredGeometry {
    pub positions: Vec<[f32; 3]>,
    pub indices: Vec<u32>,
    attributes: Attributes,
    indices_accessor: usize,
}

/// The accessors of a geometry's vertex attributes.
#[derive(Clone, Copy, Debug)]
struct Attributes {
    position: usize,
    normal: usize,
    texcoord_0: usize,
}

impl Attributes {
    fn to_gltf(self) -> BTreeMap<Checked<json::mesh::Semantic>, json::Index<json::Accessor>> {
        use json::mesh::Semantic;
        [
            (Semantic::Positions, self.position),
            (Semantic::Normals, self.normal),
            (Semantic::TexCoords(0), self.texcoord_0),
        ]
        .into_iter()
        .map(|(semantic, accessor)| (Checked::Valid(semantic), index(accessor)))
        .collect()
    }
}

/// Builds the glTF document and its binary buffer.
#[derive(Default)]
pub struct LevelBuilder {
    bin: Vec<u8>,
    buffer_views: Vec<json::buffer::View>,
    accessors: Vec<json::Accessor>,
    images: Vec<json::Image>,
    textures: Vec<json::Texture>,
    materials: Vec<MaterialSpec>,
    geometries: Vec<StoredGeometry>,
    meshes: Vec<StoredMesh>,
    nodes: Vec<StoredNode>,
    cameras: Vec<json::Camera>,
}

const SAMPLER_LINEAR_REPEAT: usize = 0;

impl LevelBuilder {
    pub fn new() -> Self {
        Self::default()
    }

    /// Embeds `image` as a PNG in the buffer and returns a texture (linear, mipmapped,
    /// repeating) that samples it.
    pub fn add_texture(&mut self, name: &'static str, image: &RgbImage) -> TextureId {
        let view = self.push_view(&png_bytes(image), None);
        self.images.push(json::Image {
            name: Some(name.to_owned()),
            buffer_view: Some(index(view)),
            mime_type: Some(json::image::MimeType("image/png".to_owned())),
            uri: None,
            extensions: None,
            extras: None,
        });
        self.textures.push(json::Texture {
            name: Some(name.to_owned()),
            sampler: Some(index(SAMPLER_LINEAR_REPEAT)),
            source: index(self.images.len() - 1),
            extensions: None,
            extras: None,
        });
        TextureId(self.textures.len() - 1)
    }

    pub fn add_material(&mut self, material: MaterialSpec) -> MaterialId {
        self.materials.push(material);
        MaterialId(self.materials.len() - 1)
    }

    /// Stores the vertices and indices of `mesh` (POSITION with min/max, NORMAL,
    /// TEXCOORD_0; u16 indices when they fit, else u32).
    pub fn add_geometry(&mut self, mesh: &MeshData) -> GeometryId {
        let positions: Vec<[f32; 3]> = mesh.positions.iter().map(|p| round_f32(p.to_array())).collect();
        let normals: Vec<[f32; 3]> =
            mesh.normals.iter().map(|n| round_f32(n.normalize().to_array())).collect();
        let uvs: Vec<[f32; 2]> = mesh.uvs.iter().map(|uv| round_f32(uv.to_array())).collect();

        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        for p in &positions {
            for k in 0..3 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
        let position = self.push_f32_accessor(
            positions.as_flattened(),
            json::accessor::Type::Vec3,
            Some((min.to_vec(), max.to_vec())),
        );
        let normal = self.push_f32_accessor(normals.as_flattened(), json::accessor::Type::Vec3, None);
        let texcoord_0 = self.push_f32_accessor(uvs.as_flattened(), json::accessor::Type::Vec2, None);

        let fits_u16 = positions.len() <= usize::from(u16::MAX);
        let (bytes, component_type) = if fits_u16 {
            let short =
                |i: &u32| u16::try_from(*i).expect("checked: fewer than 65535 vertices").to_le_bytes();
            (mesh.indices.iter().flat_map(short).collect::<Vec<u8>>(), json::accessor::ComponentType::U16)
        } else {
            (mesh.indices.iter().flat_map(|i| i.to_le_bytes()).collect(), json::accessor::ComponentType::U32)
        };
        let view = self.push_view(&bytes, Some(json::buffer::Target::ElementArrayBuffer));
        self.accessors.push(accessor(
            view,
            component_type,
            mesh.indices.len(),
            json::accessor::Type::Scalar,
            None,
        ));
        let indices_accessor = self.accessors.len() - 1;

        self.geometries.push(StoredGeometry {
            positions,
            indices: mesh.indices.clone(),
            attributes: Attributes { position, normal, texcoord_0 },
            indices_accessor,
        });
        GeometryId(self.geometries.len() - 1)
    }

    /// A mesh whose primitives draw the given geometries with the given materials.
    pub fn add_mesh(&mut self, name: &'static str, primitives: &[(GeometryId, MaterialId)]) -> MeshId {
        self.meshes.push(StoredMesh { name, primitives: primitives.to_vec() });
        MeshId(self.meshes.len() - 1)
    }

    pub fn add_node(&mut self, spec: NodeSpec) -> NodeId {
        let index = self.nodes.len();
        if let Some(NodeId(parent)) = spec.parent {
            self.nodes[parent].children.push(index);
        }
        self.nodes.push(StoredNode { spec, children: Vec::new(), camera: None });
        NodeId(index)
    }

    /// A root node `name` holding a perspective camera at `eye` looking at `target`.
    pub fn add_camera(&mut self, name: &'static str, eye: DVec3, target: DVec3, yfov_radians: f32) -> NodeId {
        self.cameras.push(json::Camera {
            name: Some(name.to_owned()),
            type_: Checked::Valid(json::camera::Type::Perspective),
            perspective: Some(json::camera::Perspective {
                aspect_ratio: None,
                yfov: yfov_radians,
                zfar: Some(200.0),
                znear: 0.05,
                extensions: None,
                extras: None,
            }),
            orthographic: None,
            extensions: None,
            extras: None,
        });
        let transform = NodeTransform::at(eye).with_rotation(look_at_rotation(eye, target));
        let node = self.add_node(NodeSpec::group(name, None, transform));
        self.nodes[node.0].camera = Some(self.cameras.len() - 1);
        node
    }

    /// The node's world matrix as a reader of the file computes it.
    pub fn world_matrix(&self, node: NodeId) -> DMat4 {
        let stored = &self.nodes[node.0];
        let local = stored.spec.transform.stored_matrix();
        match stored.spec.parent {
            Some(parent) => self.world_matrix(parent) * local,
            None => local,
        }
    }

    pub fn node_name(&self, node: NodeId) -> &'static str {
        self.nodes[node.0].spec.name
    }

    pub fn node_mesh(&self, node: NodeId) -> Option<MeshId> {
        self.nodes[node.0].spec.mesh
    }

    pub fn mesh_name(&self, mesh: MeshId) -> &'static str {
        self.meshes[mesh.0].name
    }

    /// The geometry and material of a mesh's primitive.
    pub fn primitive(&self, mesh: MeshId, primitive: usize) -> Option<(&StoredGeometry, &MaterialSpec)> {
        let (geometry, material) = self.meshes[mesh.0].primitives.get(primitive)?;
        Some((&self.geometries[geometry.0], &self.materials[material.0]))
    }

    /// The glTF JSON document and the binary buffer it refers to.
    pub fn to_document(&self, scene_name: &str) -> (json::Root, Vec<u8>) {
        let mut bin = self.bin.clone();
        bin.resize(bin.len().next_multiple_of(4), 0);
        let uses_transmission = self.materials.iter().any(|m| m.transmission.is_some());
        let document = json::Root {
            asset: json::Asset {
                version: "2.0".to_owned(),
                generator: Some("ppr-demo-level (cargo run -p ppr-demo-level)".to_owned()),
                copyright: Some("PPR toolkit contributors, MIT OR Apache-2.0".to_owned()),
                ..json::Asset::default()
            },
            extensions_used: if uses_transmission {
                vec!["KHR_materials_transmission".to_owned()]
            } else {
                Vec::new()
            },
            scene: Some(index(0)),
            scenes: vec![json::Scene {
                name: Some(scene_name.to_owned()),
                nodes: (0..self.nodes.len())
                    .filter(|&i| self.nodes[i].spec.parent.is_none())
                    .map(index)
                    .collect(),
                extensions: None,
                extras: None,
            }],
            nodes: self.nodes.iter().map(stored_node_to_gltf).collect(),
            meshes: self
                .meshes
                .iter()
                .map(|mesh| json::Mesh {
                    name: Some(mesh.name.to_owned()),
                    primitives: mesh
                        .primitives
                        .iter()
                        .map(|(geometry, material)| json::mesh::Primitive {
                            attributes: self.geometries[geometry.0].attributes.to_gltf(),
                            indices: Some(index(self.geometries[geometry.0].indices_accessor)),
                            material: Some(index(material.0)),
                            mode: Checked::Valid(json::mesh::Mode::Triangles),
                            targets: None,
                            extensions: None,
                            extras: None,
                        })
                        .collect(),
                    weights: None,
                    extensions: None,
                    extras: None,
                })
                .collect(),
            materials: self.materials.iter().map(material_to_gltf).collect(),
            cameras: self.cameras.clone(),
            textures: self.textures.clone(),
            images: self.images.clone(),
            samplers: vec![json::texture::Sampler {
                name: Some("linear_repeat".to_owned()),
                mag_filter: Some(Checked::Valid(json::texture::MagFilter::Linear)),
                min_filter: Some(Checked::Valid(json::texture::MinFilter::LinearMipmapLinear)),
                wrap_s: Checked::Valid(json::texture::WrappingMode::Repeat),
                wrap_t: Checked::Valid(json::texture::WrappingMode::Repeat),
                extensions: None,
                extras: None,
            }],
            accessors: self.accessors.clone(),
            buffer_views: self.buffer_views.clone(),
            buffers: vec![json::Buffer {
                byte_length: USize64::from(bin.len()),
                name: None,
                uri: None,
                extensions: None,
                extras: None,
            }],
            ..json::Root::default()
        };
        (document, bin)
    }

    /// Appends `bytes` to the buffer (4-byte aligned) as a new buffer view.
    fn push_view(&mut self, bytes: &[u8], target: Option<json::buffer::Target>) -> usize {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        self.buffer_views.push(json::buffer::View {
            buffer: index(0),
            byte_offset: Some(USize64::from(self.bin.len())),
            byte_length: USize64::from(bytes.len()),
            byte_stride: None,
            target: target.map(Checked::Valid),
            name: None,
            extensions: None,
            extras: None,
        });
        self.bin.extend_from_slice(bytes);
        self.buffer_views.len() - 1
    }

    fn push_f32_accessor(
        &mut self,
        values: &[f32],
        kind: json::accessor::Type,
        bounds: Option<(Vec<f32>, Vec<f32>)>,
    ) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.push_view(&bytes, Some(json::buffer::Target::ArrayBuffer));
        let count = values.len() / kind.multiplicity();
        self.accessors.push(accessor(view, json::accessor::ComponentType::F32, count, kind, bounds));
        self.accessors.len() - 1
    }
}

/// glTF's index of the `i`-th element of its array.
fn index<T>(i: usize) -> json::Index<T> {
    json::Index::new(u32::try_from(i).expect("the demo level has far fewer than 2^32 of anything"))
}

/// A tightly packed accessor of the whole buffer view `view`, with `min` and `max` when
/// given.
fn accessor(
    view: usize,
    component_type: json::accessor::ComponentType,
    count: usize,
    kind: json::accessor::Type,
    bounds: Option<(Vec<f32>, Vec<f32>)>,
) -> json::Accessor {
    let (min, max) =
        bounds.map(|(lo, hi)| (serde_json::Value::from(lo), serde_json::Value::from(hi))).unzip();
    json::Accessor {
        buffer_view: Some(index(view)),
        byte_offset: None,
        count: USize64::from(count),
        component_type: Checked::Valid(json::accessor::GenericComponentType(component_type)),
        type_: Checked::Valid(kind),
        min,
        max,
        name: None,
        normalized: false,
        sparse: None,
        extensions: None,
        extras: None,
    }
}

fn stored_node_to_gltf(node: &StoredNode) -> json::Node {
    let transform = node.spec.transform;
    let translation = round_f32(transform.translation.to_array());
    let rotation = round_f32(transform.rotation.to_array());
    let scale = round_f32(transform.scale.to_array());
    json::Node {
        name: Some(node.spec.name.to_owned()),
        children: (!node.children.is_empty()).then(|| node.children.iter().copied().map(index).collect()),
        mesh: node.spec.mesh.map(|MeshId(i)| index(i)),
        camera: node.camera.map(index),
        translation: (translation != [0.0; 3]).then_some(translation),
        rotation: (rotation != [0.0, 0.0, 0.0, 1.0]).then_some(json::scene::UnitQuaternion(rotation)),
        scale: (scale != [1.0; 3]).then_some(scale),
        extras: node.spec.extras.as_ref().map(PprExtras::to_raw),
        ..json::Node::default()
    }
}

fn material_to_gltf(material: &MaterialSpec) -> json::Material {
    json::Material {
        name: Some(material.name.to_owned()),
        pbr_metallic_roughness: json::material::PbrMetallicRoughness {
            base_color_factor: json::material::PbrBaseColorFactor(material.base_color),
            base_color_texture: material.base_color_texture.map(|TextureId(i)| json::texture::Info {
                index: index(i),
                tex_coord: 0,
                extensions: None,
                extras: None,
            }),
            metallic_factor: json::material::StrengthFactor(material.metallic),
            roughness_factor: json::material::StrengthFactor(material.roughness),
            ..json::material::PbrMetallicRoughness::default()
        },
        alpha_mode: Checked::Valid(material.alpha_mode),
        double_sided: material.double_sided,
        extensions: material.transmission.map(|factor| json::extensions::material::Material {
            transmission: Some(json::extensions::material::Transmission {
                transmission_factor: json::extensions::material::TransmissionFactor(factor),
                transmission_texture: None,
                extras: None,
            }),
            ..json::extensions::material::Material::default()
        }),
        ..json::Material::default()
    }
}

/// Rounds each value to the nearest `f32` (what the file stores).
fn round_f32<const N: usize>(values: [f64; N]) -> [f32; N] {
    values.map(|v| v as f32)
}
