//! Near-planar regions merged into one plane when the reflection error stays small.
//!
//! Region growing refuses a triangle whose normal is more than the angle tolerance off the
//! region's plane, so a wall whose two triangles differ by 1° becomes two triangular
//! regions (and, fitted, a staircase of rectangles). Here, touching regions of the same kind
//! whose oriented planes are less than `near_planar_angle_deg` apart are merged into one
//! plane (an area-weighted fit of both) when the error that plane makes in reflections
//! stays under `max_reflection_error_m`:
//!
//! **error = 2 (δ + L tan θ)**, with δ the largest distance of a vertex from the merged
//! plane, θ the largest angle between a merged region's own plane and the merged plane,
//! and L = [`REFERENCE_DISTANCE_M`] (1 m): how far the reflected image of a point 1 m in
//! front of the surface moves (a plane moved by δ moves the image by 2δ; a plane turned by
//! θ turns reflected rays by 2θ).
//!
//! δ is bounded without visiting vertices again: each group keeps the box of its vertices
//! in its own plane's frame, and the merged plane's largest distance over the corners of
//! both boxes bounds it (a distance to a plane is affine, so its largest value over a box is
//! at a corner). Pairs are tried smallest angle first; each merge is reported with its
//! error ([`MergeReport`]).

use glam::DVec3;

use crate::cluster::{Connectivity, GrownRegion};
use crate::plane::{Plane, PlaneAccumulator};
use crate::select::Candidate;

/// The distance the reflection error is stated at, metres.
pub const REFERENCE_DISTANCE_M: f64 = 1.0;

/// When near-planar regions merge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearPlanarRule {
    /// Largest angle between the two groups' planes, degrees (0: never merge).
    pub max_angle_deg: f64,
    /// Largest reflection error of the merged plane at 1 m, metres.
    pub max_error_m: f64,
}

/// One merged group of regions.
#[derive(Clone, Debug, PartialEq)]
pub struct MergeReport {
    /// Regions merged.
    pub regions: usize,
    /// A point of the merged plane (local coordinates).
    pub origin: DVec3,
    /// Largest angle between a merged region's plane and the merged plane, degrees.
    pub angle_deg: f64,
    /// Bound on the largest vertex distance from the merged plane, metres.
    pub offset_m: f64,
    /// Reflection error at 1 m, metres: `2 (offset + tan(angle))`.
    pub error_m: f64,
}

/// A group of regions being merged.
struct Group {
    acc: PlaneAccumulator,
    plane: Plane,
    /// Corners of the box of the group's vertices in its plane's frame.
    corners: [DVec3; 8],
    /// Largest angle of a member region's plane to `plane`, radians.
    angle: f64,
    /// Bound on the vertex distance from `plane` when the group was formed, metres.
    offset: f64,
    regions: usize,
}

/// The corners of the box of `points` in `plane`'s frame (u, v, normal).
fn frame_box(plane: &Plane, points: impl Iterator<Item = DVec3>) -> [DVec3; 8] {
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for p in points {
        let d = p - plane.origin;
        let l = DVec3::new(d.dot(plane.u), d.dot(plane.v), d.dot(plane.normal));
        lo = lo.min(l);
        hi = hi.max(l);
    }
    std::array::from_fn(|k| {
        let l = DVec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        );
        plane.origin + plane.u * l.x + plane.v * l.y + plane.normal * l.z
    })
}

fn angle_between(a: DVec3, b: DVec3) -> f64 {
    a.dot(b).clamp(-1.0, 1.0).acos()
}

/// Merges near-planar touching regions of `regions` (see the module docs). Regions keep
/// the order of their first member region; members of a merged group are concatenated in
/// region order. Deterministic.
pub fn merge_near_planar(
    candidates: &[Candidate],
    regions: Vec<GrownRegion>,
    conn: &Connectivity,
    rule: &NearPlanarRule,
) -> (Vec<GrownRegion>, Vec<MergeReport>) {
    if !(rule.max_angle_deg > 0.0) || regions.len() < 2 {
        return (regions, Vec::new());
    }
    let max_angle = rule.max_angle_deg.to_radians();
    let planes: Vec<Option<Plane>> = regions.iter().map(|r| r.moments.fit()).collect();
    // Groups are made for the regions of some candidate pair only (see below).
    let mut groups: Vec<Option<Group>> = (0..regions.len()).map(|_| None).collect();
    let group_of = |r: &GrownRegion, plane: Plane| {
        let corners = frame_box(&plane, r.members.iter().flat_map(|&m| candidates[m as usize].positions));
        Group { acc: r.moments.clone(), plane, corners, angle: 0.0, offset: 0.0, regions: 1 }
    };
    // Touching pairs of the same kind with planes within the angle, smallest angle first.
    let mut region_of = vec![u32::MAX; candidates.len()];
    for (i, r) in regions.iter().enumerate() {
        for &m in &r.members {
            region_of[m as usize] = i as u32;
        }
    }
    let mut pairs: Vec<(u32, u32)> = Vec::new();
    let mut here: Vec<u32> = Vec::new();
    for v in 0..conn.vertex_count() as u32 {
        here.clear();
        here.extend(conn.users(v).iter().map(|&t| region_of[t as usize]).filter(|&r| r != u32::MAX));
        if here.len() < 2 {
            continue;
        }
        here.sort_unstable();
        here.dedup();
        for (k, &a) in here.iter().enumerate() {
            for &b in &here[k + 1..] {
                pairs.push((a, b));
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    let mut ranked: Vec<(f64, u32, u32)> = pairs
        .into_iter()
        .filter(|&(a, b)| regions[a as usize].kind == regions[b as usize].kind)
        .filter_map(|(a, b)| {
            let (pa, pb) = (planes[a as usize].as_ref()?, planes[b as usize].as_ref()?);
            let angle = angle_between(pa.normal, pb.normal);
            (angle <= max_angle).then_some((angle, a, b))
        })
        .collect();
    for &(_, a, b) in &ranked {
        for r in [a, b] {
            if groups[r as usize].is_none()
                && let Some(plane) = planes[r as usize]
            {
                groups[r as usize] = Some(group_of(&regions[r as usize], plane));
            }
        }
    }
    ranked.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.cmp(&y.2)));
    // Union-find over regions; a group lives at its smallest region.
    let mut parent: Vec<u32> = (0..regions.len() as u32).collect();
    fn root(parent: &mut [u32], mut i: u32) -> u32 {
        while parent[i as usize] != i {
            parent[i as usize] = parent[parent[i as usize] as usize];
            i = parent[i as usize];
        }
        i
    }
    for (_, a, b) in ranked {
        let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
        if ra == rb {
            continue;
        }
        let (Some(ga), Some(gb)) = (groups[ra as usize].as_ref(), groups[rb as usize].as_ref()) else {
            continue;
        };
        if angle_between(ga.plane.normal, gb.plane.normal) > max_angle {
            continue;
        }
        let mut acc = ga.acc.clone();
        acc.merge(&gb.acc);
        let Some(plane) = acc.fit() else { continue };
        let all = ga.corners.iter().chain(&gb.corners).copied();
        let offset = all.clone().map(|c| plane.signed_distance(c).abs()).fold(0.0, f64::max);
        let angle = (ga.angle + angle_between(ga.plane.normal, plane.normal))
            .max(gb.angle + angle_between(gb.plane.normal, plane.normal));
        let error = 2.0 * (offset + REFERENCE_DISTANCE_M * angle.tan());
        if !(error <= rule.max_error_m) {
            continue;
        }
        let merged = Group {
            corners: frame_box(&plane, all),
            acc,
            plane,
            angle,
            offset,
            regions: ga.regions + gb.regions,
        };
        let (keep, gone) = (ra.min(rb), ra.max(rb));
        parent[gone as usize] = keep;
        groups[keep as usize] = Some(merged);
        groups[gone as usize] = None;
    }
    // Members per group, in region order.
    let mut out: Vec<GrownRegion> = Vec::new();
    let mut slot = vec![u32::MAX; regions.len()];
    let mut reports = Vec::new();
    let roots: Vec<u32> = (0..regions.len() as u32).map(|i| root(&mut parent, i)).collect();
    for (i, region) in regions.into_iter().enumerate() {
        let r = roots[i] as usize;
        if slot[r] == u32::MAX {
            slot[r] = out.len() as u32;
            let moments = groups[r].as_ref().map_or_else(|| region.moments.clone(), |g| g.acc.clone());
            out.push(GrownRegion { kind: region.kind, members: Vec::new(), moments });
            if let Some(g) = groups[r].as_ref().filter(|g| g.regions > 1) {
                reports.push(MergeReport {
                    regions: g.regions,
                    origin: g.plane.origin,
                    angle_deg: g.angle.to_degrees(),
                    offset_m: g.offset,
                    error_m: 2.0 * (g.offset + REFERENCE_DISTANCE_M * g.angle.tan()),
                });
            }
        }
        out[slot[r] as usize].members.extend(region.members);
    }
    (out, reports)
}
