//! Which surfaces take a reflection, and how much: the game's material rule, not PPR's.
//!
//! PPR only says *what* is reflected at a pixel (and whether it found anything); the
//! renderer decides *how much* of it to show. Here: a surface is reflective when its
//! glTF `extras.ppr.reflector` says so, or, without that hint, when it is smooth
//! (roughness below [`REFLECTIVE_ROUGHNESS`]), metallic, or transmissive (the rule the
//! extractor and the testbed use). Its reflectivity falls with roughness; the forward
//! pass multiplies it by a Fresnel term.

use crate::gltf_level::Material;

/// Surfaces smoother than this are reflective without a hint.
pub const REFLECTIVE_ROUGHNESS: f32 = 0.1;

/// Reflectivity in `[0, 1]` of `material` on an instance with `instance_hint`
/// (`extras.ppr.reflector` of the node or mesh, which wins over the material's).
pub fn reflectivity(material: &Material, instance_hint: Option<bool>) -> f32 {
    let by_material =
        material.roughness < REFLECTIVE_ROUGHNESS || material.metallic >= 0.5 || material.transmission > 0.0;
    if !instance_hint.or(material.ppr.reflector).unwrap_or(by_material) {
        return 0.0;
    }
    let smoothness = (1.0 - material.roughness).clamp(0.0, 1.0);
    smoothness * smoothness
}

#[cfg(test)]
mod tests {
    use super::*;

    fn material(roughness: f32, metallic: f32) -> Material {
        Material { roughness, metallic, ..Material::default() }
    }

    #[test]
    fn smooth_or_metallic_surfaces_reflect_and_hints_win() {
        assert!(reflectivity(&material(0.02, 1.0), None) > 0.95, "mirror");
        assert!(reflectivity(&material(0.05, 0.0), None) > 0.9, "polished marble");
        assert_eq!(reflectivity(&material(0.9, 0.0), None), 0.0, "brick");
        assert_eq!(reflectivity(&material(0.2, 0.0), None), 0.0, "lacquered wood");
        assert_eq!(reflectivity(&material(0.02, 0.0), Some(false)), 0.0, "node says no");
        assert!(reflectivity(&material(0.2, 0.0), Some(true)) > 0.6, "node says yes");
        assert_eq!(reflectivity(&Material::default(), None), 0.0, "glTF default: metallic but fully rough");
    }
}
