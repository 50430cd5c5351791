//! The light of the scene raster passes (`lit_colour` of `scene_raster.wgsl`): one sun plus
//! ambient, no shadows; the testbed's G-buffer and the walkthrough's forward pass share it,
//! so their frames compare.

use glam::Vec3;

/// One directional light plus ambient.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lighting {
    /// Direction towards the light (world space, normalised when used).
    pub direction: Vec3,
    /// Linear intensity of the light (multiplies Lambert's cosine).
    pub intensity: f32,
    /// Linear ambient colour added to the light.
    pub ambient: [f32; 3],
}

impl Default for Lighting {
    fn default() -> Self {
        Self { direction: Vec3::new(0.35, 1.0, 0.55), intensity: 0.85, ambient: [0.25, 0.25, 0.27] }
    }
}

impl Lighting {
    /// The `light` (xyz: unit direction towards the light, w: intensity) and `ambient`
    /// (rgb) vectors of a pass's view uniform.
    pub fn uniform_vectors(&self) -> ([f32; 4], [f32; 4]) {
        let l = self.direction.normalize_or(Vec3::Y);
        let a = self.ambient;
        ([l.x, l.y, l.z, self.intensity], [a[0], a[1], a[2], 0.0])
    }
}
