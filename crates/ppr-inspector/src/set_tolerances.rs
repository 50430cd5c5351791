//! The tolerances edits need (occluder reach, coplanarity), read from the parameters the
//! extractor recorded in the set, or derived from the set's size when it has none.

use glam::DVec3;
use ppr_extract::ExtractParams;
use ppr_extract::occluders::{OccluderRule, ranked_occluder_lists};
use ppr_format::ReflectorSet;

use crate::reflector_geometry::CoplanarTolerance;

/// Tolerances of one set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SetTolerances {
    /// A point near the reflectors (precision origin of the occluder BVH).
    pub origin: DVec3,
    /// Distance tolerance, metres (`distance_tolerance_m`).
    pub distance: f64,
    /// Occluder reach, metres (`reach_m`; infinite when the set has none).
    pub reach: f64,
    /// Most occluders per list (`max_occluders`).
    pub max_occluders: usize,
    /// Angle tolerance, degrees (`angle_tolerance_deg`).
    pub angle_deg: f64,
}

impl SetTolerances {
    /// The tolerances recorded in `set.extractor.params` (older records' names too, see
    /// `ExtractParams::from_record`), with the extractor's defaults for any that is missing.
    pub fn of(set: &ReflectorSet) -> Self {
        let (lo, hi) = set
            .reflectors
            .iter()
            .flat_map(|r| r.corners())
            .fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), p| {
                (lo.min(p), hi.max(p))
            });
        let origin = if lo.x <= hi.x { (lo + hi) * 0.5 } else { DVec3::ZERO };
        let params = ExtractParams::from_record(&set.extractor.params);
        Self {
            origin,
            distance: params.distance_tolerance_m,
            reach: params.reach_m.unwrap_or(f64::INFINITY),
            max_occluders: params.max_occluders,
            angle_deg: params.angle_tolerance_deg,
        }
    }

    /// What merging accepts as one plane.
    pub fn coplanar(&self) -> CoplanarTolerance {
        CoplanarTolerance { cos_angle: self.angle_deg.to_radians().cos(), distance: 2.0 * self.distance }
    }

    /// Recomputes every occluder list of `set` (the extractor's rule and BVH).
    pub fn recompute_occluders(&self, set: &mut ReflectorSet) {
        let rule =
            OccluderRule { epsilon: self.distance, reach: self.reach, max_per_list: self.max_occluders };
        let lists = ranked_occluder_lists(&set.reflectors, self.origin, &rule);
        for (r, list) in set.reflectors.iter_mut().zip(lists.lists) {
            r.occluders = list;
        }
    }
}

pub use ppr_extract::manual_edits::fresh_ids;
