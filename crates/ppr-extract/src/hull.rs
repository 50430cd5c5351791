//! Convex hull of 2-D points (Andrew's monotone chain with robust orientation tests):
//! counter-clockwise, no duplicate and no collinear points.

use glam::DVec2;

/// Orientation of `c` relative to the line `a → b`: positive when counter-clockwise
/// (exact sign, from Shewchuk's adaptive predicates).
pub fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    let p = |v: DVec2| robust::Coord { x: v.x, y: v.y };
    robust::orient2d(p(a), p(b), p(c))
}

/// The convex hull, counter-clockwise, starting at the lowest-x (then lowest-y) point.
/// Fewer than three points come back when the input is empty, one point, or collinear
/// (then the two extreme points).
pub fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut pts: Vec<DVec2> = without_inner_points(points);
    // Points equal under this order are equal bit for bit: an unstable sort gives the same.
    pts.sort_unstable_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut hull: Vec<DVec2> = Vec::with_capacity(pts.len() + 1);
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &DVec2>> =
            if pass == 0 { Box::new(pts.iter()) } else { Box::new(pts.iter().rev()) };
        for &p in iter {
            while hull.len() >= start + 2 && orient(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop(); // the last point starts the other chain
    }
    if hull.len() < 3 {
        // Collinear input: the two extremes.
        return vec![pts[0], pts[pts.len() - 1]];
    }
    hull
}

/// Points fewer than this are sorted as they are.
const CULL_FROM: usize = 32;

/// `points` less those strictly inside the polygon of their extremes along x, y and the
/// diagonals (Akl and Toussaint's heuristic): a point strictly left of every edge of a closed
/// polygon of input points is interior to their hull, so it is no hull vertex and the hull
/// is the same, while the sort gets only the points near the boundary. Exact tests.
fn without_inner_points(points: &[DVec2]) -> Vec<DVec2> {
    if points.len() < CULL_FROM {
        return points.to_vec();
    }
    // Directions counter-clockwise from −y.
    let dirs = [
        (0.0, -1.0),
        (1.0, -1.0),
        (1.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
        (-1.0, 1.0),
        (-1.0, 0.0),
        (-1.0, -1.0),
    ]
    .map(|(x, y)| DVec2::new(x, y));
    let mut extreme = [points[0]; 8];
    let mut reach = [f64::NEG_INFINITY; 8];
    for &p in points {
        for k in 0..8 {
            let s = dirs[k].dot(p);
            if s > reach[k] {
                reach[k] = s;
                extreme[k] = p;
            }
        }
    }
    let edges: Vec<(DVec2, DVec2)> =
        (0..8).map(|k| (extreme[k], extreme[(k + 1) % 8])).filter(|(a, b)| a != b).collect();
    if edges.len() < 3 {
        return points.to_vec();
    }
    points.iter().copied().filter(|&p| !edges.iter().all(|&(a, b)| orient(a, b, p) > 0.0)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    fn check(input: &[DVec2], expected: &[DVec2]) {
        assert_eq!(convex_hull(input), expected, "hull of {input:?}");
    }

    #[test]
    fn hulls() {
        check(&[], &[]);
        check(&[v(1.0, 1.0), v(1.0, 1.0)], &[v(1.0, 1.0)]);
        // Square with interior, duplicate and edge-collinear points.
        check(
            &[
                v(0.0, 0.0),
                v(1.0, 0.0),
                v(1.0, 1.0),
                v(0.0, 1.0),
                v(0.5, 0.5),
                v(0.5, 0.0),
                v(1.0, 1.0),
                v(0.0, 0.5),
            ],
            &[v(0.0, 0.0), v(1.0, 0.0), v(1.0, 1.0), v(0.0, 1.0)],
        );
        // All collinear.
        check(&[v(0.0, 0.0), v(2.0, 2.0), v(1.0, 1.0)], &[v(0.0, 0.0), v(2.0, 2.0)]);
        // Nearly collinear point just outside an edge is kept (exact predicate).
        let eps = 1e-12;
        let h = convex_hull(&[v(0.0, 0.0), v(1.0, 0.0), v(0.5, -eps), v(0.5, 1.0)]);
        assert_eq!(h.len(), 4, "{h:?}");
    }

    #[test]
    fn culling_inner_points_keeps_the_hull() {
        let mut seed = 11u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for round in 0..40 {
            // Grids (many collinear and duplicate points), discs and thin slivers.
            let pts: Vec<DVec2> = (0..200)
                .map(|k| match round % 3 {
                    0 => v((k % 13) as f64 * 0.25, (k / 13) as f64 * 0.25),
                    1 => DVec2::from_angle(rnd() * 6.3) * rnd().sqrt() * 3.0,
                    _ => v(rnd() * 10.0, rnd() * 1e-9),
                })
                .collect();
            let full = {
                let mut p = pts.clone();
                p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
                p.dedup();
                p
            };
            assert!(full.len() >= CULL_FROM);
            let kept = without_inner_points(&pts);
            assert!(kept.len() <= pts.len());
            let h = convex_hull(&pts);
            // The hull of every point, by the plain monotone chain on all of them.
            let mut all: Vec<DVec2> = Vec::new();
            for pass in 0..2 {
                let start = all.len();
                let iter: Box<dyn Iterator<Item = &DVec2>> =
                    if pass == 0 { Box::new(full.iter()) } else { Box::new(full.iter().rev()) };
                for &p in iter {
                    while all.len() >= start + 2 && orient(all[all.len() - 2], all[all.len() - 1], p) <= 0.0 {
                        all.pop();
                    }
                    all.push(p);
                }
                all.pop();
            }
            if all.len() < 3 {
                all = vec![full[0], full[full.len() - 1]];
            }
            assert_eq!(h, all, "round {round}");
        }
    }

    #[test]
    fn hull_contains_every_point() {
        let mut seed = 7u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..50 {
            let pts: Vec<DVec2> = (0..60).map(|_| v(rnd() * 10.0 - 5.0, rnd() * 3.0)).collect();
            let h = convex_hull(&pts);
            for i in 0..h.len() {
                let (a, b) = (h[i], h[(i + 1) % h.len()]);
                for &p in &pts {
                    assert!(orient(a, b, p) >= 0.0, "{p:?} outside edge {a:?}-{b:?}");
                }
                assert!(orient(a, b, h[(i + 2) % h.len()]) > 0.0, "collinear hull point");
            }
        }
    }
}
