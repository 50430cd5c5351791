//! The extraction pipeline: selection, clustering, regions, fitting, parallel groups,
//! stable ids and occluder lists, timed stage by stage.

use std::time::{Duration, Instant};

use glam::DVec2;
use ppr_format::{ExtractorInfo, Reflector, ReflectorSet, ReflectorSource, SourceInfo};

use crate::cluster::{Connectivity, grow_regions};
use crate::extraction::{Extraction, ExtractionStats, Stage, Warning};
use crate::fit::{FitStats, FittedShape, fit_shapes, prepare_regions};
use crate::near_planar::{MergeReport, NearPlanarRule, merge_near_planar};
use crate::occluders::{OccluderRule, ranked_occluder_lists_threaded};
use crate::parallel::extraction_groups;
use crate::parallel_map::thread_count;
use crate::params::CandidateRule;
use crate::roughness::area_weighted_roughness;
use crate::select::select;
use crate::stable_id::{IdContent, content_hash, dedupe_ids};
use crate::{ExtractParams, Level, SceneScale};

/// Near-planar merges listed one by one in the warnings (the rest are counted).
const MERGES_LISTED: usize = 20;

/// Extracts the reflector set of `level`. `progress(stage, fraction)` is called at the
/// start (0) and end (1) of each stage and now and then in between.
///
/// Deterministic: the same level and parameters give the same set, byte for byte once
/// written. Extraction never fails on geometry: problems become [`Warning`]s.
///
/// # Panics
/// Never on valid input; `params` should pass [`ExtractParams::validate`] (the CLI checks).
pub fn extract(level: &Level, params: &ExtractParams, progress: &dyn Fn(Stage, f32)) -> Extraction {
    let mut timings = Vec::new();
    let mut clock = StageClock { timings: &mut timings, progress, started: Instant::now() };
    let scale = SceneScale::new(level, params);
    let threads = thread_count(params.threads);
    let mut warnings: Vec<Warning> = level.notes.iter().cloned().map(Warning::Loader).collect();

    clock.start(Stage::Select);
    let selection = select(level, params, &scale);
    clock.finish(Stage::Select);
    if selection.degenerate > 0 {
        warnings.push(Warning::DegenerateTriangles(selection.degenerate));
    }
    if selection.candidates.is_empty() {
        warnings.push(Warning::NoCandidates);
    }

    clock.start(Stage::Cluster);
    let conn = Connectivity::build(&selection.candidates, &scale);
    clock.report(Stage::Cluster, 0.4);
    let grown =
        grow_regions(&selection.candidates, &conn, &scale, &mut |f| progress(Stage::Cluster, 0.4 + 0.5 * f));
    let region_count = grown.len();
    let rule = NearPlanarRule {
        max_angle_deg: params.near_planar_angle_deg,
        max_error_m: params.max_reflection_error_m,
    };
    let (grown, merges) = merge_near_planar(&selection.candidates, grown, &conn, &rule);
    for (k, report) in merges.iter().enumerate() {
        if k == MERGES_LISTED {
            warnings.push(Warning::MoreNearPlanarMerges(merges.len() - MERGES_LISTED));
            break;
        }
        let report = MergeReport { origin: report.origin + scale.center, ..report.clone() };
        warnings.push(Warning::NearPlanarMerge { report });
    }
    clock.finish(Stage::Cluster);

    clock.start(Stage::Regions);
    let mut fit_stats = FitStats::default();
    let prepared = prepare_regions(level, &selection.candidates, &grown, &conn, &scale, &mut fit_stats);
    clock.finish(Stage::Regions);

    clock.start(Stage::Fit);
    let shapes =
        fit_shapes(prepared, params, &scale, threads, &mut fit_stats, &mut |f| progress(Stage::Fit, f));
    clock.finish(Stage::Fit);

    clock.start(Stage::Occluders);
    let (mut set, regions) = build_set(level, params, &scale, shapes);
    let rule = OccluderRule {
        epsilon: scale.distance_tolerance,
        reach: scale.reach,
        max_per_list: params.max_occluders,
    };
    let lists = ranked_occluder_lists_threaded(&set.reflectors, scale.center, &rule, threads);
    if lists.capped > 0 {
        warnings.push(Warning::OccluderListsCapped { lists: lists.capped, cap: params.max_occluders });
    }
    let mut occluder_pairs = 0;
    for (r, list) in set.reflectors.iter_mut().zip(lists.lists) {
        occluder_pairs += list.len();
        r.occluders = list;
    }
    clock.finish(Stage::Occluders);

    if fit_stats.duplicate_triangles > 0 {
        warnings.push(Warning::DuplicateTriangles(fit_stats.duplicate_triangles));
    }
    if fit_stats.small_regions_dropped > 0 {
        warnings
            .push(Warning::SmallRegions { count: fit_stats.small_regions_dropped, min_area: scale.min_area });
    }
    if fit_stats.budget.regions_dropped > 0 || fit_stats.budget.splits_refused > 0 {
        warnings.push(Warning::Budget {
            max_per_cube: params.max_shapes_per_cube,
            cube_m: params.budget_cube_m,
            report: fit_stats.budget,
        });
    }
    if fit_stats.regions_split > 0 {
        warnings.push(Warning::Splits {
            regions: fit_stats.regions_split,
            extra_shapes: fit_stats.shapes_added_by_splits,
            area_before: fit_stats.split_area_before,
            area_after: fit_stats.split_area_after,
        });
    }
    let stats = ExtractionStats {
        triangles: level.triangles.len(),
        candidates: selection.candidates.len(),
        regions: region_count,
        regions_kept: fit_stats.regions,
        parallel_groups: set.reflectors.iter().map(|r| r.parallel_group + 1).max().unwrap_or(0) as usize,
        occluder_pairs,
        diagonal: scale.diagonal,
    };
    Extraction { set, regions, warnings, timings, stats }
}

struct StageClock<'a> {
    timings: &'a mut Vec<(Stage, Duration)>,
    progress: &'a dyn Fn(Stage, f32),
    started: Instant,
}

impl StageClock<'_> {
    fn start(&mut self, stage: Stage) {
        (self.progress)(stage, 0.0);
        self.started = Instant::now();
    }
    fn report(&self, stage: Stage, fraction: f32) {
        (self.progress)(stage, fraction);
    }
    fn finish(&mut self, stage: Stage) {
        self.timings.push((stage, self.started.elapsed()));
        (self.progress)(stage, 1.0);
    }
}

/// World-space reflectors in a deterministic order, with ids, names, groups and sources;
/// and each one's region vertices.
fn build_set(
    level: &Level,
    params: &ExtractParams,
    scale: &SceneScale,
    shapes: Vec<FittedShape>,
) -> (ReflectorSet, Vec<Vec<glam::DVec3>>) {
    let min_half = (1e-12 * scale.diagonal).max(f64::MIN_POSITIVE);
    let mut drafts: Vec<(Reflector, Vec<glam::DVec3>, u32)> = shapes
        .into_iter()
        .map(|s| {
            let normal = s.plane.normal;
            let axis_u = s.plane.lift_direction(s.rect.axis).normalize();
            let axis_v = normal.cross(axis_u).normalize();
            let center = scale.center + s.plane.lift(s.rect.center);
            let half = DVec2::new(s.rect.half.x.max(min_half), s.rect.half.y.max(min_half));
            let rect_area = 4.0 * half.x * half.y;
            let name = if s.part.1 > 1 {
                format!("{} on {} [{}/{}]", s.primary.1, s.primary.0, s.part.0, s.part.1)
            } else {
                format!("{} on {}", s.primary.1, s.primary.0)
            };
            let hash = content_hash(&IdContent {
                kind: s.kind,
                normal,
                center,
                node: &s.primary.0,
                material: &s.primary.1,
            });
            let mut r = Reflector::new(0, name, s.kind, center, normal, axis_u, half);
            // The fit's own in-plane frame, which may be left-handed about the normal.
            r.axis_v = axis_v;
            r.coverage = (s.area / rect_area).clamp(0.0, 1.0);
            // `--all-planar` declares every planar surface a mirror: the level's materials
            // say nothing (one material for everything, often rough), and a roughness
            // from them would leave every reflector to the runtime's rough fallback.
            r.roughness = match params.candidates {
                CandidateRule::AllPlanar => 0.0,
                CandidateRule::Materials => area_weighted_roughness(&s.polygons),
            };
            r.normal_map =
                s.materials.iter().any(|m| level.materials.iter().any(|l| l.normal_map && &l.name == m));
            r.source = ReflectorSource { nodes: s.nodes, materials: s.materials };
            let vertices =
                s.polygons.iter().flat_map(|p| p.spatial.iter().map(|&v| v + scale.center)).collect();
            (r, vertices, hash)
        })
        .collect();
    // Deterministic order: kind, larger first, then content.
    drafts.sort_by(|a, b| {
        (a.0.kind as u8)
            .cmp(&(b.0.kind as u8))
            .then(b.0.area().total_cmp(&a.0.area()))
            .then(a.2.cmp(&b.2))
            .then(
                a.0.center
                    .to_array()
                    .partial_cmp(&b.0.center.to_array())
                    .unwrap_or(std::cmp::Ordering::Equal),
            )
    });
    let ids = dedupe_ids(&drafts.iter().map(|d| d.2).collect::<Vec<_>>());
    let normals: Vec<glam::DVec3> = drafts.iter().map(|d| d.0.normal).collect();
    let groups = extraction_groups(&normals, scale.cos_angle);
    let mut set = ReflectorSet::new(level.path.clone());
    set.source = SourceInfo { path: level.path.clone(), hash: level.hash.clone() };
    set.extractor = ExtractorInfo {
        name: env!("CARGO_PKG_NAME").to_owned(),
        version: env!("CARGO_PKG_VERSION").to_owned(),
        params: params.to_record(scale),
    };
    let mut regions = Vec::with_capacity(drafts.len());
    for ((mut r, vertices, _), (id, group)) in drafts.into_iter().zip(ids.into_iter().zip(groups)) {
        r.id = id;
        r.parallel_group = group;
        set.reflectors.push(r);
        regions.push(vertices);
    }
    (set, regions)
}
