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
    let mut pts: Vec<DVec2> = points.to_vec();
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
