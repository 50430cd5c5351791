//! Parallel groups: reflectors whose normals agree within the angle tolerance share a group
//! (same oriented normal; a floor and a ceiling are in different groups).

use glam::DVec3;

/// Group number of each normal, in order of first appearance.
pub fn parallel_groups(normals: &[DVec3], cos_angle: f64) -> Vec<u32> {
    let mut reps: Vec<DVec3> = Vec::new();
    normals
        .iter()
        .map(|n| match reps.iter().position(|r| r.dot(*n) >= cos_angle) {
            Some(g) => g as u32,
            None => {
                reps.push(*n);
                (reps.len() - 1) as u32
            }
        })
        .collect()
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
}
