//! Clustering coplanar candidate triangles into connected planar regions.
//!
//! Triangles are connected when they use a common weld point ([`Connectivity`]: shared
//! vertices, T-junctions, touching pieces). Regions grow from the largest unassigned
//! triangle over those connections, taking a neighbour of the same kind when all its
//! vertices lie within the distance tolerance of the region's plane and its normal is
//! within the angle tolerance (either winding; tiny triangles are judged by distance alone,
//! so noisy tessellation still merges). The plane is refitted (area-weighted least
//! squares, relative to a local origin) each time the region's area doubles, so a noisy
//! seed does not stop the growth, and the neighbours an earlier plane refused are asked
//! again after each refit. Growth over connections yields each plane's connected regions
//! directly; coplanar pieces that do not touch become separate regions.
//!
//! Linear time: each weld point is expanded at most once per region that reaches it.

use std::collections::VecDeque;

use ppr_format::ReflectorKind;

use crate::SceneScale;
pub use crate::connectivity::{Connectivity, point_triangle_distance_sq};
use crate::plane::{Plane, PlaneAccumulator};
use crate::select::Candidate;

/// A connected planar region: candidate indices, all of one kind.
#[derive(Clone, Debug)]
pub struct GrownRegion {
    /// The kind of every member.
    pub kind: ReflectorKind,
    /// Indices into the candidate list, in growth order (seed first).
    pub members: Vec<u32>,
    /// The area-weighted moments of every member (the region's plane fit).
    pub moments: PlaneAccumulator,
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
    // Larger area first, then lower index: sorted on flat keys (the order of
    // `f64::total_cmp`, reversed) rather than by reading the candidates in the comparisons.
    let mut keyed: Vec<(i64, u32)> =
        candidates.iter().enumerate().map(|(i, c)| (!total_order_key(c.area), i as u32)).collect();
    keyed.sort_unstable();
    let order: Vec<u32> = keyed.into_iter().map(|(_, i)| i).collect();
    let mut assigned = vec![false; n];
    // The region that last expanded each weld point (+1; 0: none yet).
    let mut expanded_by = vec![0u32; conn.vertex_count()];
    let mut regions = Vec::new();
    let mut done = 0usize;
    let mut queue = VecDeque::new();
    let mut refused: Vec<u32> = Vec::new();
    for &seed in &order {
        if assigned[seed as usize] {
            continue;
        }
        let stamp = regions.len() as u32 + 1;
        let s = &candidates[seed as usize];
        let mut acc = PlaneAccumulator::new(s.positions[0]);
        acc.add(s.positions);
        let mut plane = Plane::new((s.positions[0] + s.positions[1] + s.positions[2]) / 3.0, s.normal);
        let mut refit_at = 2.0 * s.area;
        assigned[seed as usize] = true;
        let mut members = vec![seed];
        queue.clear();
        refused.clear();
        queue.push_back(seed);
        while let Some(t) = queue.pop_front() {
            for v in conn.vertices(t) {
                if expanded_by[v as usize] == stamp {
                    continue;
                }
                expanded_by[v as usize] = stamp;
                for &nb in conn.users(v) {
                    let c = &candidates[nb as usize];
                    if assigned[nb as usize] || c.kind != s.kind {
                        continue;
                    }
                    if !accepts(c, &plane, scale) {
                        refused.push(nb);
                        continue;
                    }
                    assigned[nb as usize] = true;
                    members.push(nb);
                    queue.push_back(nb);
                    acc.add(c.positions);
                }
            }
            if acc.area() >= refit_at {
                if let Some(p) = acc.fit() {
                    plane = p;
                }
                refit_at = 2.0 * acc.area();
                // Ask the neighbours the old plane refused again.
                refused.retain(|&nb| {
                    if assigned[nb as usize] || !accepts(&candidates[nb as usize], &plane, scale) {
                        return !assigned[nb as usize];
                    }
                    assigned[nb as usize] = true;
                    members.push(nb);
                    queue.push_back(nb);
                    acc.add(candidates[nb as usize].positions);
                    false
                });
            }
        }
        done += members.len();
        if regions.len() % 256 == 0 {
            progress(done as f32 / n.max(1) as f32);
        }
        regions.push(GrownRegion { kind: s.kind, members, moments: acc });
    }
    regions
}

/// An integer that orders like [`f64::total_cmp`].
fn total_order_key(x: f64) -> i64 {
    let bits = x.to_bits() as i64;
    bits ^ (((bits >> 63) as u64) >> 1) as i64
}

fn accepts(c: &Candidate, plane: &Plane, scale: &SceneScale) -> bool {
    c.positions.iter().all(|&p| plane.signed_distance(p).abs() <= scale.distance_tolerance)
        && (c.normal.dot(plane.normal).abs() >= scale.cos_angle || c.longest_edge <= scale.small_triangle)
}

#[cfg(test)]
mod tests {
    use super::total_order_key;

    #[test]
    fn total_order_keys_order_like_total_cmp() {
        let xs = [f64::NEG_INFINITY, -2.5, -1e-300, -0.0, 0.0, 1e-300, 0.5, 3.0, f64::INFINITY];
        for a in xs {
            for b in xs {
                assert_eq!(total_order_key(a).cmp(&total_order_key(b)), a.total_cmp(&b), "{a} {b}");
            }
        }
    }
}
