//! Clustering coplanar candidate triangles into connected planar regions.
//!
//! Triangles are connected when they share a vertex (positions welded within the gap
//! tolerance, since exporters duplicate vertices) or when a vertex of one lies within the
//! gap tolerance of the other (T-junctions, touching or overlapping coplanar pieces).
//! Regions then grow from the largest unassigned triangle over those connections, taking a
//! neighbour of the same kind when all its vertices lie within the distance tolerance of
//! the region's plane and its normal is within the angle tolerance (either winding; tiny
//! triangles are judged by distance alone, so noisy tessellation still merges). The plane
//! is refitted (area-weighted least squares, relative to a local origin) each time the
//! region's area doubles, so a noisy seed does not stop the growth. Growth over
//! connections yields each plane's connected regions directly; coplanar pieces that do not
//! touch become separate regions.

use std::collections::VecDeque;

use glam::DVec3;
use ppr_format::ReflectorKind;

use crate::SceneScale;
use crate::int_hash::{IntMap, cell_of};
use crate::plane::{Plane, PlaneAccumulator};
use crate::select::Candidate;

/// A connected planar region: candidate indices, all of one kind.
#[derive(Clone, Debug, PartialEq)]
pub struct GrownRegion {
    /// The kind of every member.
    pub kind: ReflectorKind,
    /// Indices into the candidate list, in growth order (seed first).
    pub members: Vec<u32>,
}

/// Connections between candidate triangles.
pub struct Connectivity {
    /// Welded vertex ids of each candidate's corners.
    pub welded: Vec<[u32; 3]>,
    /// For each welded vertex, the candidates that use it (CSR offsets and items).
    vertex_offsets: Vec<u32>,
    vertex_items: Vec<u32>,
    /// Extra neighbours through T-junctions and gaps, per candidate (CSR).
    extra_offsets: Vec<u32>,
    extra_items: Vec<u32>,
}

impl Connectivity {
    /// Welds vertices and finds vertex-to-triangle contacts within `scale.gap`.
    pub fn build(candidates: &[Candidate], scale: &SceneScale) -> Self {
        let gap = scale.gap.max(1e-15 * scale.diagonal);
        let (welded, weld_points) = weld(candidates, gap);
        let nv = weld_points.len();
        let (vertex_offsets, vertex_items) =
            csr(nv, welded.iter().enumerate().flat_map(|(t, w)| w.map(|v| (v, t as u32))));
        let contacts = contacts(candidates, &welded, &weld_points, gap);
        let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(contacts.len() * 4);
        for (v, t) in contacts {
            for &a in
                &vertex_items[vertex_offsets[v as usize] as usize..vertex_offsets[v as usize + 1] as usize]
            {
                pairs.push((a, t));
                pairs.push((t, a));
            }
        }
        let (extra_offsets, extra_items) = csr(candidates.len(), pairs.into_iter());
        Self { welded, vertex_offsets, vertex_items, extra_offsets, extra_items }
    }

    /// Every candidate connected to `t` (may repeat).
    pub fn neighbours(&self, t: u32) -> impl Iterator<Item = u32> + '_ {
        let via_vertices = self.welded[t as usize].into_iter().flat_map(move |v| {
            self.vertex_items
                [self.vertex_offsets[v as usize] as usize..self.vertex_offsets[v as usize + 1] as usize]
                .iter()
                .copied()
        });
        let extra = self.extra_items
            [self.extra_offsets[t as usize] as usize..self.extra_offsets[t as usize + 1] as usize]
            .iter()
            .copied();
        via_vertices.chain(extra)
    }
}

/// Compressed rows: for keys `0..n`, the values paired with them, in input order.
fn csr(n: usize, pairs: impl Iterator<Item = (u32, u32)> + Clone) -> (Vec<u32>, Vec<u32>) {
    let mut offsets = vec![0u32; n + 1];
    for (k, _) in pairs.clone() {
        offsets[k as usize + 1] += 1;
    }
    for i in 0..n {
        offsets[i + 1] += offsets[i];
    }
    let mut fill = offsets.clone();
    let mut items = vec![0u32; offsets[n] as usize];
    for (k, v) in pairs {
        items[fill[k as usize] as usize] = v;
        fill[k as usize] += 1;
    }
    (offsets, items)
}

/// Welds corner positions within `tol`: returns per-candidate welded ids and the weld points.
fn weld(candidates: &[Candidate], tol: f64) -> (Vec<[u32; 3]>, Vec<DVec3>) {
    // Cells of 2·tol: the ball of radius tol around a point lies in the 2×2×2 cells nearest it.
    let cell = 2.0 * tol;
    let mut grid: IntMap<(i64, i64, i64), Vec<u32>> = IntMap::default();
    let mut points: Vec<DVec3> = Vec::new();
    let mut welded = Vec::with_capacity(candidates.len());
    for c in candidates {
        let mut ids = [0u32; 3];
        for (k, &p) in c.positions.iter().enumerate() {
            let base = [p.x, p.y, p.z].map(|x| cell_of(x, cell));
            let near = [p.x, p.y, p.z].map(|x| if (x / cell) - (x / cell).floor() < 0.5 { -1 } else { 1 });
            let mut found = None;
            'search: for dx in [0, near[0]] {
                for dy in [0, near[1]] {
                    for dz in [0, near[2]] {
                        if let Some(list) = grid.get(&(base[0] + dx, base[1] + dy, base[2] + dz)) {
                            for &id in list {
                                if points[id as usize].distance_squared(p) <= tol * tol {
                                    found = Some(id);
                                    break 'search;
                                }
                            }
                        }
                    }
                }
            }
            ids[k] = found.unwrap_or_else(|| {
                let id = points.len() as u32;
                points.push(p);
                grid.entry((base[0], base[1], base[2])).or_default().push(id);
                id
            });
        }
        welded.push(ids);
    }
    (welded, points)
}

/// (welded vertex, candidate) pairs where the vertex is within `gap` of the triangle
/// without being one of its corners: T-junctions and touching pieces.
fn contacts(candidates: &[Candidate], welded: &[[u32; 3]], points: &[DVec3], gap: f64) -> Vec<(u32, u32)> {
    if candidates.is_empty() {
        return Vec::new();
    }
    // Grid of weld points, cells about the size of a typical triangle.
    let mut edges: Vec<f64> = candidates.iter().map(|c| c.longest_edge).collect();
    let mid = edges.len() / 2;
    let median = *edges.select_nth_unstable_by(mid, f64::total_cmp).1;
    let cell = median.max(4.0 * gap);
    let mut grid: IntMap<(i64, i64, i64), Vec<u32>> = IntMap::default();
    for (i, p) in points.iter().enumerate() {
        grid.entry((cell_of(p.x, cell), cell_of(p.y, cell), cell_of(p.z, cell))).or_default().push(i as u32);
    }
    let mut occupied: Vec<(i64, i64, i64)> = grid.keys().copied().collect();
    occupied.sort_unstable();
    let mut out = Vec::new();
    for (t, c) in candidates.iter().enumerate() {
        let lo = c.positions[0].min(c.positions[1]).min(c.positions[2]) - DVec3::splat(gap);
        let hi = c.positions[0].max(c.positions[1]).max(c.positions[2]) + DVec3::splat(gap);
        let (l, h) =
            ([lo.x, lo.y, lo.z].map(|x| cell_of(x, cell)), [hi.x, hi.y, hi.z].map(|x| cell_of(x, cell)));
        let span = (h[0] - l[0] + 1) as f64 * (h[1] - l[1] + 1) as f64 * (h[2] - l[2] + 1) as f64;
        let mut test = |list: &Vec<u32>| {
            for &v in list {
                if welded[t].contains(&v) {
                    continue;
                }
                let p = points[v as usize];
                if p.cmpge(lo).all()
                    && p.cmple(hi).all()
                    && point_triangle_distance_sq(p, c.positions) <= gap * gap
                {
                    out.push((v, t as u32));
                }
            }
        };
        if span <= occupied.len() as f64 {
            for x in l[0]..=h[0] {
                for y in l[1]..=h[1] {
                    for z in l[2]..=h[2] {
                        if let Some(list) = grid.get(&(x, y, z)) {
                            test(list);
                        }
                    }
                }
            }
        } else {
            for key in &occupied {
                if (0..3).all(|a| [key.0, key.1, key.2][a] >= l[a] && [key.0, key.1, key.2][a] <= h[a]) {
                    test(&grid[key]);
                }
            }
        }
    }
    out
}

/// Squared distance from `p` to the triangle (Ericson, Real-Time Collision Detection 5.1.5).
pub fn point_triangle_distance_sq(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length_squared();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length_squared();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (p - (a + ab * v)).length_squared();
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length_squared();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (p - (a + ac * w)).length_squared();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (p - (b + (c - b) * w)).length_squared();
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    (p - (a + ab * v + ac * w)).length_squared()
}

/// Grows connected planar regions over `conn`, largest seeds first.
/// `progress(f)` is called with the fraction of candidates assigned.
pub fn grow_regions(
    candidates: &[Candidate],
    conn: &Connectivity,
    scale: &SceneScale,
    progress: &mut dyn FnMut(f32),
) -> Vec<GrownRegion> {
    let n = candidates.len();
    let mut order: Vec<u32> = (0..n as u32).collect();
    order.sort_by(|&a, &b| {
        candidates[b as usize].area.total_cmp(&candidates[a as usize].area).then(a.cmp(&b))
    });
    let mut assigned = vec![false; n];
    let mut regions = Vec::new();
    let mut done = 0usize;
    let mut queue = VecDeque::new();
    for &seed in &order {
        if assigned[seed as usize] {
            continue;
        }
        let s = &candidates[seed as usize];
        let mut acc = PlaneAccumulator::new(s.positions[0]);
        acc.add(s.positions);
        let mut plane = Plane::new((s.positions[0] + s.positions[1] + s.positions[2]) / 3.0, s.normal);
        let mut refit_at = 2.0 * s.area;
        assigned[seed as usize] = true;
        let mut members = vec![seed];
        queue.clear();
        queue.push_back(seed);
        while let Some(t) = queue.pop_front() {
            for nb in conn.neighbours(t) {
                let c = &candidates[nb as usize];
                if assigned[nb as usize] || c.kind != s.kind || !accepts(c, &plane, scale) {
                    continue;
                }
                assigned[nb as usize] = true;
                members.push(nb);
                queue.push_back(nb);
                acc.add(c.positions);
                if acc.area() >= refit_at {
                    if let Some(p) = acc.fit() {
                        plane = p;
                    }
                    refit_at = 2.0 * acc.area();
                }
            }
        }
        done += members.len();
        if regions.len() % 256 == 0 {
            progress(done as f32 / n.max(1) as f32);
        }
        regions.push(GrownRegion { kind: s.kind, members });
    }
    regions
}

fn accepts(c: &Candidate, plane: &Plane, scale: &SceneScale) -> bool {
    c.positions.iter().all(|&p| plane.signed_distance(p).abs() <= scale.distance_tolerance)
        && (c.normal.dot(plane.normal).abs() >= scale.cos_angle || c.longest_edge <= scale.small_triangle)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_triangle_distances() {
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let check =
            |p: DVec3, d: f64| assert!((point_triangle_distance_sq(p, t).sqrt() - d).abs() < 1e-12, "{p:?}");
        check(DVec3::new(0.2, 0.2, 3.0), 3.0);
        check(DVec3::new(-1.0, -1.0, 0.0), 2f64.sqrt());
        check(DVec3::new(0.5, -2.0, 0.0), 2.0);
        check(DVec3::new(1.0, 1.0, 0.0), 0.5f64.sqrt());
        check(DVec3::new(3.0, 0.0, 0.0), 2.0);
    }

    #[test]
    fn csr_groups_in_order() {
        let (o, i) = csr(3, [(2, 7), (0, 1), (2, 8)].into_iter());
        assert_eq!(o, vec![0, 1, 1, 3]);
        assert_eq!(i, vec![1, 7, 8]);
    }
}
