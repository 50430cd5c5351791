//! Extraction parameters: a documented struct with presets, in physical units (metres,
//! square metres, degrees; glTF is metres), so the same room gives the same set however
//! large the level around it is.

use std::collections::BTreeMap;

use serde_json::{Value, json};

/// Which triangles may become reflectors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CandidateRule {
    /// Material driven (see [`crate::select`] for the rule); `extras.ppr` overrides it.
    Materials,
    /// Every triangle is a candidate (for levels without meaningful materials);
    /// `extras.ppr.reflector = false` still vetoes.
    AllPlanar,
}

/// How extraction chooses and fits reflectors. Every length is in metres and every area
/// in square metres (glTF's unit); nothing depends on the size of the level, so a room
/// extracts alike alone or inside a city. For a level modelled in another unit, see
/// [`ExtractParams::in_level_units`].
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
    /// Largest distance of a vertex from its region's plane, metres (usable: 1e-4..0.02).
    pub distance_tolerance_m: f64,
    /// Triangles whose longest edge is below this many distance tolerances skip the angle test.
    pub small_triangle_factor: f64,
    /// Gap bridged when connecting triangles into regions (T-junctions, welds), metres
    /// (usable: 1e-4..0.02).
    pub gap_tolerance_m: f64,
    /// Smallest reflective area kept, square metres (usable: 0..0.25).
    pub min_area_m2: f64,
    /// A split of a non-convex region is kept when every extra shape saves at least this
    /// fraction of the parent rectangle's area (usable: 0.02..0.5; 1 disables splitting).
    pub split_min_gain: f64,
    /// Most rectangles one region may be split into.
    pub max_shapes_per_region: usize,
    /// Cells of the occupancy grid a region is rasterised into when looking for holes.
    pub split_grid_cells: usize,
    /// How far in front of a reflector occluders are looked for, metres; `None` (the
    /// default): anywhere in front of it.
    pub reach_m: Option<f64>,
    /// Most occluders listed per reflector: the ones that look largest from it (area over
    /// squared distance) are kept; the summary reports lists that were cut.
    pub max_occluders: usize,
    /// Touching regions whose planes are less than this apart merge into one plane when
    /// the reflection error stays under [`Self::max_reflection_error_m`], degrees (0: never;
    /// see [`crate::near_planar`]).
    pub near_planar_angle_deg: f64,
    /// Largest reflection error a near-planar merge may cause, metres: how far the image of
    /// a point 1 m in front of the surface moves (usable: 0.01..0.2).
    pub max_reflection_error_m: f64,
    /// Edge of the cubes the density budget counts rectangles in, metres (a world-aligned
    /// grid; see [`crate::budget`]).
    pub budget_cube_m: f64,
    /// Most rectangles per cube: regions and splits are kept by what they buy per shape
    /// (usable: 16..1024).
    pub max_shapes_per_cube: usize,
    /// Worker threads (0: every core). The output does not depend on it; it is not recorded.
    pub threads: usize,
}

/// Default distance tolerance, metres: the plane offset an exporter's rounding and a
/// hand-placed tile leave, and a reflection error of 1 cm at most (`docs/perf/extract.md`).
pub const DEFAULT_DISTANCE_TOLERANCE_M: f64 = 0.005;
/// Default gap bridged between triangles, metres.
pub const DEFAULT_GAP_TOLERANCE_M: f64 = 0.005;
/// Default smallest reflective area, square metres (a 10 × 10 cm tile).
pub const DEFAULT_MIN_AREA_M2: f64 = 0.01;
/// Default cap on one occluder list.
pub const DEFAULT_MAX_OCCLUDERS: usize = 64;
/// Default edge of the budget's cubes, metres (about a room).
pub const DEFAULT_BUDGET_CUBE_M: f64 = 10.0;
/// Default most rectangles per budget cube: a view that sees eight such cubes has at most
/// 1024 shapes, about 1.1 ms at 4K on the H100 with tile culling (`docs/perf/scaling.md`).
pub const DEFAULT_MAX_SHAPES_PER_CUBE: usize = 128;

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
            distance_tolerance_m: DEFAULT_DISTANCE_TOLERANCE_M,
            small_triangle_factor: 20.0,
            gap_tolerance_m: DEFAULT_GAP_TOLERANCE_M,
            min_area_m2: DEFAULT_MIN_AREA_M2,
            split_min_gain: 0.1,
            max_shapes_per_region: 8,
            split_grid_cells: 4096,
            reach_m: None,
            max_occluders: DEFAULT_MAX_OCCLUDERS,
            near_planar_angle_deg: 2.0,
            max_reflection_error_m: 0.08,
            budget_cube_m: DEFAULT_BUDGET_CUBE_M,
            max_shapes_per_cube: DEFAULT_MAX_SHAPES_PER_CUBE,
            threads: 0,
        }
    }
}

impl ExtractParams {
    /// Every planar area is a candidate (levels with one material for everything).
    pub fn all_planar() -> Self {
        Self { candidates: CandidateRule::AllPlanar, ..Self::default() }
    }

    /// No density budget (every region and split that pays is kept).
    pub fn unbudgeted(self) -> Self {
        Self { max_shapes_per_cube: usize::MAX, ..self }
    }

    /// One rectangle per region: no splitting of non-convex regions.
    pub fn no_split() -> Self {
        Self { split_min_gain: 1.0, max_shapes_per_region: 1, ..Self::default() }
    }

    /// Every preset, for tests and benchmarks that loop over them.
    pub fn presets() -> Vec<(&'static str, Self)> {
        vec![("default", Self::default()), ("all_planar", Self::all_planar()), ("no_split", Self::no_split())]
    }

    /// These parameters for a level modelled in units of `metres_per_unit` metres (0.01
    /// for centimetres): every length divided by it, every area by its square, so the
    /// tolerances keep their physical size.
    pub fn in_level_units(mut self, metres_per_unit: f64) -> Self {
        let k = 1.0 / metres_per_unit;
        self.distance_tolerance_m *= k;
        self.gap_tolerance_m *= k;
        self.min_area_m2 *= k * k;
        self.reach_m = self.reach_m.map(|r| r * k);
        self.budget_cube_m *= k;
        self.max_reflection_error_m *= k;
        self
    }

    /// Checks the ranges stated on each field.
    ///
    /// # Errors
    /// A message naming the first field out of range.
    pub fn validate(&self) -> Result<(), String> {
        let positive = [
            ("angle_tolerance_deg", self.angle_tolerance_deg),
            ("distance_tolerance_m", self.distance_tolerance_m),
            ("gap_tolerance_m", self.gap_tolerance_m),
            ("reach_m", self.reach_m.unwrap_or(1.0)),
            ("budget_cube_m", self.budget_cube_m),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!("{name} must be finite and positive, not {v}"));
            }
        }
        if !(self.angle_tolerance_deg < 90.0) {
            return Err(format!("angle_tolerance_deg must be below 90, not {}", self.angle_tolerance_deg));
        }
        for (name, v) in
            [("min_area_m2", self.min_area_m2), ("small_triangle_factor", self.small_triangle_factor)]
        {
            if !(v.is_finite() && v >= 0.0) {
                return Err(format!("{name} must be finite and not negative, not {v}"));
            }
        }
        if !(self.split_min_gain.is_finite() && self.split_min_gain > 0.0) {
            return Err(format!("split_min_gain must be positive, not {}", self.split_min_gain));
        }
        if self.max_shapes_per_region == 0 {
            return Err("max_shapes_per_region must be at least 1".into());
        }
        if self.max_shapes_per_cube == 0 {
            return Err("max_shapes_per_cube must be at least 1".into());
        }
        if self.max_occluders == 0 {
            return Err("max_occluders must be at least 1".into());
        }
        if !(16..=1 << 20).contains(&self.split_grid_cells) {
            return Err(format!("split_grid_cells must be in 16..=1048576, not {}", self.split_grid_cells));
        }
        Ok(())
    }

    /// The parameters as recorded in the reflector set (`extractor.params`), with the
    /// level's diagonal for reference.
    pub fn to_record(&self, scale: &crate::SceneScale) -> BTreeMap<String, Value> {
        let mut m = BTreeMap::new();
        let candidates = match self.candidates {
            CandidateRule::Materials => "materials",
            CandidateRule::AllPlanar => "all-planar",
        };
        m.insert("candidates".into(), json!(candidates));
        m.insert("max_roughness".into(), json!(self.max_roughness));
        m.insert("min_metallic".into(), json!(self.min_metallic));
        m.insert("metallic_max_roughness".into(), json!(self.metallic_max_roughness));
        m.insert("name_patterns".into(), json!(self.name_patterns));
        m.insert("water_patterns".into(), json!(self.water_patterns));
        m.insert("transparent_patterns".into(), json!(self.transparent_patterns));
        m.insert("angle_tolerance_deg".into(), json!(self.angle_tolerance_deg));
        m.insert("distance_tolerance_m".into(), json!(self.distance_tolerance_m));
        m.insert("small_triangle_factor".into(), json!(self.small_triangle_factor));
        m.insert("gap_tolerance_m".into(), json!(self.gap_tolerance_m));
        m.insert("min_area_m2".into(), json!(self.min_area_m2));
        m.insert("split_min_gain".into(), json!(self.split_min_gain));
        m.insert("max_shapes_per_region".into(), json!(self.max_shapes_per_region));
        m.insert("split_grid_cells".into(), json!(self.split_grid_cells));
        m.insert("reach_m".into(), json!(self.reach_m));
        m.insert("max_occluders".into(), json!(self.max_occluders));
        m.insert("near_planar_angle_deg".into(), json!(self.near_planar_angle_deg));
        m.insert("max_reflection_error_m".into(), json!(self.max_reflection_error_m));
        m.insert("budget_cube_m".into(), json!(self.budget_cube_m));
        m.insert("max_shapes_per_cube".into(), json!(self.max_shapes_per_cube));
        m.insert("scene_diagonal_m".into(), json!(scale.diagonal));
        m
    }

    /// The parameters a set's record (`extractor.params`) states, on top of the defaults.
    /// Reads the names written by [`Self::to_record`] and the older ones: the relative
    /// `distance_tolerance`, `gap_tolerance`, `min_area_relative` and `reach` (fractions of
    /// the recorded `scene_diagonal_m`), and `resolved_distance_tolerance_m`,
    /// `resolved_min_area_m2`, `resolved_reach_m` (which win over them). A record without
    /// any reach states one of a quarter of its diagonal only when it is an old record
    /// (it has `reach`); new records without `reach_m` mean no reach.
    pub fn from_record(record: &BTreeMap<String, Value>) -> Self {
        let mut p = Self::default();
        let num = |k: &str| record.get(k).and_then(Value::as_f64).filter(|v| v.is_finite());
        let count = |k: &str| record.get(k).and_then(Value::as_u64).map(|v| v as usize);
        let strings = |k: &str| {
            record
                .get(k)
                .and_then(Value::as_array)
                .map(|a| a.iter().filter_map(|s| s.as_str().map(str::to_owned)).collect::<Vec<String>>())
        };
        let diagonal = num("scene_diagonal_m").filter(|d| *d > 0.0);
        let relative = |k: &str, power: i32| Some(num(k)? * diagonal?.powi(power));
        if let Some(c) = record.get("candidates").and_then(Value::as_str) {
            p.candidates =
                if c == "all-planar" { CandidateRule::AllPlanar } else { CandidateRule::Materials };
        }
        for (key, field) in [
            ("max_roughness", &mut p.max_roughness),
            ("min_metallic", &mut p.min_metallic),
            ("metallic_max_roughness", &mut p.metallic_max_roughness),
            ("angle_tolerance_deg", &mut p.angle_tolerance_deg),
            ("small_triangle_factor", &mut p.small_triangle_factor),
            ("split_min_gain", &mut p.split_min_gain),
            ("budget_cube_m", &mut p.budget_cube_m),
            ("near_planar_angle_deg", &mut p.near_planar_angle_deg),
            ("max_reflection_error_m", &mut p.max_reflection_error_m),
        ] {
            if let Some(v) = num(key) {
                *field = v;
            }
        }
        for (key, field) in [
            ("name_patterns", &mut p.name_patterns),
            ("water_patterns", &mut p.water_patterns),
            ("transparent_patterns", &mut p.transparent_patterns),
        ] {
            if let Some(v) = strings(key) {
                *field = v;
            }
        }
        for (key, field) in [
            ("max_shapes_per_region", &mut p.max_shapes_per_region),
            ("split_grid_cells", &mut p.split_grid_cells),
            ("max_occluders", &mut p.max_occluders),
            ("max_shapes_per_cube", &mut p.max_shapes_per_cube),
        ] {
            if let Some(v) = count(key) {
                *field = v;
            }
        }
        let first = |options: [Option<f64>; 3]| options.into_iter().flatten().next();
        if let Some(v) = first([
            num("distance_tolerance_m"),
            num("resolved_distance_tolerance_m"),
            relative("distance_tolerance", 1),
        ]) {
            p.distance_tolerance_m = v;
        }
        if let Some(v) = first([num("gap_tolerance_m"), None, relative("gap_tolerance", 1)]) {
            p.gap_tolerance_m = v;
        }
        if let Some(v) =
            first([num("min_area_m2"), num("resolved_min_area_m2"), relative("min_area_relative", 2)])
        {
            p.min_area_m2 = v;
        }
        p.reach_m = first([num("reach_m"), num("resolved_reach_m"), relative("reach", 1)]);
        p
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
        let p = ExtractParams { distance_tolerance_m: -1.0, ..ExtractParams::default() };
        assert!(p.validate().unwrap_err().contains("distance_tolerance_m"));
        let p = ExtractParams { angle_tolerance_deg: f64::NAN, ..ExtractParams::default() };
        assert!(p.validate().unwrap_err().contains("angle_tolerance_deg"));
        let p = ExtractParams { max_shapes_per_region: 0, ..ExtractParams::default() };
        assert!(p.validate().unwrap_err().contains("max_shapes_per_region"));
        let p = ExtractParams { reach_m: Some(0.0), ..ExtractParams::default() };
        assert!(p.validate().unwrap_err().contains("reach_m"));
    }

    #[test]
    fn records_round_trip_and_old_names_are_read() {
        let scale = crate::SceneScale {
            center: glam::DVec3::ZERO,
            diagonal: 20.0,
            distance_tolerance: 0.0,
            gap: 0.0,
            cos_angle: 1.0,
            small_triangle: 0.0,
            min_area: 0.0,
            reach: f64::INFINITY,
        };
        let p = ExtractParams { reach_m: Some(3.0), min_area_m2: 0.5, ..ExtractParams::all_planar() };
        assert_eq!(ExtractParams::from_record(&p.to_record(&scale)), p);
        let p = ExtractParams::default();
        assert_eq!(ExtractParams::from_record(&p.to_record(&scale)), p, "no reach stays no reach");
        // A record of the relative parameters (before physical units).
        let old: BTreeMap<String, Value> = [
            ("distance_tolerance", json!(5e-4)),
            ("gap_tolerance", json!(1e-3)),
            ("min_area_relative", json!(1e-4)),
            ("min_area_m2", json!(null)),
            ("reach", json!(0.25)),
            ("reach_m", json!(null)),
            ("scene_diagonal_m", json!(20.0)),
            ("resolved_reach_m", json!(5.0)),
            ("angle_tolerance_deg", json!(2.0)),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_owned(), v))
        .collect();
        let p = ExtractParams::from_record(&old);
        assert!((p.distance_tolerance_m - 0.01).abs() < 1e-12, "{p:?}");
        assert!((p.gap_tolerance_m - 0.02).abs() < 1e-12);
        assert!((p.min_area_m2 - 0.04).abs() < 1e-12);
        assert_eq!(p.reach_m, Some(5.0));
        assert_eq!(p.angle_tolerance_deg, 2.0);
    }

    #[test]
    fn level_units_keep_physical_sizes() {
        let cm = ExtractParams { reach_m: Some(2.0), ..ExtractParams::default() }.in_level_units(0.01);
        assert!((cm.distance_tolerance_m - 100.0 * DEFAULT_DISTANCE_TOLERANCE_M).abs() < 1e-9);
        assert!((cm.min_area_m2 - 1e4 * DEFAULT_MIN_AREA_M2).abs() < 1e-6);
        assert_eq!(cm.reach_m, Some(200.0));
    }
}
