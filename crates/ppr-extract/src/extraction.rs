//! What extraction returns: the reflector set plus what the summary and the inspector need.

use std::time::Duration;

use glam::DVec3;
use ppr_format::ReflectorSet;

/// The stages of extraction, in order (`Load` and `Write` are timed by the caller).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Stage {
    /// Reading and flattening the glTF file.
    Load,
    /// Picking candidate triangles.
    Select,
    /// Welding, connectivity and growing coplanar regions.
    Cluster,
    /// Plane fit per region and projection (reported together with `Fit`'s rectangles).
    Regions,
    /// Rectangles and splits.
    Fit,
    /// Parallel groups, ids and occluder lists.
    Occluders,
    /// Writing the file.
    Write,
}

impl Stage {
    /// Every stage, in order.
    pub const ALL: [Stage; 7] = [
        Stage::Load,
        Stage::Select,
        Stage::Cluster,
        Stage::Regions,
        Stage::Fit,
        Stage::Occluders,
        Stage::Write,
    ];

    /// Lower-case name for tables.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Load => "load",
            Stage::Select => "select",
            Stage::Cluster => "cluster",
            Stage::Regions => "regions",
            Stage::Fit => "fit",
            Stage::Occluders => "occluders",
            Stage::Write => "write",
        }
    }
}

/// Something extraction skipped or decided that is worth telling, not an error.
#[derive(Clone, Debug, PartialEq)]
pub enum Warning {
    /// Degenerate (zero-area) triangles skipped.
    DegenerateTriangles(usize),
    /// Duplicate triangles (same corners) counted once.
    DuplicateTriangles(usize),
    /// Regions below the minimum area dropped.
    SmallRegions {
        /// How many.
        count: usize,
        /// The minimum area, square metres.
        min_area: f64,
    },
    /// Non-convex regions split into several rectangles: the trade made.
    Splits {
        /// Regions split.
        regions: usize,
        /// Rectangles added.
        extra_shapes: usize,
        /// Their rectangle area before, square metres.
        area_before: f64,
        /// ... and after.
        area_after: f64,
    },
    /// Near-planar regions merged into one plane, with the reflection error it causes.
    NearPlanarMerge {
        /// The merge (its `origin` in world coordinates).
        report: crate::near_planar::MergeReport,
    },
    /// More merges than are listed one by one.
    MoreNearPlanarMerges(usize),
    /// What the density budget left out.
    Budget {
        /// The budget: rectangles per cube, and the cube's edge in metres.
        max_per_cube: usize,
        /// Cube edge, metres.
        cube_m: f64,
        /// What it did.
        report: crate::budget::BudgetReport,
    },
    /// Occluder lists that reached the cap: they keep the occluders that look largest from
    /// their reflector.
    OccluderListsCapped {
        /// How many lists.
        lists: usize,
        /// The cap.
        cap: usize,
    },
    /// No triangle was a candidate (try `--all-planar`).
    NoCandidates,
    /// A note from the loader.
    Loader(String),
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Warning::DegenerateTriangles(n) => write!(f, "degenerate triangles skipped: {n}"),
            Warning::DuplicateTriangles(n) => write!(f, "duplicate triangles counted once: {n}"),
            Warning::SmallRegions { count, min_area } => {
                write!(f, "regions smaller than {min_area:.3e} m² dropped: {count}")
            }
            Warning::Splits { regions, extra_shapes, area_before, area_after } => write!(
                f,
                "split {regions} non-convex regions into {extra_shapes} more rectangles: rectangle area {area_before:.3} → {area_after:.3} m² ({:.1}% less)",
                100.0 * (1.0 - area_after / area_before.max(f64::MIN_POSITIVE))
            ),
            Warning::NearPlanarMerge { report: m } => write!(
                f,
                "near-planar: {} regions at ({:.2}, {:.2}, {:.2}) merged into one plane: planes ≤ {:.2}° off it, vertices ≤ {:.1} mm from it; reflection error ≤ {:.1} mm at 1 m",
                m.regions,
                m.origin.x,
                m.origin.y,
                m.origin.z,
                m.angle_deg,
                m.offset_m * 1e3,
                m.error_m * 1e3
            ),
            Warning::MoreNearPlanarMerges(n) => write!(f, "near-planar: {n} more merges (not listed)"),
            Warning::Budget { max_per_cube, cube_m, report } => write!(
                f,
                "density budget ({max_per_cube} rectangles per {cube_m} m cube, {} cubes full): dropped {} regions ({:.3} m² of reflective area, the least per shape), refused {} splits (they would have saved {:.3} m² of rectangle area)",
                report.full_cells,
                report.regions_dropped,
                report.area_dropped,
                report.splits_refused,
                report.saving_refused
            ),
            Warning::OccluderListsCapped { lists, cap } => write!(
                f,
                "occluder lists at the cap of {cap}: {lists} (they keep the occluders that look largest from their reflector)"
            ),
            Warning::NoCandidates => {
                f.write_str("no candidate triangles (levels without meaningful materials need --all-planar)")
            }
            Warning::Loader(s) => f.write_str(s),
        }
    }
}

/// Counts for the summary.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ExtractionStats {
    /// Triangles in the level.
    pub triangles: usize,
    /// Candidate triangles.
    pub candidates: usize,
    /// Connected planar regions found (before the area filter).
    pub regions: usize,
    /// Regions kept.
    pub regions_kept: usize,
    /// Parallel groups.
    pub parallel_groups: usize,
    /// Sum of the occluder list lengths.
    pub occluder_pairs: usize,
    /// The level's diagonal, metres.
    pub diagonal: f64,
}

/// The result of [`crate::extract`].
#[derive(Clone, Debug)]
pub struct Extraction {
    /// The reflectors (valid: ids unique, occluders in range).
    pub set: ReflectorSet,
    /// Per reflector (same order), the world-space vertices of the region part it encloses.
    pub regions: Vec<Vec<DVec3>>,
    /// What was skipped or traded.
    pub warnings: Vec<Warning>,
    /// Time per stage run by `extract` (select .. occluders).
    pub timings: Vec<(Stage, Duration)>,
    /// Counts.
    pub stats: ExtractionStats,
}
