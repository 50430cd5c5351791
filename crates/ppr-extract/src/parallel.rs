//! Parallel groups: reflectors whose normals agree within the angle tolerance share a group
//! (same oriented normal; a floor and a ceiling are in different groups). The grouping is
//! `ppr_format`'s, which also holds the invariant a loaded set must meet.

use glam::DVec3;

pub use ppr_format::parallel_groups;

/// The cosine the extractor groups with: its angle tolerance, but at most half of
/// [`ppr_format::PARALLEL_GROUP_MAX_ANGLE_DEG`], so that the set it writes loads.
pub fn grouping_cos(cos_angle: f64) -> f64 {
    cos_angle.max((0.5 * ppr_format::PARALLEL_GROUP_MAX_ANGLE_DEG).to_radians().cos())
}

/// Groups of `normals` for an extraction with the angle tolerance `cos_angle`.
pub fn extraction_groups(normals: &[DVec3], cos_angle: f64) -> Vec<u32> {
    parallel_groups(normals, grouping_cos(cos_angle))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_by_oriented_normal() {
        let cos = 1f64.to_radians().cos();
        let tilted = DVec3::new(0.001, 1.0, 0.0).normalize();
        let groups = parallel_groups(&[DVec3::Y, DVec3::X, tilted, DVec3::NEG_Y, DVec3::X], cos);
        assert_eq!(groups, vec![0, 1, 0, 2, 1]);
    }

    #[test]
    fn a_wide_angle_tolerance_still_groups_only_what_loads() {
        // 20° apart: one plane for a 30° clustering tolerance, but not one parallel group.
        let tilted = DVec3::new(20f64.to_radians().sin(), 20f64.to_radians().cos(), 0.0);
        let groups = extraction_groups(&[DVec3::Y, tilted], 30f64.to_radians().cos());
        assert_eq!(groups, vec![0, 1]);
        assert_eq!(extraction_groups(&[DVec3::Y, tilted], 1f64.to_radians().cos()), vec![0, 1]);
    }
}
