//! Minimum-area enclosing rectangle of 2-D points: convex hull, then rotating calipers
//! over the hull's edges (the optimum has a side collinear with a hull edge, Freeman and
//! Shapira 1975). The extents are finally taken over *all* points, so the rectangle
//! encloses every input point whatever rounding did to the hull.

use glam::DVec2;

use crate::hull::convex_hull;

/// A rectangle in a plane's 2-D frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect2 {
    /// Centre.
    pub center: DVec2,
    /// Unit direction of the first side; the second is its left perpendicular.
    pub axis: DVec2,
    /// Half sizes along `axis` and its perpendicular; `x >= y`.
    pub half: DVec2,
}

impl Rect2 {
    /// Area.
    pub fn area(&self) -> f64 {
        4.0 * self.half.x * self.half.y
    }

    /// The second axis (`axis` turned by +90°).
    pub fn perp(&self) -> DVec2 {
        self.axis.perp()
    }

    /// Coordinates of `p` in the rectangle's frame, relative to its centre.
    pub fn local(&self, p: DVec2) -> DVec2 {
        let d = p - self.center;
        DVec2::new(d.dot(self.axis), d.dot(self.perp()))
    }

    /// Whether `p` is inside, with `margin`.
    pub fn contains(&self, p: DVec2, margin: f64) -> bool {
        let l = self.local(p);
        l.x.abs() <= self.half.x + margin && l.y.abs() <= self.half.y + margin
    }
}

/// The rectangle with sides along `axis` and its perpendicular that tightly encloses `points`.
pub fn enclosing_rect_along(points: &[DVec2], axis: DVec2) -> Rect2 {
    let perp = axis.perp();
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for &p in points {
        let l = DVec2::new(p.dot(axis), p.dot(perp));
        lo = lo.min(l);
        hi = hi.max(l);
    }
    let mid = (lo + hi) * 0.5;
    let half = (hi - lo) * 0.5;
    canonical(Rect2 { center: axis * mid.x + perp * mid.y, axis, half })
}

/// Long side first, and a deterministic sign for the axis.
fn canonical(mut r: Rect2) -> Rect2 {
    if r.half.y > r.half.x {
        r.axis = r.axis.perp();
        r.half = DVec2::new(r.half.y, r.half.x);
    }
    if r.axis.x < 0.0 || (r.axis.x == 0.0 && r.axis.y < 0.0) {
        r.axis = -r.axis;
    }
    r
}

/// The minimum-area rectangle enclosing `points` (`None` when there are none).
/// Degenerate inputs give zero half extents where the points have no spread.
pub fn min_area_rect(points: &[DVec2]) -> Option<Rect2> {
    let first = *points.first()?;
    // Work relative to a point of the set: the caller's coordinates may be large.
    let local: Vec<DVec2> = points.iter().map(|&p| p - first).collect();
    let hull = convex_hull(&local);
    let axis = match hull.len() {
        0 | 1 => DVec2::X,
        2 => (hull[1] - hull[0]).normalize(),
        _ => calipers_best_axis(&hull),
    };
    let mut r = enclosing_rect_along(&local, axis);
    r.center += first;
    Some(r)
}

/// Direction of the hull edge whose edge-aligned bounding rectangle has the least area.
fn calipers_best_axis(hull: &[DVec2]) -> DVec2 {
    let n = hull.len();
    let at = |i: usize| hull[i % n];
    let edge = |i: usize| (at(i + 1) - at(i)).normalize();
    let e0 = edge(0);
    let n0 = e0.perp();
    // Initial extremes for edge 0: max along e, max along n (height), min along e.
    let argbest = |f: &dyn Fn(DVec2) -> f64| {
        (0..n).max_by(|&a, &b| f(hull[a]).total_cmp(&f(hull[b])).then(b.cmp(&a))).unwrap_or(0)
    };
    let mut j = argbest(&|p| p.dot(e0));
    let mut k = argbest(&|p| p.dot(n0));
    let mut l = argbest(&|p| -p.dot(e0));
    let mut best = (f64::INFINITY, e0);
    for i in 0..n {
        let e = edge(i);
        let nrm = e.perp();
        // Each caliper only moves forward (counter-clockwise) as the edge turns.
        for _ in 0..n {
            if at(j + 1).dot(e) > at(j).dot(e) { j += 1 } else { break }
        }
        for _ in 0..n {
            if at(k + 1).dot(nrm) > at(k).dot(nrm) { k += 1 } else { break }
        }
        for _ in 0..n {
            if at(l + 1).dot(e) < at(l).dot(e) { l += 1 } else { break }
        }
        let width = at(j).dot(e) - at(l).dot(e);
        let height = at(k).dot(nrm) - at(i).dot(nrm);
        let area = width * height;
        if area < best.0 {
            best = (area, e);
        }
    }
    best.1
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Reference: the minimum over every hull edge direction plus many sampled angles.
    fn brute_force_min_area(points: &[DVec2]) -> f64 {
        let hull = convex_hull(points);
        let mut best = f64::INFINITY;
        let mut dirs: Vec<DVec2> =
            (0..hull.len()).map(|i| (hull[(i + 1) % hull.len()] - hull[i]).normalize()).collect();
        dirs.extend((0..3600).map(|k| DVec2::from_angle(k as f64 * std::f64::consts::PI / 7200.0)));
        for d in dirs {
            if d.is_finite() {
                best = best.min(enclosing_rect_along(points, d).area());
            }
        }
        best
    }

    fn rect_points(angle: f64, w: f64, h: f64, c: DVec2) -> Vec<DVec2> {
        let a = DVec2::from_angle(angle);
        let b = a.perp();
        [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0), (0.3, -1.0), (0.0, 0.2)]
            .iter()
            .map(|&(x, y)| c + a * (x * w) + b * (y * h))
            .collect()
    }

    #[test]
    fn axis_aligned_and_degenerate() {
        let r = min_area_rect(&rect_points(0.0, 2.0, 1.0, DVec2::ZERO)).unwrap();
        assert!((r.area() - 8.0).abs() < 1e-12 && r.half.x >= r.half.y);
        let r = min_area_rect(&[DVec2::ONE; 3]).unwrap();
        assert_eq!(r.area(), 0.0);
        let r = min_area_rect(&[DVec2::ZERO, DVec2::new(3.0, 4.0), DVec2::new(1.5, 2.0)]).unwrap();
        assert!((r.half.x - 2.5).abs() < 1e-12 && r.half.y.abs() < 1e-12);
        assert!(min_area_rect(&[]).is_none());
    }

    #[test]
    fn rotated_rectangles_at_many_angles_are_found_exactly() {
        for k in 0..720 {
            let angle = k as f64 * std::f64::consts::TAU / 720.0 + 1e-3;
            for (w, h) in [(1.0, 1.0), (5.0, 0.01), (3.0, 2.0)] {
                let c = DVec2::new(1e4, -2e4);
                let pts = rect_points(angle, w, h, c);
                let r = min_area_rect(&pts).unwrap();
                let truth = 4.0 * w * h;
                assert!(
                    (r.area() - truth).abs() <= 1e-6 * truth,
                    "angle {angle} {w}x{h}: {} vs {truth}",
                    r.area()
                );
                for p in &pts {
                    assert!(r.contains(*p, 1e-9 * (w + h + c.length())));
                }
            }
        }
    }

    proptest! {
        #[test]
        fn encloses_and_matches_brute_force(
            pts in proptest::collection::vec((-50.0f64..50.0, -50.0f64..50.0), 1..60),
            angle in 0.0f64..std::f64::consts::TAU,
            stretch in 0.01f64..10.0,
        ) {
            let rot = DVec2::from_angle(angle);
            let points: Vec<DVec2> = pts.iter().map(|&(x, y)| rot.rotate(DVec2::new(x * stretch, y))).collect();
            let r = min_area_rect(&points).unwrap();
            let scale = points.iter().map(|p| p.length()).fold(1.0, f64::max);
            for p in &points {
                prop_assert!(r.contains(*p, 1e-9 * scale), "{p:?} outside {r:?}");
            }
            let reference = brute_force_min_area(&points);
            prop_assert!(r.area() <= reference * (1.0 + 1e-6) + 1e-12 * scale * scale, "{} > brute force {}", r.area(), reference);
        }

        #[test]
        fn rotated_rectangles_with_collinear_and_duplicate_points(
            angle in 0.0f64..std::f64::consts::TAU,
            w in 0.001f64..1000.0,
            h in 0.001f64..1000.0,
            n in 2usize..20,
        ) {
            let a = DVec2::from_angle(angle);
            let b = a.perp();
            let mut pts = Vec::new();
            for i in 0..=n {
                let t = i as f64 / n as f64 * 2.0 - 1.0;
                for (x, y) in [(t, -1.0), (t, 1.0), (-1.0, t), (1.0, t)] {
                    pts.push(a * (x * w) + b * (y * h));
                    pts.push(a * (x * w) + b * (y * h)); // duplicate
                }
            }
            let r = min_area_rect(&pts).unwrap();
            let truth = 4.0 * w * h;
            prop_assert!((r.area() - truth).abs() <= 1e-6 * truth, "{} vs {}", r.area(), truth);
        }
    }
}
