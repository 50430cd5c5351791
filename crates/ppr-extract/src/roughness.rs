//! Each reflector's roughness, from its glTF materials: the perceptual roughness (glTF's
//! `roughnessFactor` times the metallic-roughness texture's green channel) averaged over
//! the surface the reflector encloses.
//!
//! The statistic is the **area-weighted mean over the region's surface**: per triangle,
//! the factor times the mean of the texels its UV footprint covers; per reflector, the
//! mean of its triangles' values weighted by their area (so a region that merges
//! triangles of several materials takes each material in proportion to its area). Why the
//! mean: the blur a viewer sees on a glossy surface integrates the surface under each
//! pixel, and a reflector has one roughness for all of its pixels, so the number that is
//! right on average over its pixels is the surface mean. The whole texture's mean would be
//! wrong for atlases and trim sheets, where a floor uses only a part of the texture; the
//! mean of perceptual roughness (not of GGX's α = roughness²) is kept because it is the
//! quantity glTF stores and artists edit.
//!
//! Sampling: a triangle's UV footprint is cut into `n²` equal-area sub-triangles (the
//! regular subdivision) and the texel under each one's centroid is read (nearest, with the
//! sampler's wrap), `n` chosen for about four samples per texel covered and at most
//! [`MAX_SUBDIVISIONS`]: the cost stays linear in the triangles, and the same triangle
//! always gives the same bits. Within a triangle UVs are affine, so equal UV areas are
//! equal surface areas. A triangle cut by a split keeps its whole triangle's mean.

use glam::DVec2;

use crate::level::Level;
use crate::polygon::Polygon;

/// The most subdivisions per triangle side: at most `MAX_SUBDIVISIONS²` texel reads per
/// triangle.
pub const MAX_SUBDIVISIONS: usize = 32;

/// The perceptual roughness of triangle `triangle` of `level`, in `[0, 1]`: its material's
/// roughness factor times the mean of its roughness map over the triangle's UVs (the
/// factor alone without a map, or when the level kept no UVs).
pub fn triangle_roughness(level: &Level, triangle: usize) -> f64 {
    let source = level.triangles[triangle].source as usize;
    let material = &level.materials[level.sources[source].material as usize];
    let factor = material.roughness.clamp(0.0, 1.0);
    let (Some(map), Some(uvs)) = (&material.roughness_map, level.uvs.get(triangle)) else {
        return factor;
    };
    let [a, b, c] = uvs.map(|uv| DVec2::new(f64::from(uv[0]), f64::from(uv[1])));
    let (e1, e2) = (b - a, c - a);
    // About four samples per texel covered, and one per texel along the longest edge (for
    // footprints of little area).
    let size = DVec2::new(f64::from(map.width), f64::from(map.height));
    let texels = 0.5 * (e1 * size).perp_dot(e2 * size).abs();
    let longest = [e1, e2, c - b].map(|e| (e * size).length()).into_iter().fold(0.0, f64::max);
    let n = (2.0 * texels.sqrt()).max(longest).ceil();
    let n = if n.is_finite() { n.clamp(1.0, MAX_SUBDIVISIONS as f64) } else { 1.0 };
    let n = n as usize; // an integer in [1, MAX_SUBDIVISIONS]
    let inv = 1.0 / n as f64;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n - i {
            // The upward sub-triangle at (i, j), and the downward one beside it.
            let (s, t) = ((i as f64 + 1.0 / 3.0) * inv, (j as f64 + 1.0 / 3.0) * inv);
            sum += map.at((a + e1 * s + e2 * t).to_array());
            if i + j + 2 <= n {
                let (s, t) = ((i as f64 + 2.0 / 3.0) * inv, (j as f64 + 2.0 / 3.0) * inv);
                sum += map.at((a + e1 * s + e2 * t).to_array());
            }
        }
    }
    (factor * sum / (n * n) as f64).clamp(0.0, 1.0)
}

/// The area-weighted mean roughness of `polygons` (each carries its triangle's), in
/// `[0, 1]`; their plain mean when they have no area, 0 when there are none.
pub fn area_weighted_roughness(polygons: &[Polygon]) -> f64 {
    let (mut weighted, mut area, mut plain) = (0.0, 0.0, 0.0);
    for p in polygons {
        let a = p.area();
        weighted += a * p.roughness;
        area += a;
        plain += p.roughness;
    }
    let mean = if area > 0.0 {
        weighted / area
    } else if polygons.is_empty() {
        0.0
    } else {
        plain / polygons.len() as f64
    };
    if mean.is_finite() { mean.clamp(0.0, 1.0) } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::DVec3;
    use ppr_level::{RoughnessMap, Wrap};

    use super::*;
    use crate::generated_levels::level_of;

    fn textured(green: Vec<u8>, width: u32, uvs: [[f32; 2]; 3], factor: f64) -> Level {
        let mut level = level_of("t", &[[DVec3::ZERO, DVec3::Z, DVec3::X]]);
        let height = green.len() as u32 / width;
        level.materials[0].roughness = factor;
        level.materials[0].roughness_map =
            Some(Arc::new(RoughnessMap { name: "r".into(), width, height, green, wrap: [Wrap::Repeat; 2] }));
        level.uvs = vec![uvs];
        level
    }

    #[test]
    fn a_triangle_takes_the_mean_of_the_texels_it_covers() {
        // Left half 0, right half 255: the lower-left triangle covers 3/4 of the left half.
        let stripes: Vec<u8> = (0..64 * 64).map(|k| if k % 64 < 32 { 0 } else { 255 }).collect();
        let lower_left = [[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]];
        let r = triangle_roughness(&textured(stripes.clone(), 64, lower_left, 1.0), 0);
        assert!((r - 0.25).abs() < 0.02, "{r}");
        // Only the left half: 0, times any factor; only the right half: the factor.
        let left = [[0.0, 0.0], [0.0, 1.0], [0.4, 0.0]];
        assert_eq!(triangle_roughness(&textured(stripes.clone(), 64, left, 0.8), 0), 0.0);
        let right = [[0.6, 0.0], [0.6, 1.0], [0.99, 0.0]];
        assert_eq!(triangle_roughness(&textured(stripes.clone(), 64, right, 0.8), 0), 0.8);
        // Tiling (UVs over [0, 8]) reads the same mean, with a bounded number of reads.
        let tiled = [[0.0, 0.0], [0.0, 8.0], [8.0, 0.0]];
        let r = triangle_roughness(&textured(stripes, 64, tiled, 1.0), 0);
        assert!((r - 0.5).abs() < 0.05, "{r}");
        // Without a map or UVs, the factor.
        let mut plain = level_of("t", &[[DVec3::ZERO, DVec3::Z, DVec3::X]]);
        plain.materials[0].roughness = 0.3;
        assert_eq!(triangle_roughness(&plain, 0), 0.3);
    }

    #[test]
    fn polygons_are_weighted_by_area() {
        let square = |x: f64, side: f64, roughness: f64| Polygon {
            flat: vec![
                DVec2::new(x, 0.0),
                DVec2::new(x + side, 0.0),
                DVec2::new(x + side, side),
                DVec2::new(x, side),
            ],
            spatial: vec![DVec3::ZERO; 4],
            roughness,
        };
        let r = area_weighted_roughness(&[square(0.0, 1.0, 0.0), square(1.0, 3f64.sqrt(), 0.4)]);
        assert!((r - 0.3).abs() < 1e-12, "{r}");
        assert_eq!(area_weighted_roughness(&[]), 0.0);
        let degenerate = area_weighted_roughness(&[square(0.0, 0.0, 0.2), square(0.0, 0.0, 0.4)]);
        assert!((degenerate - 0.3).abs() < 1e-12, "{degenerate}");
    }
}
