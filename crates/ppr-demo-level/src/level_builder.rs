//! `LevelBuilder`: collects textures, materials, meshes, nodes and cameras, packs the binary buffer and writes the glTF document.

use glam::{DMat4, DQuat, DVec3};

use crate::exact_trig::look_at_rotation;
use crate::gltf_document as gltf;
use crate::mesh_data::MeshData;
use crate::png_encoder::{RgbImage, png_bytes};

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
    /// glTF `alphaMode` (`None`: OPAQUE).
    pub alpha_mode: Option<&'static str>,
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
            alpha_mode: None,
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
    pub extras: Option<gltf::PprExtras>,
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

    pub fn with_extras(self, extras: gltf::PprExtras) -> Self {
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
    attributes: gltf::Attributes,
    indices_accessor: usize,
}

/// Builds the glTF document and its binary buffer.
#[derive(Default)]
pub struct LevelBuilder {
    bin: Vec<u8>,
    buffer_views: Vec<gltf::BufferView>,
    accessors: Vec<gltf::Accessor>,
    images: Vec<gltf::Image>,
    textures: Vec<gltf::Texture>,
    materials: Vec<MaterialSpec>,
    geometries: Vec<StoredGeometry>,
    meshes: Vec<StoredMesh>,
    nodes: Vec<StoredNode>,
    cameras: Vec<gltf::Camera>,
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
        self.images.push(gltf::Image { name: name.to_owned(), buffer_view: view, mime_type: "image/png" });
        self.textures.push(gltf::Texture {
            name: name.to_owned(),
            sampler: SAMPLER_LINEAR_REPEAT,
            source: self.images.len() - 1,
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
        let position =
            self.push_f32_accessor(positions.as_flattened(), "VEC3", Some((min.to_vec(), max.to_vec())));
        let normal = self.push_f32_accessor(normals.as_flattened(), "VEC3", None);
        let texcoord_0 = self.push_f32_accessor(uvs.as_flattened(), "VEC2", None);

        let fits_u16 = positions.len() <= usize::from(u16::MAX);
        let (bytes, component_type): (Vec<u8>, u32) = if fits_u16 {
            let short =
                |i: &u32| u16::try_from(*i).expect("checked: fewer than 65535 vertices").to_le_bytes();
            (mesh.indices.iter().flat_map(short).collect(), gltf::COMPONENT_U16)
        } else {
            (mesh.indices.iter().flat_map(|i| i.to_le_bytes()).collect(), gltf::COMPONENT_U32)
        };
        let view = self.push_view(&bytes, Some(gltf::TARGET_ELEMENT_ARRAY_BUFFER));
        self.accessors.push(gltf::Accessor {
            buffer_view: view,
            component_type,
            count: mesh.indices.len(),
            kind: "SCALAR",
            min: None,
            max: None,
        });
        let indices_accessor = self.accessors.len() - 1;

        self.geometries.push(StoredGeometry {
            positions,
            indices: mesh.indices.clone(),
            attributes: gltf::Attributes { position, normal, texcoord_0 },
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
        self.cameras.push(gltf::Camera {
            name: name.to_owned(),
            kind: "perspective",
            perspective: gltf::Perspective { yfov: yfov_radians, znear: 0.05, zfar: 200.0 },
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
    pub fn to_document(&self, scene_name: &str) -> (gltf::Document, Vec<u8>) {
        let mut bin = self.bin.clone();
        bin.resize(bin.len().next_multiple_of(4), 0);
        let uses_transmission = self.materials.iter().any(|m| m.transmission.is_some());
        let document = gltf::Document {
            asset: gltf::Asset {
                version: "2.0",
                generator: "ppr-demo-level (cargo run -p ppr-demo-level)",
                copyright: "PPR toolkit contributors, MIT OR Apache-2.0",
            },
            extensions_used: if uses_transmission { vec!["KHR_materials_transmission"] } else { Vec::new() },
            scene: 0,
            scenes: vec![gltf::Scene {
                name: scene_name.to_owned(),
                nodes: (0..self.nodes.len()).filter(|&i| self.nodes[i].spec.parent.is_none()).collect(),
            }],
            nodes: self.nodes.iter().map(stored_node_to_gltf).collect(),
            meshes: self
                .meshes
                .iter()
                .map(|mesh| gltf::Mesh {
                    name: mesh.name.to_owned(),
                    primitives: mesh
                        .primitives
                        .iter()
                        .map(|(geometry, material)| gltf::Primitive {
                            attributes: self.geometries[geometry.0].attributes,
                            indices: self.geometries[geometry.0].indices_accessor,
                            material: material.0,
                        })
                        .collect(),
                })
                .collect(),
            materials: self.materials.iter().map(material_to_gltf).collect(),
            cameras: self.cameras.clone(),
            textures: self.textures.clone(),
            images: self.images.clone(),
            samplers: vec![gltf::Sampler {
                name: "linear_repeat".to_owned(),
                mag_filter: 9729, // LINEAR
                min_filter: 9987, // LINEAR_MIPMAP_LINEAR
                wrap_s: 10497,    // REPEAT
                wrap_t: 10497,
            }],
            accessors: self.accessors.clone(),
            buffer_views: self.buffer_views.clone(),
            buffers: vec![gltf::Buffer { byte_length: bin.len() }],
        };
        (document, bin)
    }

    /// Appends `bytes` to the buffer (4-byte aligned) as a new buffer view.
    fn push_view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        self.buffer_views.push(gltf::BufferView {
            buffer: 0,
            byte_offset: self.bin.len(),
            byte_length: bytes.len(),
            target,
        });
        self.bin.extend_from_slice(bytes);
        self.buffer_views.len() - 1
    }

    fn push_f32_accessor(
        &mut self,
        values: &[f32],
        kind: &'static str,
        bounds: Option<(Vec<f32>, Vec<f32>)>,
    ) -> usize {
        let components = if kind == "VEC3" { 3 } else { 2 };
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.push_view(&bytes, Some(gltf::TARGET_ARRAY_BUFFER));
        let (min, max) = bounds.unzip();
        self.accessors.push(gltf::Accessor {
            buffer_view: view,
            component_type: gltf::COMPONENT_F32,
            count: values.len() / components,
            kind,
            min,
            max,
        });
        self.accessors.len() - 1
    }
}

fn stored_node_to_gltf(node: &StoredNode) -> gltf::Node {
    let transform = node.spec.transform;
    let translation = round_f32(transform.translation.to_array());
    let rotation = round_f32(transform.rotation.to_array());
    let scale = round_f32(transform.scale.to_array());
    gltf::Node {
        name: node.spec.name.to_owned(),
        children: node.children.clone(),
        mesh: node.spec.mesh.map(|MeshId(i)| i),
        camera: node.camera,
        translation: (translation != [0.0; 3]).then_some(translation),
        rotation: (rotation != [0.0, 0.0, 0.0, 1.0]).then_some(rotation),
        scale: (scale != [1.0; 3]).then_some(scale),
        extras: node.spec.extras.clone(),
    }
}

fn material_to_gltf(material: &MaterialSpec) -> gltf::Material {
    gltf::Material {
        name: material.name.to_owned(),
        pbr_metallic_roughness: gltf::PbrMetallicRoughness {
            base_color_factor: material.base_color,
            base_color_texture: material
                .base_color_texture
                .map(|TextureId(index)| gltf::TextureInfo { index }),
            metallic_factor: material.metallic,
            roughness_factor: material.roughness,
        },
        alpha_mode: material.alpha_mode,
        double_sided: material.double_sided,
        extensions: material.transmission.map(|transmission_factor| gltf::MaterialExtensions {
            transmission: gltf::Transmission { transmission_factor },
        }),
    }
}

/// Rounds each value to the nearest `f32` (what the file stores).
fn round_f32<const N: usize>(values: [f64; N]) -> [f32; N] {
    values.map(|v| v as f32)
}
