//! The tolerances edits need (occluder reach, coplanarity), read from the parameters the
//! extractor recorded in the set, or derived from the set's size when it has none.

use glam::DVec3;
use ppr_extract::occluders::occluder_lists;
use ppr_format::ReflectorSet;

use crate::reflector_geometry::CoplanarTolerance;

/// Tolerances of one set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SetTolerances {
    /// A point near the reflectors (precision origin of the occluder BVH).
    pub origin: DVec3,
    /// Distance tolerance, metres (`resolved_distance_tolerance_m`).
    pub distance: f64,
    /// Occluder reach, metres (`resolved_reach_m`).
    pub reach: f64,
    /// Angle tolerance, degrees (`angle_tolerance_deg`).
    pub angle_deg: f64,
}

impl SetTolerances {
    /// The tolerances recorded in `set.extractor.params`, with the extractor's defaults
    /// (relative to the diagonal of the reflectors' bounds) for any that is missing.
    pub fn of(set: &ReflectorSet) -> Self {
        let (lo, hi) = set
            .reflectors
            .iter()
            .flat_map(|r| r.corners())
            .fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), p| {
                (lo.min(p), hi.max(p))
            });
        let (origin, diagonal) =
            if lo.x <= hi.x { ((lo + hi) * 0.5, (hi - lo).length()) } else { (DVec3::ZERO, 1.0) };
        let diagonal = diagonal.max(1e-6);
        let read = |key: &str| {
            set.extractor.params.get(key).and_then(|v| v.as_f64()).filter(|v| v.is_finite() && *v > 0.0)
        };
        Self {
            origin,
            distance: read("resolved_distance_tolerance_m").unwrap_or(5e-4 * diagonal),
            reach: read("resolved_reach_m").unwrap_or(0.25 * diagonal),
            angle_deg: read("angle_tolerance_deg").unwrap_or(1.0),
        }
    }

    /// What merging accepts as one plane.
    pub fn coplanar(&self) -> CoplanarTolerance {
        CoplanarTolerance { cos_angle: self.angle_deg.to_radians().cos(), distance: 2.0 * self.distance }
    }

    /// Recomputes every occluder list of `set` (the extractor's rule and BVH).
    pub fn recompute_occluders(&self, set: &mut ReflectorSet) {
        let lists = occluder_lists(&set.reflectors, self.origin, self.distance, self.reach);
        for (r, list) in set.reflectors.iter_mut().zip(lists) {
            r.occluders = list;
        }
    }
}

/// `count` ids unused in `set`, above the largest one in use (31-bit like the extractor's).
pub fn fresh_ids(set: &ReflectorSet, count: usize) -> Vec<u32> {
    let used: std::collections::BTreeSet<u32> = set.reflectors.iter().map(|r| r.id).collect();
    let mut next = set.next_id() & 0x7FFF_FFFF;
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        if !used.contains(&next) && !out.contains(&next) {
            out.push(next);
        }
        next = (next + 1) & 0x7FFF_FFFF;
    }
    out
}
