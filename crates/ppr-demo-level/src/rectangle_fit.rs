//! The minimum-area rectangle enclosing a set of coplanar points (convex hull + rotating calipers).

use glam::{DVec2, DVec3};

/// A rectangle in world space. Invariants: `axis_u`, `axis_v`, `normal` are unit and
/// orthogonal with `axis_u × axis_v = normal`; `half_extents.x >= half_extents.y > 0`;
/// the component of `axis_u` with the largest magnitude is positive.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rectangle {
    pub center: DVec3,
    pub axis_u: DVec3,
    pub axis_v: DVec3,
    pub half_extents: DVec2,
    pub normal: DVec3,
}

impl Rectangle {
    pub fn area(&self) -> f64 {
        4.0 * self.half_extents.x * self.half_extents.y
    }

    /// Corners counter-clockwise seen from the reflecting side, starting at `-u -v`.
    pub fn corners(&self) -> [DVec3; 4] {
        let u = self.axis_u * self.half_extents.x;
        let v = self.axis_v * self.half_extents.y;
        [self.center - u - v, self.center + u - v, self.center + u + v, self.center - u + v]
    }
}

/// The smallest-area rectangle in the plane with unit `normal` that encloses `points`
/// (which lie in one such plane); the rectangle's centre sits at their mean height along
/// the normal. `None` with fewer than three non-collinear points.
pub fn minimum_area_rectangle(points: &[DVec3], normal: DVec3) -> Option<Rectangle> {
    let origin = *points.first()?;
    let (e1, e2) = plane_basis(normal);
    let flat: Vec<DVec2> =
        points.iter().map(|p| DVec2::new((*p - origin).dot(e1), (*p - origin).dot(e2))).collect();
    let height = points.iter().map(|p| (*p - origin).dot(normal)).sum::<f64>() / points.len() as f64;
    let hull = convex_hull(&flat);
    if hull.len() < 3 {
        return None;
    }

    // The best rectangle has a side along a hull edge; try each.
    let mut best: Option<(f64, DVec2, DVec2, DVec2)> = None; // (area, dir, min, max)
    for (i, a) in hull.iter().enumerate() {
        let edge = hull[(i + 1) % hull.len()] - *a;
        let dir = edge.normalize();
        let perp = dir.perp();
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for p in &hull {
            let local = DVec2::new(p.dot(dir), p.dot(perp));
            lo = lo.min(local);
            hi = hi.max(local);
        }
        let area = (hi.x - lo.x) * (hi.y - lo.y);
        // A strictly smaller area (beyond rounding) replaces the best; ties keep the first.
        if best.is_none_or(|(best_area, ..)| area < best_area * (1.0 - 1e-12)) {
            best = Some((area, dir, lo, hi));
        }
    }
    let (_, dir, lo, hi) = best?;
    let perp = dir.perp();
    let mid = (lo + hi) * 0.5;
    let centre_2d = dir * mid.x + perp * mid.y;
    let center = origin + e1 * centre_2d.x + e2 * centre_2d.y + normal * height;
    let side_a = (e1 * dir.x + e2 * dir.y).normalize();
    let half = (hi - lo) * 0.5;
    Some(canonical(center, side_a, half, normal))
}

/// Puts the longer side first, makes `axis_u`'s largest component positive and sets
/// `axis_v = normal × axis_u` (so `axis_u × axis_v = normal`).
fn canonical(center: DVec3, side_a: DVec3, half: DVec2, normal: DVec3) -> Rectangle {
    let side_b = normal.cross(side_a);
    let (mut axis_u, half_extents) =
        if half.y > half.x * (1.0 + 1e-9) { (side_b, DVec2::new(half.y, half.x)) } else { (side_a, half) };
    let largest = axis_u.abs().max_element();
    let first_largest = axis_u.to_array().into_iter().find(|c| c.abs() >= largest * (1.0 - 1e-9));
    if first_largest.is_some_and(|c| c < 0.0) {
        axis_u = -axis_u;
    }
    Rectangle { center, axis_u, axis_v: normal.cross(axis_u), half_extents, normal }
}

/// Two unit vectors spanning the plane orthogonal to the unit `normal`.
fn plane_basis(normal: DVec3) -> (DVec3, DVec3) {
    let helper = if normal.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let e1 = helper.cross(normal).normalize();
    (e1, normal.cross(e1))
}

/// Convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    sorted.dedup();
    if sorted.len() < 3 {
        return sorted;
    }
    let scale = sorted.iter().map(|p| p.abs().max_element()).fold(1.0, f64::max);
    let turns_left = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o) > 1e-12 * scale * scale;
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * sorted.len());
    for pass in [sorted.clone(), sorted.into_iter().rev().collect()] {
        let start = hull.len();
        for p in pass {
            while hull.len() >= start + 2 && !turns_left(hull[hull.len() - 2], hull[hull.len() - 1], p) {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(points: &[DVec3], normal: DVec3, center: DVec3, half_extents: DVec2) {
        let rect = minimum_area_rectangle(points, normal).expect("enough points");
        assert!((rect.center - center).length() < 1e-9, "centre {:?}", rect.center);
        assert!((rect.half_extents - half_extents).length() < 1e-9, "extents {:?}", rect.half_extents);
        assert!((rect.axis_u.cross(rect.axis_v) - normal).length() < 1e-12);
        for p in points {
            let d = *p - rect.center;
            assert!(d.dot(rect.axis_u).abs() <= rect.half_extents.x + 1e-9);
            assert!(d.dot(rect.axis_v).abs() <= rect.half_extents.y + 1e-9);
        }
    }

    #[test]
    fn axis_aligned_rectangle_is_itself() {
        let pts =
            [(0.0, 0.0), (4.0, 0.0), (4.0, 2.0), (0.0, 2.0), (2.0, 1.0)].map(|(x, z)| DVec3::new(x, 1.0, z));
        check(&pts, DVec3::Y, DVec3::new(2.0, 1.0, 1.0), DVec2::new(2.0, 1.0));
    }

    #[test]
    fn rotated_rectangle_is_found() {
        let (u, v) = (DVec3::new(0.6, 0.0, 0.8), DVec3::new(-0.8, 0.0, 0.6));
        let c = DVec3::new(1.0, 0.0, -2.0);
        let pts = [c + u * 3.0 + v, c - u * 3.0 + v, c - u * 3.0 - v, c + u * 3.0 - v, c + u];
        check(&pts, DVec3::Y, c, DVec2::new(3.0, 1.0));
    }

    #[test]
    fn l_shape_gets_its_bounding_box() {
        let pts = [(0.0, 0.0), (6.0, 0.0), (6.0, 2.0), (2.0, 2.0), (2.0, 5.0), (0.0, 5.0)]
            .map(|(x, y)| DVec3::new(x, y, 0.0));
        check(&pts, DVec3::Z, DVec3::new(3.0, 2.5, 0.0), DVec2::new(3.0, 2.5));
    }

    #[test]
    fn axis_u_is_long_and_positive() {
        let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 3.0), (0.0, 3.0)].map(|(x, y)| DVec3::new(x, y, 0.0));
        let rect = minimum_area_rectangle(&pts, DVec3::Z).expect("enough points");
        assert_eq!(rect.axis_u, DVec3::Y);
        assert_eq!(rect.axis_v, DVec3::new(-1.0, 0.0, 0.0));
    }
}
