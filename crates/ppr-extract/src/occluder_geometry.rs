//! The occluder rule's geometry: whether one rectangle has a part strictly in front of
//! another's plane, and how far that part is from the other rectangle (exact distances
//! between convex planar polygons).

use glam::DVec3;
use ppr_format::Reflector;

/// The rule of the [`crate::occluders`] docs for one ordered pair: may `b` occlude `a`
/// within `reach` (infinite: anywhere in front)?
pub fn may_occlude(a: &Reflector, b: &Reflector, epsilon: f64, reach: f64) -> bool {
    occlusion_distance(a, b, epsilon).is_some_and(|d| within_reach(a, b, d, reach))
}

/// Whether distance `d` between `a` and `b` is within `reach`, with a relative slack of 1e-9
/// of their sizes and distance for rounding.
pub(crate) fn within_reach(a: &Reflector, b: &Reflector, d: f64, reach: f64) -> bool {
    let slack = 1e-9 * (a.half_extents.length() + b.half_extents.length() + (a.center - b.center).length());
    d <= reach + slack
}

/// The distance from `a`'s rectangle to the part of `b` strictly in front of `a`'s plane
/// (signed distance > `epsilon`), or `None` when no part of `b` is in front.
pub fn occlusion_distance(a: &Reflector, b: &Reflector, epsilon: f64) -> Option<f64> {
    occlusion_distance_of(a, &a.corners(), b, &b.corners(), epsilon)
}

/// [`occlusion_distance`] with both rectangles' corners given.
pub(crate) fn occlusion_distance_of(
    a: &Reflector,
    a_corners: &[DVec3; 4],
    b: &Reflector,
    b_corners: &[DVec3; 4],
    epsilon: f64,
) -> Option<f64> {
    if b_corners.iter().all(|&p| a.signed_distance(p) <= epsilon) {
        return None;
    }
    let (front, n) = clip_front(b_corners, a, epsilon);
    Some(polygon_distance(&front[..n], b.normal, a_corners, a.normal))
}

/// The part of the rectangle `poly` where `a.signed_distance >= epsilon`: up to eight
/// vertices and their count (a quad clipped by a plane has at most five).
fn clip_front(poly: &[DVec3; 4], a: &Reflector, epsilon: f64) -> ([DVec3; 8], usize) {
    let mut out = [DVec3::ZERO; 8];
    let mut n = 0;
    for i in 0..poly.len() {
        let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
        let (sp, sq) = (a.signed_distance(p) - epsilon, a.signed_distance(q) - epsilon);
        if sp >= 0.0 {
            out[n] = p;
            n += 1;
        }
        if (sp >= 0.0) != (sq >= 0.0) {
            out[n] = p.lerp(q, sp / (sp - sq));
            n += 1;
        }
    }
    (out, n)
}

/// Distance between two convex planar polygons (counter-clockwise about their normals)
/// that do not intersect: the least of the vertex-to-polygon and edge-to-edge distances.
/// A candidate whose boxes are farther apart than the best so far (by more than rounding)
/// cannot be the least and is not computed: the result is the same, bit for bit.
fn polygon_distance(p: &[DVec3], np: DVec3, q: &[DVec3], nq: DVec3) -> f64 {
    let bounds = |s: &[DVec3]| {
        s.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), &v| (l.min(v), h.max(v)))
    };
    let ((pl, ph), (ql, qh)) = (bounds(p), bounds(q));
    // Rounding of the computed distances and of the box gaps, with a wide margin.
    let size = pl.abs().max(ph.abs()).max(ql.abs()).max(qh.abs()).max_element();
    let slack = 1e-9 * size;
    let beyond = |gap: f64, best: f64| gap > best + slack + 1e-9 * best;
    let mut best = f64::INFINITY;
    for &v in p {
        if !beyond(box_gap((v, v), (ql, qh)), best) {
            best = best.min(point_polygon_distance(v, q, nq));
        }
    }
    for &v in q {
        if !beyond(box_gap((v, v), (pl, ph)), best) {
            best = best.min(point_polygon_distance(v, p, np));
        }
    }
    for i in 0..p.len() {
        let (p1, p2) = (p[i], p[(i + 1) % p.len()]);
        let pb = (p1.min(p2), p1.max(p2));
        if beyond(box_gap(pb, (ql, qh)), best) {
            continue;
        }
        for j in 0..q.len() {
            let (q1, q2) = (q[j], q[(j + 1) % q.len()]);
            if !beyond(box_gap(pb, (q1.min(q2), q1.max(q2))), best) {
                best = best.min(segment_distance(p1, p2, q1, q2));
            }
        }
    }
    best
}

/// Distance between the boxes `[al, ah]` and `[bl, bh]` (0 when they overlap).
fn box_gap((al, ah): (DVec3, DVec3), (bl, bh): (DVec3, DVec3)) -> f64 {
    (bl - ah).max(al - bh).max(DVec3::ZERO).length()
}

/// Distance from `x` to a convex polygon with normal `n`.
fn point_polygon_distance(x: DVec3, poly: &[DVec3], n: DVec3) -> f64 {
    if poly.len() >= 3 {
        let inside = (0..poly.len()).all(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            (b - a).cross(x - a).dot(n) >= 0.0
        });
        if inside {
            return (x - poly[0]).dot(n).abs();
        }
    }
    (0..poly.len())
        .map(|i| segment_distance(x, x, poly[i], poly[(i + 1) % poly.len()]))
        .fold(f64::INFINITY, f64::min)
}

/// Distance between segments `p1 p2` and `q1 q2` (Ericson, 5.1.9; points allowed).
fn segment_distance(p1: DVec3, p2: DVec3, q1: DVec3, q2: DVec3) -> f64 {
    let (d1, d2, r) = (p2 - p1, q2 - q1, p1 - q1);
    let (a, e, f) = (d1.length_squared(), d2.length_squared(), d2.dot(r));
    let tiny = 1e-300;
    let (s, t) = if a <= tiny && e <= tiny {
        (0.0, 0.0)
    } else if a <= tiny {
        (0.0, (f / e).clamp(0.0, 1.0))
    } else {
        let c = d1.dot(r);
        if e <= tiny {
            ((-c / a).clamp(0.0, 1.0), 0.0)
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let mut s = if denom > 0.0 { ((b * f - c * e) / denom).clamp(0.0, 1.0) } else { 0.0 };
            let mut t = (b * s + f) / e;
            if t < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            }
            (s, t)
        }
    };
    ((p1 + d1 * s) - (q1 + d2 * t)).length()
}
