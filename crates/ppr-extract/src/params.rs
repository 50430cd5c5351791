//! Extraction parameters: a documented struct with presets.

use std::collections::BTreeMap;

/// Which triangles may become reflectors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CandidateRule {
    /// Material driven (see [`crate::select`] for the rule); `extras.ppr` overrides it.
    Materials,
    /// Every triangle is a candidate (for levels without meaningful materials);
    /// `extras.ppr.reflector = false` still vetoes.
    AllPlanar,
}

/// How extraction chooses and fits reflectors. Lengths marked *relative* are fractions of
/// the level's bounding-box diagonal, so the same parameters work at any scale and any
/// distance from the origin.
#[derive(Clone, Debug, PartialEq)]
pub struct ExtractParams {
    /// Which triangles are candidates.
    pub candidates: CandidateRule,
    /// Material rule: roughness at most this is glossy enough (usable: 0.1..0.5).
    pub max_roughness: f64,
    /// Material rule: metallic at least this ...
    pub min_metallic: f64,
    /// ... with roughness at most this is a reflector too.
    pub metallic_max_roughness: f64,
    /// Material rule: lower-case substrings of material, mesh or node names that make a
    /// candidate whatever the factors say.
    pub name_patterns: Vec<String>,
    /// Lower-case substrings of material, mesh or node names that make the kind `water`.
    pub water_patterns: Vec<String>,
    /// Lower-case substrings of names that make the kind `transparent` (glass modelled
    /// without `KHR_materials_transmission`).
    pub transparent_patterns: Vec<String>,
    /// Largest angle between a triangle's normal and its plane, degrees (usable: 0.1..5).
    /// Triangles smaller than [`Self::small_triangle_factor`] distance tolerances are
    /// judged by distance only, so noisy tessellation still merges.
    pub angle_tolerance_deg: f64,
    /// Largest distance of a vertex from its plane, *relative* (usable: 1e-5..1e-2).
    pub distance_tolerance: f64,
    /// Triangles whose longest edge is below this many distance tolerances skip the angle test.
    pub small_triangle_factor: f64,
    /// Gap bridged when connecting triangles into regions (T-junctions, welds), *relative*.
    pub gap_tolerance: f64,
    /// Smallest reflective area kept, as a fraction of the diagonal squared.
    pub min_area_relative: f64,
    /// Smallest reflective area kept in square metres; overrides `min_area_relative`.
    pub min_area_m2: Option<f64>,
    /// A split of a non-convex region is kept when every extra shape saves at least this
    /// fraction of the parent rectangle's area (usable: 0.02..0.5; 1 disables splitting).
    pub split_min_gain: f64,
    /// Most rectangles one region may be split into.
    pub max_shapes_per_region: usize,
    /// Cells of the occupancy grid a region is rasterised into when looking for holes.
    pub split_grid_cells: usize,
    /// How far in front of a reflector an occluder is looked for, *relative*.
    pub reach: f64,
    /// The same in metres; overrides `reach`.
    pub reach_m: Option<f64>,
}

impl Default for ExtractParams {
    /// Material-driven selection with tolerances that suit hand-made levels.
    fn default() -> Self {
        Self {
            candidates: CandidateRule::Materials,
            max_roughness: 0.3,
            min_metallic: 0.8,
            metallic_max_roughness: 0.5,
            name_patterns: ["mirror", "glass", "water", "puddle", "chrome", "polished"]
                .map(String::from)
                .to_vec(),
            water_patterns: vec!["water".into()],
            transparent_patterns: vec!["glass".into(), "window".into()],
            angle_tolerance_deg: 1.0,
            distance_tolerance: 5e-4,
            small_triangle_factor: 20.0,
            gap_tolerance: 5e-4,
            min_area_relative: 1e-4,
            min_area_m2: None,
            split_min_gain: 0.1,
            max_shapes_per_region: 8,
            split_grid_cells: 4096,
            reach: 0.25,
            reach_m: None,
        }
    }
}

impl ExtractParams {
    /// Every planar area is a candidate (levels with one material for everything).
    pub fn all_planar() -> Self {
        Self { candidates: CandidateRule::AllPlanar, ..Self::default() }
    }

    /// One rectangle per region: no splitting of non-convex regions.
    pub fn no_split() -> Self {
        Self { split_min_gain: 1.0, max_shapes_per_region: 1, ..Self::default() }
    }

    /// Every preset, for tests and benchmarks that loop over them.
    pub fn presets() -> Vec<(&'static str, Self)> {
        vec![("default", Self::default()), ("all_planar", Self::all_planar()), ("no_split", Self::no_split())]
    }

    /// Checks the ranges stated on each field.
    ///
    /// # Errors
    /// A message naming the first field out of range.
    pub fn validate(&self) -> Result<(), String> {
        let positive = [
            ("angle_tolerance_deg", self.angle_tolerance_deg),
            ("distance_tolerance", self.distance_tolerance),
            ("gap_tolerance", self.gap_tolerance),
            ("reach", self.reach),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!("{name} must be finite and positive, not {v}"));
            }
        }
        if !(self.angle_tolerance_deg < 90.0) {
            return Err(format!("angle_tolerance_deg must be below 90, not {}", self.angle_tolerance_deg));
        }
        for (name, v) in [
            ("min_area_relative", Some(self.min_area_relative)),
            ("min_area_m2", self.min_area_m2),
            ("reach_m", self.reach_m),
        ] {
            if let Some(v) = v
                && !(v.is_finite() && v >= 0.0)
            {
                return Err(format!("{name} must be finite and not negative, not {v}"));
            }
        }
        if !(self.split_min_gain.is_finite() && self.split_min_gain > 0.0) {
            return Err(format!("split_min_gain must be positive, not {}", self.split_min_gain));
        }
        if self.max_shapes_per_region == 0 {
            return Err("max_shapes_per_region must be at least 1".into());
        }
        if !(16..=1 << 20).contains(&self.split_grid_cells) {
            return Err(format!("split_grid_cells must be in 16..=1048576, not {}", self.split_grid_cells));
        }
        Ok(())
    }

    /// The parameters as recorded in the reflector set (`extractor.params`).
    pub fn to_record(&self, scale: &crate::SceneScale) -> BTreeMap<String, serde_json::Value> {
        use serde_json::json;
        let mut m = BTreeMap::new();
        m.insert(
            "candidates".into(),
            json!(match self.candidates {
                CandidateRule::Materials => "materials",
                CandidateRule::AllPlanar => "all-planar",
            }),
        );
        m.insert("max_roughness".into(), json!(self.max_roughness));
        m.insert("min_metallic".into(), json!(self.min_metallic));
        m.insert("metallic_max_roughness".into(), json!(self.metallic_max_roughness));
        m.insert("name_patterns".into(), json!(self.name_patterns));
        m.insert("water_patterns".into(), json!(self.water_patterns));
        m.insert("transparent_patterns".into(), json!(self.transparent_patterns));
        m.insert("angle_tolerance_deg".into(), json!(self.angle_tolerance_deg));
        m.insert("distance_tolerance".into(), json!(self.distance_tolerance));
        m.insert("small_triangle_factor".into(), json!(self.small_triangle_factor));
        m.insert("gap_tolerance".into(), json!(self.gap_tolerance));
        m.insert("min_area_relative".into(), json!(self.min_area_relative));
        m.insert("min_area_m2".into(), json!(self.min_area_m2));
        m.insert("split_min_gain".into(), json!(self.split_min_gain));
        m.insert("max_shapes_per_region".into(), json!(self.max_shapes_per_region));
        m.insert("split_grid_cells".into(), json!(self.split_grid_cells));
        m.insert("reach".into(), json!(self.reach));
        m.insert("reach_m".into(), json!(self.reach_m));
        m.insert("scene_diagonal_m".into(), json!(scale.diagonal));
        m.insert("resolved_distance_tolerance_m".into(), json!(scale.distance_tolerance));
        m.insert("resolved_min_area_m2".into(), json!(scale.min_area));
        m.insert("resolved_reach_m".into(), json!(scale.reach));
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_valid_and_bad_values_are_named() {
        for (name, p) in ExtractParams::presets() {
            assert_eq!(p.validate(), Ok(()), "{name}");
        }
        let p = ExtractParams { distance_tolerance: -1.0, ..ExtractParams::default() };
        assert!(p.validate().unwrap_err().contains("distance_tolerance"));
        let p = ExtractParams { angle_tolerance_deg: f64::NAN, ..ExtractParams::default() };
        assert!(p.validate().unwrap_err().contains("angle_tolerance_deg"));
        let p = ExtractParams { max_shapes_per_region: 0, ..ExtractParams::default() };
        assert!(p.validate().unwrap_err().contains("max_shapes_per_region"));
    }
}
