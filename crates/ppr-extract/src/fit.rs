//! Fitting each planar region with rectangles: the region's own plane (area-weighted fit,
//! reflecting side by area-weighted majority), its triangles as polygons in that plane,
//! the minimum-area rectangle, the split of non-convex regions, and the density budget
//! that decides which regions and splits are kept ([`crate::budget`]).

use std::collections::{BTreeMap, HashSet};
use std::hash::BuildHasherDefault;

use ppr_format::ReflectorKind;

use crate::budget::{BudgetReport, BudgetRule, RegionOffer, apply_budget};
use crate::cluster::{Connectivity, GrownRegion};
use crate::int_hash::IntHasher;
use crate::level::Level;
use crate::parallel_map::{map_ranges, map_slice_mut};
use crate::plane::Plane;
use crate::polygon::Polygon;
use crate::rect_fit::Rect2;
use crate::roughness::triangle_roughness;
use crate::select::Candidate;
use crate::split::{Piece, SplitSettings, SplitStep, split_region_steps};
use crate::{ExtractParams, SceneScale};

/// One rectangle fitted to (part of) a region, in local coordinates.
#[derive(Clone, Debug)]
pub struct FittedShape {
    /// Reflector kind.
    pub kind: ReflectorKind,
    /// The region's plane (local coordinates).
    pub plane: Plane,
    /// The rectangle in the plane's frame.
    pub rect: Rect2,
    /// Reflective area enclosed, square metres.
    pub area: f64,
    /// The polygons enclosed (their `spatial` vertices are the region's vertices).
    pub polygons: Vec<Polygon>,
    /// Names of the nodes the triangles came from (sorted).
    pub nodes: Vec<String>,
    /// Names of their materials (sorted).
    pub materials: Vec<String>,
    /// The node and material with the most area: used for names and ids.
    pub primary: (String, String),
    /// Part number and part count when the region was split (1-based), else (1, 1).
    pub part: (usize, usize),
}

/// What fitting did, for the summary.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FitStats {
    /// Regions fitted (kept).
    pub regions: usize,
    /// Regions dropped for an area below the minimum.
    pub small_regions_dropped: usize,
    /// Duplicate triangles (same welded corners) counted once.
    pub duplicate_triangles: usize,
    /// Regions split into several rectangles.
    pub regions_split: usize,
    /// Extra rectangles those splits added.
    pub shapes_added_by_splits: usize,
    /// Rectangle area of the split regions before splitting, square metres.
    pub split_area_before: f64,
    /// ... and after, square metres.
    pub split_area_after: f64,
    /// What the density budget left out.
    pub budget: BudgetReport,
}

/// A region ready for fitting: its plane and its polygons (duplicates removed).
#[derive(Clone, Debug)]
pub struct PreparedRegion {
    /// Reflector kind.
    pub kind: ReflectorKind,
    /// The region's plane (local coordinates).
    pub plane: Plane,
    /// Its triangles as polygons in the plane.
    pub polygons: Vec<Polygon>,
    /// Names of the nodes the triangles came from (sorted).
    pub nodes: Vec<String>,
    /// Names of their materials (sorted).
    pub materials: Vec<String>,
    /// The node and material with the most area.
    pub primary: (String, String),
}

/// Plane fit and projection of every region large enough to keep.
pub fn prepare_regions(
    level: &Level,
    candidates: &[Candidate],
    regions: &[GrownRegion],
    conn: &Connectivity,
    scale: &SceneScale,
    stats: &mut FitStats,
) -> Vec<PreparedRegion> {
    let mut out = Vec::new();
    // Welded corner triples already met in the region (only membership matters: any hasher
    // gives the same answer).
    let mut seen: HashSet<[u32; 3], BuildHasherDefault<IntHasher>> = HashSet::default();
    for region in regions {
        // Quick reject on raw area before any work.
        let raw_area: f64 = region.members.iter().map(|&m| candidates[m as usize].area).sum();
        if raw_area < scale.min_area {
            stats.small_regions_dropped += 1;
            continue;
        }
        let Some(plane) = region.moments.fit() else { continue };
        seen.clear();
        let mut polygons = Vec::with_capacity(region.members.len());
        let mut source_area: BTreeMap<u32, f64> = BTreeMap::new();
        let mut last_source = (u32::MAX, 0.0);
        for &m in &region.members {
            let c = &candidates[m as usize];
            let mut key = conn.welded[m as usize];
            key.sort_unstable();
            if !seen.insert(key) {
                stats.duplicate_triangles += 1;
                continue;
            }
            // Runs of one source are summed before they reach the map.
            let source = level.triangles[c.triangle as usize].source;
            if source != last_source.0 {
                if last_source.0 != u32::MAX {
                    *source_area.entry(last_source.0).or_default() += last_source.1;
                }
                last_source = (source, 0.0);
            }
            last_source.1 += c.area;
            polygons.push(Polygon {
                flat: c.positions.iter().map(|&p| plane.project(p)).collect(),
                spatial: c.positions.to_vec(),
                roughness: triangle_roughness(level, c.triangle as usize),
            });
        }
        if last_source.0 != u32::MAX {
            *source_area.entry(last_source.0).or_default() += last_source.1;
        }
        let mut node_area: BTreeMap<&str, f64> = BTreeMap::new();
        let mut material_area: BTreeMap<&str, f64> = BTreeMap::new();
        for (&source, &area) in &source_area {
            let source = &level.sources[source as usize];
            *node_area.entry(&source.node).or_default() += area;
            *material_area.entry(&level.materials[source.material as usize].name).or_default() += area;
        }
        let heaviest = |m: &BTreeMap<&str, f64>| {
            m.iter()
                .max_by(|a, b| a.1.total_cmp(b.1).then(b.0.cmp(a.0)))
                .map(|(k, _)| (*k).to_owned())
                .unwrap_or_default()
        };
        out.push(PreparedRegion {
            kind: region.kind,
            plane,
            primary: (heaviest(&node_area), heaviest(&material_area)),
            nodes: node_area.keys().map(|s| (*s).to_owned()).collect(),
            materials: material_area.keys().map(|s| (*s).to_owned()).collect(),
            polygons,
        });
    }
    out
}

/// One region fitted with every split that pays.
struct FittedRegion {
    /// The region's single rectangle's area, m².
    rect_area: f64,
    /// World position of its centre.
    center: glam::DVec3,
    /// Reflective area, m².
    area: f64,
    pieces: Vec<Piece>,
    steps: Vec<SplitStep>,
}

/// The region with every split that pays, or `None` when it has no vertex or less area
/// than `min_area`. Takes the region's polygons, and gives them back when it was split
/// (the budget may replay fewer splits from them).
fn fit_region(
    region: &mut PreparedRegion,
    settings: &SplitSettings,
    scale: &SceneScale,
) -> Option<FittedRegion> {
    let piece = Piece::new(std::mem::take(&mut region.polygons))?;
    if piece.area < scale.min_area {
        return None;
    }
    let (rect_area, area) = (piece.rect.area(), piece.area);
    let center = scale.center + region.plane.lift(piece.rect.center);
    let originals = (piece.waste() >= settings.min_gain * rect_area).then(|| piece.polygons.clone());
    let (pieces, steps) = split_region_steps(piece, settings, usize::MAX);
    if !steps.is_empty() {
        region.polygons = originals.unwrap_or_default();
    }
    Some(FittedRegion { rect_area, center, area, pieces, steps })
}

/// Fits every prepared region with one or more rectangles under the density budget, on up
/// to `threads` threads (the result does not depend on the count); `progress(f)` gets the
/// fraction done.
pub fn fit_shapes(
    regions: Vec<PreparedRegion>,
    params: &ExtractParams,
    scale: &SceneScale,
    threads: usize,
    stats: &mut FitStats,
    progress: &mut dyn FnMut(f32),
) -> Vec<FittedShape> {
    let settings = SplitSettings {
        min_gain: params.split_min_gain,
        max_pieces: params.max_shapes_per_region,
        grid_cells: params.split_grid_cells,
    };
    // Every region with every split that pays, in batches for progress.
    let batch = 256 * threads.max(1);
    let mut regions = regions;
    let mut fitted: Vec<Option<FittedRegion>> = Vec::with_capacity(regions.len());
    let total = regions.len();
    for (k, chunk) in regions.chunks_mut(batch).enumerate() {
        progress(0.9 * (k * batch) as f32 / total.max(1) as f32);
        fitted.extend(map_slice_mut(chunk, threads, |region| fit_region(region, &settings, scale)));
    }
    // The budget, then the regions it cut short split again with the steps it kept.
    let kept: Vec<usize> = (0..regions.len()).filter(|&r| fitted[r].is_some()).collect();
    let offers: Vec<RegionOffer> = kept
        .iter()
        .filter_map(|&r| fitted[r].as_ref())
        .map(|f| RegionOffer { center: f.center, area: f.area, steps: f.steps.clone() })
        .collect();
    let rule = BudgetRule { cell_m: params.budget_cube_m, max_per_cell: params.max_shapes_per_cube };
    let (choices, report) = apply_budget(&offers, &rule);
    stats.budget = report;
    let replay: Vec<(usize, usize)> = kept
        .iter()
        .zip(&choices)
        .filter(|(r, c)| c.keep && fitted[**r].as_ref().is_some_and(|f| c.steps < f.steps.len()))
        .map(|(&r, c)| (r, c.steps))
        .collect();
    let replayed = map_ranges(replay.len(), threads, |range| {
        range
            .map(|k| {
                let (r, steps) = replay[k];
                let piece = Piece::new(regions[r].polygons.clone())
                    .map(|p| split_region_steps(p, &settings, steps).0);
                (r, piece.unwrap_or_default())
            })
            .collect()
    });
    for (r, pieces) in replayed {
        if let Some(f) = fitted[r].as_mut() {
            f.pieces = pieces;
        }
    }
    let keep: std::collections::BTreeSet<usize> =
        kept.iter().zip(&choices).filter(|(_, c)| c.keep).map(|(&r, _)| r).collect();
    let mut shapes = Vec::new();
    for (r, (region, outcome)) in regions.into_iter().zip(fitted).enumerate() {
        let Some(f) = outcome else {
            stats.small_regions_dropped += 1;
            continue;
        };
        if !keep.contains(&r) {
            continue;
        }
        stats.regions += 1;
        if f.pieces.len() > 1 {
            stats.regions_split += 1;
            stats.shapes_added_by_splits += f.pieces.len() - 1;
            stats.split_area_before += f.rect_area;
            stats.split_area_after += f.pieces.iter().map(|p| p.rect.area()).sum::<f64>();
        }
        let count = f.pieces.len();
        for (k, p) in f.pieces.into_iter().enumerate() {
            shapes.push(FittedShape {
                kind: region.kind,
                plane: region.plane,
                rect: p.rect,
                area: p.area,
                polygons: p.polygons,
                nodes: region.nodes.clone(),
                materials: region.materials.clone(),
                primary: region.primary.clone(),
                part: (k + 1, count),
            });
        }
    }
    progress(1.0);
    shapes
}
