//! The level's bounds (the local origin geometry is processed around) and the parameters'
//! lengths as the pipeline uses them.

use glam::DVec3;

use crate::{ExtractParams, Level};

/// Where a level is and the absolute lengths extraction works with. Only `center` and
/// `diagonal` depend on the level, and only for floating-point precision (the local
/// origin, the smallest length that is not rounding noise); tolerances are the
/// parameters' physical lengths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneScale {
    /// Centre of the level's bounds: the local origin geometry is processed around.
    pub center: DVec3,
    /// Bounding-box diagonal, metres (1 for an empty or single-point level).
    pub diagonal: f64,
    /// Largest vertex distance from its plane, metres.
    pub distance_tolerance: f64,
    /// Gap bridged between triangles of one region, metres.
    pub gap: f64,
    /// Cosine of the angle tolerance.
    pub cos_angle: f64,
    /// Triangles with a longest edge below this skip the angle test, metres.
    pub small_triangle: f64,
    /// Smallest reflective area kept, square metres.
    pub min_area: f64,
    /// Occluder reach, metres (infinite: no reach).
    pub reach: f64,
}

impl SceneScale {
    /// The scale of `level` under `params`.
    pub fn new(level: &Level, params: &ExtractParams) -> Self {
        let (center, diagonal) = match level.bounds() {
            Some((lo, hi)) => ((lo + hi) * 0.5, (hi - lo).length()),
            None => (DVec3::ZERO, 1.0),
        };
        let diagonal = if diagonal > 0.0 && diagonal.is_finite() { diagonal } else { 1.0 };
        Self {
            center,
            diagonal,
            distance_tolerance: params.distance_tolerance_m,
            gap: params.gap_tolerance_m,
            cos_angle: params.angle_tolerance_deg.to_radians().cos(),
            small_triangle: params.small_triangle_factor * params.distance_tolerance_m,
            min_area: params.min_area_m2,
            reach: params.reach_m.unwrap_or(f64::INFINITY),
        }
    }
}
