//! Metallic-roughness textures reduced to what reflections need: the green channel
//! (glTF's roughness), with the sampler's wrap modes. Decoded for the extractor, which
//! averages it over each reflector's surface; a texture that cannot be read or decoded is
//! a note, and the material's roughness factor is used alone.

use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use crate::buffers::BufferData;
use crate::extras::display_name;
use crate::images::decode;

/// How a texture coordinate outside `[0, 1]` is brought back in (glTF sampler wrap modes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Wrap {
    /// `REPEAT` (glTF's default).
    #[default]
    Repeat,
    /// `MIRRORED_REPEAT`.
    MirroredRepeat,
    /// `CLAMP_TO_EDGE`.
    ClampToEdge,
}

impl Wrap {
    fn from_gltf(mode: gltf::texture::WrappingMode) -> Self {
        match mode {
            gltf::texture::WrappingMode::Repeat => Self::Repeat,
            gltf::texture::WrappingMode::MirroredRepeat => Self::MirroredRepeat,
            gltf::texture::WrappingMode::ClampToEdge => Self::ClampToEdge,
        }
    }

    /// The texel index along an axis of `size` texels for the coordinate `t`.
    fn texel(self, t: f64, size: u32) -> usize {
        let n = f64::from(size);
        let x = (t * n).floor();
        let x = if x.is_finite() { x } else { 0.0 };
        let i = match self {
            Self::Repeat => x.rem_euclid(n),
            Self::MirroredRepeat => {
                let m = x.rem_euclid(2.0 * n);
                if m < n { m } else { 2.0 * n - 1.0 - m }
            }
            Self::ClampToEdge => x.clamp(0.0, n - 1.0),
        };
        // `i` is an integer in [0, n - 1]: the cast is exact.
        (i as usize).min(size as usize - 1)
    }
}

/// The green channel of a metallic-roughness texture and how its sampler wraps.
///
/// Invariants: `width` and `height` are at least 1 and `green` holds `width * height`
/// texels, rows top to bottom (texture coordinate v = 0 is the top row, as in glTF).
#[derive(Clone, Debug, PartialEq)]
pub struct RoughnessMap {
    /// The image's name, or `#index`.
    pub name: String,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Green channel (roughness, 0 to 255 for 0 to 1, linear), one byte per texel.
    pub green: Vec<u8>,
    /// Wrap along u and v.
    pub wrap: [Wrap; 2],
}

impl RoughnessMap {
    /// The roughness, in `[0, 1]`, of the texel under the texture coordinate `uv`
    /// (nearest texel, after the sampler's wrap).
    pub fn at(&self, uv: [f64; 2]) -> f64 {
        let x = self.wrap[0].texel(uv[0], self.width);
        let y = self.wrap[1].texel(uv[1], self.height);
        f64::from(self.green[y * self.width as usize + x]) / 255.0
    }

    /// The mean roughness of every texel, in `[0, 1]`.
    pub fn mean(&self) -> f64 {
        let sum: u64 = self.green.iter().map(|&g| u64::from(g)).sum();
        sum as f64 / (255.0 * self.green.len() as f64)
    }
}

/// Decodes the metallic-roughness texture of every material that has one; returns, per
/// glTF texture index, its map. Textures that fail become `notes`.
pub(crate) fn read_roughness_maps(
    doc: &gltf::Document,
    data: &BufferData,
    base_dir: &Path,
    notes: &mut Vec<String>,
) -> HashMap<usize, Arc<RoughnessMap>> {
    let mut maps = HashMap::new();
    let mut tried = std::collections::HashSet::new();
    for material in doc.materials() {
        let Some(info) = material.pbr_metallic_roughness().metallic_roughness_texture() else { continue };
        let material_name = display_name(material.name(), material.index().unwrap_or(0));
        if info.tex_coord() != 0 {
            notes.push(format!(
                "material {material_name}: metallic-roughness texture uses UV set {}, only set 0 is read",
                info.tex_coord()
            ));
        }
        let texture = info.texture();
        if !tried.insert(texture.index()) {
            continue;
        }
        let image = texture.source();
        let name = display_name(image.name(), image.index());
        match decode(doc, &image, data, base_dir) {
            Ok((width, height, rgba8)) if width > 0 && height > 0 => {
                let sampler = texture.sampler();
                let map = RoughnessMap {
                    name,
                    width,
                    height,
                    green: rgba8.chunks_exact(4).map(|texel| texel[1]).collect(),
                    wrap: [Wrap::from_gltf(sampler.wrap_s()), Wrap::from_gltf(sampler.wrap_t())],
                };
                maps.insert(texture.index(), Arc::new(map));
            }
            Ok(_) => notes.push(format!(
                "image {name} (images[{}]): empty; roughness factor used alone",
                image.index()
            )),
            Err(reason) => notes.push(format!(
                "image {name} (images[{}]): {reason}; roughness factor used alone",
                image.index()
            )),
        }
    }
    maps
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(wrap: Wrap) -> RoughnessMap {
        RoughnessMap {
            name: "m".into(),
            width: 4,
            height: 2,
            green: (0..8).map(|g| g * 10).collect(),
            wrap: [wrap; 2],
        }
    }

    #[test]
    fn wrap_modes_pick_texels_as_samplers_do() {
        let r = map(Wrap::Repeat);
        assert_eq!(r.at([0.1, 0.1]), 0.0);
        assert_eq!(r.at([0.3, 0.7]), 50.0 / 255.0); // x 1, y 1
        assert_eq!(r.at([1.3, -0.3]), r.at([0.3, 0.7]));
        let m = map(Wrap::MirroredRepeat);
        assert_eq!(m.at([1.1, 0.1]), m.at([0.9, 0.1])); // mirrored back into the last texel
        let c = map(Wrap::ClampToEdge);
        assert_eq!(c.at([7.0, -3.0]), 30.0 / 255.0); // x 3, y 0
        assert_eq!(c.at([f64::NAN, 0.0]), 0.0);
        assert!((r.mean() - 35.0 / 255.0).abs() < 1e-12);
    }
}
