//! Picking by clicking: the nearest reflector rectangle a ray hits (CPU, every reflector).

use glam::DVec3;
use ppr_format::ReflectorSet;

/// Distance along the ray (origin, unit `dir`) at which it crosses the rectangle of the
/// reflector at `index`, from either side; `None` when it misses.
pub fn hit_distance(set: &ReflectorSet, index: usize, origin: DVec3, dir: DVec3) -> Option<f64> {
    let r = set.reflectors.get(index)?;
    let denom = r.normal.dot(dir);
    if denom.abs() < 1e-12 {
        return None;
    }
    let t = r.normal.dot(r.center - origin) / denom;
    (t > 0.0 && r.contains_projection(origin + dir * t, 0.0)).then_some(t)
}

/// Id of the nearest reflector the ray hits.
pub fn pick(set: &ReflectorSet, origin: DVec3, dir: DVec3) -> Option<u32> {
    (0..set.reflectors.len())
        .filter_map(|i| hit_distance(set, i, origin, dir).map(|t| (t, set.reflectors[i].id)))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, id)| id)
}

#[cfg(test)]
mod tests {
    use glam::DVec2;
    use ppr_format::{Reflector, ReflectorKind};

    use super::*;

    #[test]
    fn nearest_hit_wins_and_misses_are_none() {
        let mut set = ReflectorSet::new("x");
        let floor = |id, y: f64| {
            Reflector::new(
                id,
                "f",
                ReflectorKind::Opaque,
                DVec3::new(0.0, y, 0.0),
                DVec3::Y,
                DVec3::X,
                DVec2::ONE,
            )
        };
        set.reflectors.push(floor(7, 0.0));
        set.reflectors.push(floor(9, 1.0));
        let down = DVec3::NEG_Y;
        assert_eq!(pick(&set, DVec3::new(0.5, 3.0, 0.5), down), Some(9));
        assert_eq!(pick(&set, DVec3::new(0.5, 0.5, 0.5), down), Some(7));
        assert_eq!(pick(&set, DVec3::new(2.5, 3.0, 0.5), down), None);
        assert_eq!(pick(&set, DVec3::new(0.5, 3.0, 0.5), DVec3::X), None);
    }
}
