//! Small glTF files built in code (as `.glb`, or `.gltf` + `.bin`): what the loader tests
//! of every tool write their levels with, good and malformed alike (edit [`GltfBuilder::json`]
//! or [`GltfBuilder::bin`] before packing to break one field).

use std::path::{Path, PathBuf};

use image::ImageEncoder;
use serde_json::{Value, json};

/// How positions are stored.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PositionFormat {
    /// Plain f32.
    F32,
    /// `KHR_mesh_quantization`: normalized i16, the node scales by `range`.
    NormalizedI16,
}

/// A glTF document under construction.
pub struct GltfBuilder {
    /// The glTF JSON; arrays `nodes`, `meshes`, `materials`, `accessors`, `bufferViews`.
    pub json: Value,
    /// The one buffer's bytes.
    pub bin: Vec<u8>,
}

impl Default for GltfBuilder {
    fn default() -> Self {
        Self::new()
    }
}

impl GltfBuilder {
    /// An empty document with one scene and one buffer (filled when packed).
    pub fn new() -> Self {
        Self {
            json: json!({"asset": {"version": "2.0"}, "scenes": [{"nodes": []}], "scene": 0,
                         "nodes": [], "meshes": [], "materials": [], "accessors": [], "bufferViews": [], "buffers": []}),
            bin: Vec::new(),
        }
    }

    fn push_value(&mut self, key: &str, v: Value) -> usize {
        if !self.json[key].is_array() {
            self.json[key] = json!([]);
        }
        let arr = self.json[key].as_array_mut().expect("made an array above");
        arr.push(v);
        arr.len() - 1
    }

    /// Appends `bytes` (4-byte aligned) as a new buffer view; returns its index.
    pub fn view(&mut self, bytes: &[u8]) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.push("bufferViews", json!({"buffer": 0, "byteOffset": offset, "byteLength": bytes.len()}))
    }

    /// Adds a material; returns its index.
    pub fn material(&mut self, name: &str, roughness: f64, metallic: f64, extras: Option<Value>) -> usize {
        let mut m = json!({"name": name, "pbrMetallicRoughness": {"roughnessFactor": roughness, "metallicFactor": metallic}});
        if let Some(e) = extras {
            m["extras"] = e;
        }
        self.push("materials", m)
    }

    /// Adds a triangle-list mesh; returns its index. With `NormalizedI16` the positions
    /// must be within [-1, 1].
    pub fn mesh(
        &mut self,
        name: &str,
        positions: &[[f32; 3]],
        indices: &[u32],
        material: usize,
        format: PositionFormat,
    ) -> usize {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for p in positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let (bytes, component, normalized, min, max) = match format {
            PositionFormat::F32 => (
                positions.iter().flatten().flat_map(|f| f.to_le_bytes()).collect::<Vec<u8>>(),
                5126,
                false,
                json!(lo),
                json!(hi),
            ),
            PositionFormat::NormalizedI16 => {
                let q = |f: f32| (f * 32767.0).round() as i16;
                let mut b = Vec::new();
                for p in positions {
                    for &c in p {
                        b.extend(q(c).to_le_bytes());
                    }
                    b.extend([0u8, 0]); // pad each element to 8 bytes (4-byte alignment)
                }
                let qlo: Vec<i16> = lo.iter().map(|&f| q(f)).collect();
                let qhi: Vec<i16> = hi.iter().map(|&f| q(f)).collect();
                (b, 5122, true, json!(qlo), json!(qhi))
            }
        };
        let pview = self.view(&bytes);
        if format == PositionFormat::NormalizedI16 {
            self.json["bufferViews"][pview]["byteStride"] = json!(8);
        }
        let mut pacc = json!({"bufferView": pview, "componentType": component, "count": positions.len(), "type": "VEC3", "min": min, "max": max});
        if normalized {
            pacc["normalized"] = json!(true);
        }
        let pacc = self.push("accessors", pacc);
        let ib: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let iview = self.view(&ib);
        let iacc = self.push(
            "accessors",
            json!({"bufferView": iview, "componentType": 5125, "count": indices.len(), "type": "SCALAR"}),
        );
        self.push(
            "meshes",
            json!({"name": name, "primitives": [{"attributes": {"POSITION": pacc}, "indices": iacc, "material": material}]}),
        )
    }

    /// Adds texture coordinates (set 0) to every primitive of `mesh`, one per position.
    pub fn uvs(&mut self, mesh: usize, uvs: &[[f32; 2]]) {
        let bytes: Vec<u8> = uvs.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
        let view = self.view(&bytes);
        let acc = self.push(
            "accessors",
            json!({"bufferView": view, "componentType": 5126, "count": uvs.len(), "type": "VEC2"}),
        );
        for prim in self.json["meshes"][mesh]["primitives"].as_array_mut().into_iter().flatten() {
            prim["attributes"]["TEXCOORD_0"] = json!(acc);
        }
    }

    /// Adds a `width × height` PNG whose green channel is `green` (rows top to bottom; red
    /// and blue 0) as an embedded image and a texture with a sampler of the given glTF
    /// wrap mode (10497 repeat, 33648 mirrored, 33071 clamp), and binds it as `material`'s
    /// metallic-roughness texture; returns the texture's index.
    ///
    /// # Panics
    /// When `green` does not hold `width * height` texels.
    pub fn roughness_texture(
        &mut self,
        material: usize,
        width: u32,
        height: u32,
        green: &[u8],
        wrap: u32,
    ) -> usize {
        assert_eq!(green.len(), (width * height) as usize, "one green value per texel");
        let rgb: Vec<u8> = green.iter().flat_map(|&g| [0, g, 0]).collect();
        let mut png = Vec::new();
        image::codecs::png::PngEncoder::new(&mut png)
            .write_image(&rgb, width, height, image::ExtendedColorType::Rgb8)
            .expect("PNG encoding in memory does not fail");
        let view = self.view(&png);
        let img = self.push("images", json!({"bufferView": view, "mimeType": "image/png"}));
        let sampler = self.push("samplers", json!({"wrapS": wrap, "wrapT": wrap}));
        let texture = self.push("textures", json!({"source": img, "sampler": sampler}));
        self.json["materials"][material]["pbrMetallicRoughness"]["metallicRoughnessTexture"] =
            json!({"index": texture});
        texture
    }

    /// Adds a root node with a mesh and a TRS; returns its index.
    pub fn node(
        &mut self,
        name: &str,
        mesh: usize,
        translation: [f64; 3],
        rotation: [f64; 4],
        scale: [f64; 3],
    ) -> usize {
        let n = self.push("nodes", json!({"name": name, "mesh": mesh, "translation": translation, "rotation": rotation, "scale": scale}));
        self.push_root(n);
        n
    }

    /// Adds a JSON object to the array `key` (`"accessors"`, `"nodes"`, ...); returns its index.
    pub fn push(&mut self, key: &str, v: Value) -> usize {
        self.push_value(key, v)
    }

    /// Lists node `n` among the scene's root nodes.
    pub fn push_root(&mut self, n: usize) {
        if !self.json["scenes"][0]["nodes"].is_array() {
            self.json["scenes"][0]["nodes"] = json!([]);
        }
        self.json["scenes"][0]["nodes"].as_array_mut().expect("made an array above").push(json!(n));
    }

    fn finish_buffers(&mut self, uri: Option<&str>) {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut b = json!({"byteLength": self.bin.len()});
        if let Some(u) = uri {
            b["uri"] = json!(u);
        }
        self.json["buffers"] = json!([b]);
    }

    /// The `.glb` bytes, packed by `gltf::binary::Glb` (chunks padded to 4 bytes).
    pub fn glb(mut self) -> Vec<u8> {
        self.finish_buffers(None);
        let json = serde_json::to_vec(&self.json).expect("a serde_json::Value always serialises");
        let glb = gltf::binary::Glb {
            header: gltf::binary::Header { magic: *b"glTF", version: 2, length: 0 },
            json: json.into(),
            bin: Some(self.bin.into()),
        };
        glb.to_vec().expect("a level built in code is far below the 4 GiB a .glb can hold")
    }

    /// Writes `<dir>/<stem>.gltf` and `<dir>/<stem>.bin`; returns the `.gltf` path.
    ///
    /// # Errors
    /// When a file cannot be written.
    pub fn write_gltf(mut self, dir: &Path, stem: &str) -> std::io::Result<PathBuf> {
        let bin_name = format!("{stem}.bin");
        self.finish_buffers(Some(&bin_name));
        std::fs::write(dir.join(&bin_name), &self.bin)?;
        let path = dir.join(format!("{stem}.gltf"));
        std::fs::write(&path, serde_json::to_vec_pretty(&self.json).map_err(std::io::Error::other)?)?;
        Ok(path)
    }
}

/// A unit quad in the XZ plane facing +Y (two triangles, counter-clockwise from above).
pub fn quad_xz(x0: f32, z0: f32, x1: f32, z1: f32, y: f32) -> (Vec<[f32; 3]>, Vec<u32>) {
    (vec![[x0, y, z0], [x0, y, z1], [x1, y, z1], [x1, y, z0]], vec![0, 1, 2, 0, 2, 3])
}
