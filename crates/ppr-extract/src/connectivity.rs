//! Which candidate triangles touch: welded vertices and vertex-to-triangle contacts.
//!
//! Corner positions are welded within the gap tolerance (exporters duplicate vertices): a
//! position joins the earliest weld point within the gap in its own cell of a grid of cells
//! eight gaps wide, else the earliest in the neighbouring cells its gap ball reaches, else
//! starts a new one. A weld point
//! that lies within the gap of a triangle without being one of its corners (T-junctions,
//! touching or overlapping coplanar pieces) is a *contact*: the triangle becomes one more
//! user of that point. Two triangles are connected when they use a common weld point.
//!
//! Everything is linear in the number of candidates: the grids are flat open-addressing
//! tables of packed cell keys ([`CellTable`]); the weld's cells hold linked lists in flat
//! arrays, the contact grid's cells runs of a point array sorted by cell (no allocation per
//! cell, each cell's points in one run of memory), a vertex's users are stored once (a fan of `k`
//! triangles costs `k`, not `k²`), and a triangle spanning many grid cells is tested
//! against the points of a Morton-ordered point hierarchy instead of cell by cell.

use glam::DVec3;

use crate::SceneScale;
use crate::int_hash::{CellTable, cell_of, packed_cell};
use crate::point_hierarchy::PointHierarchy;
use crate::select::Candidate;

/// End of a linked list in the flat arrays.
const NONE: u32 = u32::MAX;

/// Offset of the contact grid's cells, as a fraction of a cell (irrational-ish, so that round
/// coordinates do not fall on cell sides).
const CELL_SHIFT: f64 = 0.381_966;

/// Triangles that span more grid cells than this query the point hierarchy.
const MAX_CELLS_PER_QUERY: f64 = 64.0;

/// Connections between candidate triangles.
pub struct Connectivity {
    /// Welded vertex ids of each candidate's corners.
    pub welded: Vec<[u32; 3]>,
    /// For each welded vertex, the candidates that use it (corners and contacts; CSR).
    user_offsets: Vec<u32>,
    user_items: Vec<u32>,
    /// For each candidate, the weld points it touches without having them as corners (CSR).
    contact_offsets: Vec<u32>,
    contact_items: Vec<u32>,
}

impl Connectivity {
    /// Welds vertices and finds vertex-to-triangle contacts within `scale.gap`.
    pub fn build(candidates: &[Candidate], scale: &SceneScale) -> Self {
        let gap = scale.gap.max(1e-15 * scale.diagonal);
        let (welded, points) = weld(candidates, gap);
        let contacts = contacts(candidates, &welded, &points, gap);
        let (contact_offsets, contact_items) = csr(candidates.len(), contacts.iter().map(|&(v, t)| (t, v)));
        let corner_users = welded.iter().enumerate().flat_map(|(t, w)| w.map(|v| (v, t as u32)));
        let (user_offsets, user_items) =
            csr(points.len(), corner_users.chain(contacts.iter().copied()).collect::<Vec<_>>().into_iter());
        Self { welded, user_offsets, user_items, contact_offsets, contact_items }
    }

    /// The weld points `t` uses: its corners, then its contacts.
    pub fn vertices(&self, t: u32) -> impl Iterator<Item = u32> + '_ {
        let contacts = &self.contact_items
            [self.contact_offsets[t as usize] as usize..self.contact_offsets[t as usize + 1] as usize];
        self.welded[t as usize].into_iter().chain(contacts.iter().copied())
    }

    /// The candidates that use weld point `v`.
    pub fn users(&self, v: u32) -> &[u32] {
        &self.user_items[self.user_offsets[v as usize] as usize..self.user_offsets[v as usize + 1] as usize]
    }

    /// Number of weld points.
    pub fn vertex_count(&self) -> usize {
        self.user_offsets.len() - 1
    }

    /// Every candidate connected to `t` (may repeat, includes `t`).
    pub fn neighbours(&self, t: u32) -> impl Iterator<Item = u32> + '_ {
        self.vertices(t).flat_map(move |v| self.users(v).iter().copied())
    }
}

/// Compressed rows: for keys `0..n`, the values paired with them, in input order.
pub(crate) fn csr(n: usize, pairs: impl Iterator<Item = (u32, u32)> + Clone) -> (Vec<u32>, Vec<u32>) {
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

type Cell = (i64, i64, i64);

/// Slots of the weld's cache of recent exact positions (a power of two).
const RECENT_SLOTS: usize = 4096;

fn recent_slot(bits: [u64; 3]) -> usize {
    let h = (bits[0] ^ bits[1].rotate_left(21) ^ bits[2].rotate_left(42)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    (h >> 52) as usize & (RECENT_SLOTS - 1)
}

fn cell3(p: DVec3, cell: f64) -> Cell {
    (cell_of(p.x, cell), cell_of(p.y, cell), cell_of(p.z, cell))
}

/// How many positions (weld) or triangles (contacts) ahead the grid look-ups are
/// prefetched.
const PREFETCH_AHEAD: usize = 16;

/// Welds corner positions within `tol`: per-candidate welded ids and the weld points.
/// A position joins the earliest weld point within `tol` (deterministic).
fn weld(candidates: &[Candidate], tol: f64) -> (Vec<[u32; 3]>, Vec<DVec3>) {
    // Exact positions seen lately (meshes reuse a vertex within a few triangles) take the
    // weld point of the position they repeat, which is the one the grid would give (ids only
    // grow, so the earliest stays so). Whether a corner repeats depends on the positions
    // alone, so the repeats are found first and the grid sees only the other positions,
    // whose look-ups it can then prefetch.
    let mut recent: Vec<([u64; 3], u32)> = vec![([u64::MAX; 3], NONE); RECENT_SLOTS];
    let mut fresh: Vec<DVec3> = Vec::new();
    let mut corner_fresh: Vec<[u32; 3]> = Vec::with_capacity(candidates.len());
    for c in candidates {
        corner_fresh.push(c.positions.map(|p| {
            let bits = p.to_array().map(f64::to_bits);
            let slot = recent_slot(bits);
            if recent[slot].0 != bits {
                recent[slot] = (bits, fresh.len() as u32);
                fresh.push(p);
            }
            recent[slot].1
        }));
    }
    drop(recent);
    // Cells of 8·tol: the ball of radius tol around a point reaches a neighbouring cell only
    // near a cell's side, so most new points look in one cell.
    let cell = 8.0 * tol;
    let keys: Vec<u64> = fresh.iter().map(|&p| packed_cell(cell3(p, cell))).collect();
    let mut head = CellTable::with_capacity(fresh.len());
    let mut next: Vec<u32> = Vec::new();
    let mut points: Vec<DVec3> = Vec::new();
    // The earliest weld point within tol of `p` in the cell `key`, or `found` when earlier.
    let earliest_in = |head: &CellTable, next: &[u32], points: &[DVec3], key: u64, p: DVec3, found: u32| {
        let mut found = found;
        let mut id = head.get(key).unwrap_or(NONE);
        while id != NONE {
            if id < found && points[id as usize].distance_squared(p) <= tol * tol {
                found = id;
            }
            id = next[id as usize];
        }
        found
    };
    let mut fresh_ids: Vec<u32> = Vec::with_capacity(fresh.len());
    for (i, &p) in fresh.iter().enumerate() {
        if let Some(&ahead) = keys.get(i + PREFETCH_AHEAD) {
            head.prefetch(ahead);
        }
        let base = cell3(p, cell);
        // The point's own cell first (exact duplicates are there), then its neighbours.
        let mut found = earliest_in(&head, &next, &points, keys[i], p, NONE);
        if found == NONE {
            // Only the cells the ball of radius tol reaches (most points: none).
            let (lo, hi) = (cell3(p - DVec3::splat(tol), cell), cell3(p + DVec3::splat(tol), cell));
            for x in lo.0..=hi.0 {
                for y in lo.1..=hi.1 {
                    for z in lo.2..=hi.2 {
                        if (x, y, z) != base {
                            found = earliest_in(&head, &next, &points, packed_cell((x, y, z)), p, found);
                        }
                    }
                }
            }
        }
        if found == NONE {
            found = points.len() as u32;
            points.push(p);
            let first = head.entry_or(keys[i], NONE);
            next.push(*first);
            *first = found;
        }
        fresh_ids.push(found);
    }
    let welded = corner_fresh.into_iter().map(|f| f.map(|i| fresh_ids[i as usize])).collect();
    (welded, points)
}

/// (welded vertex, candidate) pairs where the vertex is within `gap` of the triangle
/// without being one of its corners: T-junctions and touching pieces. In candidate order.
fn contacts(candidates: &[Candidate], welded: &[[u32; 3]], points: &[DVec3], gap: f64) -> Vec<(u32, u32)> {
    if candidates.is_empty() {
        return Vec::new();
    }
    // Grid of weld points, cells about the size of a typical triangle.
    let mut edges: Vec<f64> = candidates.iter().map(|c| c.longest_edge).collect();
    let mid = edges.len() / 2;
    let median = *edges.select_nth_unstable_by(mid, f64::total_cmp).1;
    let cell = median.max(4.0 * gap);
    // Cell sides off round coordinates: a floor at y = 0 lies inside one layer of cells, not
    // on the side between two (half the look-ups would find empty cells).
    let shift = DVec3::splat(CELL_SHIFT * cell);
    // The points grouped by cell (ascending ids in each), with their positions beside them
    // so that a query reads each cell's points from one run of memory.
    let mut cells = CellTable::with_capacity(points.len());
    let mut cell_count = 0u32;
    let point_cells: Vec<u32> = points
        .iter()
        .map(|p| {
            let c = cells.entry_or(packed_cell(cell3(*p + shift, cell)), NONE);
            if *c == NONE {
                *c = cell_count;
                cell_count += 1;
            }
            *c
        })
        .collect();
    let (cell_offsets, cell_items) =
        csr(cell_count as usize, point_cells.iter().enumerate().map(|(i, &c)| (c, i as u32)));
    drop(point_cells);
    let cell_points: Vec<DVec3> = cell_items.iter().map(|&i| points[i as usize]).collect();
    let mut hierarchy: Option<PointHierarchy> = None;
    let mut out = Vec::new();
    let mut found: Vec<u32> = Vec::new();
    let query_cells = |c: &Candidate| {
        let lo = c.positions[0].min(c.positions[1]).min(c.positions[2]) - DVec3::splat(gap);
        let hi = c.positions[0].max(c.positions[1]).max(c.positions[2]) + DVec3::splat(gap);
        (lo, hi, cell3(lo + shift, cell), cell3(hi + shift, cell))
    };
    for (t, c) in candidates.iter().enumerate() {
        if let Some(ahead) = candidates.get(t + PREFETCH_AHEAD) {
            let (_, _, l, h) = query_cells(ahead);
            if (h.0 - l.0 + 1) * (h.1 - l.1 + 1) * (h.2 - l.2 + 1) <= 8 {
                for x in l.0..=h.0 {
                    for y in l.1..=h.1 {
                        for z in l.2..=h.2 {
                            cells.prefetch(packed_cell((x, y, z)));
                        }
                    }
                }
            }
        }
        let (lo, hi, l, h) = query_cells(c);
        let span = (h.0 - l.0 + 1) as f64 * (h.1 - l.1 + 1) as f64 * (h.2 - l.2 + 1) as f64;
        let corners = welded[t];
        // Points in the box that are not corners, then the exact distance in id order.
        let wanted = |v: u32, p: DVec3| !corners.contains(&v) && p.cmpge(lo).all() && p.cmple(hi).all();
        found.clear();
        if span <= MAX_CELLS_PER_QUERY {
            for x in l.0..=h.0 {
                for y in l.1..=h.1 {
                    for z in l.2..=h.2 {
                        let Some(k) = cells.get(packed_cell((x, y, z))) else { continue };
                        let run = cell_offsets[k as usize] as usize..cell_offsets[k as usize + 1] as usize;
                        for (&v, &p) in cell_items[run.clone()].iter().zip(&cell_points[run]) {
                            if wanted(v, p) {
                                found.push(v);
                            }
                        }
                    }
                }
            }
        } else {
            let start = found.len();
            hierarchy.get_or_insert_with(|| PointHierarchy::new(points)).query(lo, hi, &mut found);
            let mut kept = start;
            for k in start..found.len() {
                let v = found[k];
                if wanted(v, points[v as usize]) {
                    found[kept] = v;
                    kept += 1;
                }
            }
            found.truncate(kept);
        }
        found.sort_unstable();
        for &v in &found {
            if point_triangle_distance_sq(points[v as usize], c.positions) <= gap * gap {
                out.push((v, t as u32));
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
