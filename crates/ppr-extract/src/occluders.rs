//! Potential occluders: per reflector, the other reflectors that may stand between a camera
//! and it.
//!
//! # The rule, and why it is conservative
//!
//! At run time a pixel of reflector A is tested with a ray from the camera (on A's
//! reflecting side) to a point of A's rectangle; another reflector B occludes it when the
//! ray meets B first. Every point of such a ray other than its end lies strictly on A's
//! reflecting side, so only the part of B that is strictly in front of A's plane matters,
//! and with reach `r` we only care about occlusion within distance `r` of A. Hence:
//!
//! **B may occlude A iff some point of B is strictly in front of A's plane (signed
//! distance > ε, the distance tolerance, so coplanar neighbours are not occluders) and
//! within distance `r` of A's rectangle.**
//!
//! The implementation decides exactly that set, and errs only towards listing more:
//! 1. the BVH query (obvhs `Bvh2::aabb_traverse`) uses A's rectangle's bounding box grown
//!    by `r` in every direction, which contains every point within `r` of the rectangle,
//!    against B's bounding box; both boxes are rounded outwards when narrowed to `f32`, so
//!    no candidate is lost to rounding;
//! 2. B's rectangle is clipped to the closed half-space `signed distance ≥ ε` of A (that is
//!    where the points strictly in front beyond ε lie; B is convex so clipping is exact),
//!    and the clipped polygon's exact distance to A's rectangle (convex polygons that do
//!    not intersect, since one lies strictly in front of the other's plane: the minimum of
//!    vertex–polygon and edge–edge distances) is compared with `r` plus a relative slack
//!    of 1e-9 for rounding.
//!
//! A test compares this with a brute-force check over all pairs of random shape soups that
//! samples points on B densely: every pair the sampling finds must be listed.

use std::time::Duration;

use glam::{DVec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::bvh2::builder::build_bvh2;
use ppr_format::Reflector;

/// Occluder lists (indices into `shapes`, ascending) for every shape.
/// `origin` is a point near the shapes (bounding boxes are stored in `f32` relative to it).
pub fn occluder_lists(shapes: &[Reflector], origin: DVec3, epsilon: f64, reach: f64) -> Vec<Vec<u32>> {
    if shapes.is_empty() {
        return Vec::new();
    }
    let boxes: Vec<Aabb> = shapes.iter().map(|s| outward_aabb(&s.corners(), 0.0, origin)).collect();
    let bvh = build_bvh2(&boxes, obvhs::BvhBuildParams::fast_build(), &mut Duration::default());
    shapes
        .iter()
        .enumerate()
        .map(|(a, shape)| {
            let query = outward_aabb(&shape.corners(), reach, origin);
            let mut list = Vec::new();
            bvh.aabb_traverse(query, |bvh, node_index| {
                let node = &bvh.nodes[node_index as usize];
                for k in node.first_index..node.first_index + node.prim_count {
                    let b = bvh.primitive_indices[k as usize] as usize;
                    if b != a && may_occlude(shape, &shapes[b], epsilon, reach) {
                        list.push(b as u32);
                    }
                }
                true
            });
            list.sort_unstable();
            list.dedup();
            list
        })
        .collect()
}

/// The `f32` box around `points` grown by `grow`, relative to `origin`, rounded outwards.
fn outward_aabb(points: &[DVec3], grow: f64, origin: DVec3) -> Aabb {
    let lo = points.iter().fold(DVec3::splat(f64::INFINITY), |m, &p| m.min(p)) - origin - DVec3::splat(grow);
    let hi =
        points.iter().fold(DVec3::splat(f64::NEG_INFINITY), |m, &p| m.max(p)) - origin + DVec3::splat(grow);
    let down = |x: f64| {
        let f = x as f32;
        if f64::from(f) > x { f.next_down() } else { f }
    };
    let up = |x: f64| {
        let f = x as f32;
        if f64::from(f) < x { f.next_up() } else { f }
    };
    Aabb::new(Vec3A::new(down(lo.x), down(lo.y), down(lo.z)), Vec3A::new(up(hi.x), up(hi.y), up(hi.z)))
}

/// The rule of the module docs for one ordered pair: may `b` occlude `a`?
pub fn may_occlude(a: &Reflector, b: &Reflector, epsilon: f64, reach: f64) -> bool {
    let corners = b.corners();
    if corners.iter().all(|&p| a.signed_distance(p) <= epsilon) {
        return false;
    }
    // Quick accept: a corner strictly in front and within reach is a witness by itself.
    let within = |p: DVec3| {
        let l = a.local(p);
        let dx = (l.x.abs() - a.half_extents.x).max(0.0);
        let dy = (l.y.abs() - a.half_extents.y).max(0.0);
        dx * dx + dy * dy + l.z * l.z <= reach * reach
    };
    if corners.iter().any(|&p| a.signed_distance(p) > epsilon && within(p)) {
        return true;
    }
    let front = clip_front(&corners, a, epsilon);
    let rect = a.corners();
    let slack =
        1e-9 * (reach + a.half_extents.length() + b.half_extents.length() + (a.center - b.center).length());
    polygon_distance(&front, b.normal, &rect, a.normal) <= reach + slack
}

/// The part of the convex polygon `poly` where `a.signed_distance >= epsilon`.
fn clip_front(poly: &[DVec3], a: &Reflector, epsilon: f64) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for i in 0..poly.len() {
        let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
        let (sp, sq) = (a.signed_distance(p) - epsilon, a.signed_distance(q) - epsilon);
        if sp >= 0.0 {
            out.push(p);
        }
        if (sp >= 0.0) != (sq >= 0.0) {
            out.push(p.lerp(q, sp / (sp - sq)));
        }
    }
    out
}

/// Distance between two convex planar polygons (counter-clockwise about their normals)
/// that do not intersect.
fn polygon_distance(p: &[DVec3], np: DVec3, q: &[DVec3], nq: DVec3) -> f64 {
    let mut best = f64::INFINITY;
    for &v in p {
        best = best.min(point_polygon_distance(v, q, nq));
    }
    for &v in q {
        best = best.min(point_polygon_distance(v, p, np));
    }
    for i in 0..p.len() {
        for j in 0..q.len() {
            let d = segment_distance(p[i], p[(i + 1) % p.len()], q[j], q[(j + 1) % q.len()]);
            best = best.min(d);
        }
    }
    best
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

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DQuat, DVec2};
    use ppr_format::ReflectorKind;
    use proptest::prelude::*;

    fn shape(center: DVec3, rot: DQuat, half: DVec2) -> Reflector {
        Reflector::new(0, "s", ReflectorKind::Opaque, center, rot * DVec3::X, rot * DVec3::NEG_Z, half)
    }

    /// Ground truth by sampling: does some sampled point of `b` lie strictly in front of
    /// `a` (beyond ε) and within `reach` of `a`'s rectangle?
    fn sampled(a: &Reflector, b: &Reflector, eps: f64, reach: f64) -> bool {
        let n = 24;
        for i in 0..=n {
            for j in 0..=n {
                let s = i as f64 / n as f64 * 2.0 - 1.0;
                let t = j as f64 / n as f64 * 2.0 - 1.0;
                let p = b.center + b.axis_u * (s * b.half_extents.x) + b.axis_v * (t * b.half_extents.y);
                if a.signed_distance(p) > eps {
                    let l = a.local(p);
                    let dx = (l.x.abs() - a.half_extents.x).max(0.0);
                    let dy = (l.y.abs() - a.half_extents.y).max(0.0);
                    if (dx * dx + dy * dy + l.z * l.z).sqrt() <= reach {
                        return true;
                    }
                }
            }
        }
        false
    }

    #[test]
    fn simple_cases() {
        let floor = shape(DVec3::ZERO, DQuat::IDENTITY, DVec2::new(2.0, 2.0));
        let shelf = shape(DVec3::new(0.0, 1.0, 0.0), DQuat::IDENTITY, DVec2::new(0.5, 0.5));
        let wall = shape(
            DVec3::new(0.0, 1.0, -2.0),
            DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2),
            DVec2::new(2.0, 1.0),
        );
        let below = shape(DVec3::new(0.0, -1.0, 0.0), DQuat::IDENTITY, DVec2::ONE);
        let beside = shape(DVec3::new(4.5, 0.0, 0.0), DQuat::IDENTITY, DVec2::ONE);
        let far = shape(DVec3::new(0.0, 10.0, 0.0), DQuat::IDENTITY, DVec2::ONE);
        assert!(floor.normal.y > 0.99);
        let eps = 1e-6;
        assert!(may_occlude(&floor, &shelf, eps, 2.0));
        assert!(may_occlude(&floor, &wall, eps, 2.0), "a wall standing on the floor");
        assert!(!may_occlude(&floor, &below, eps, 2.0));
        assert!(!may_occlude(&floor, &beside, eps, 2.0), "coplanar neighbour");
        assert!(!may_occlude(&floor, &far, eps, 2.0));
        assert!(may_occlude(&floor, &far, eps, 10.0));
        let lists = occluder_lists(&[floor, shelf, wall, below, beside, far], DVec3::ZERO, eps, 2.0);
        assert_eq!(lists[0], vec![1, 2]);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn never_misses_an_occluder_on_random_soups(
            seeds in proptest::collection::vec(
                ((-5.0f64..5.0, -5.0f64..5.0, -5.0f64..5.0), (-3.2f64..3.2, -1.6f64..1.6, -3.2f64..3.2), (0.05f64..3.0, 0.05f64..3.0)),
                2..40),
            reach in 0.1f64..6.0,
            far in prop_oneof![Just(0.0), Just(1e4)],
        ) {
            let offset = DVec3::new(far, -far, far * 0.5);
            let shapes: Vec<Reflector> = seeds
                .iter()
                .map(|&((x, y, z), (a, b, c), (w, h))| {
                    shape(DVec3::new(x, y, z) + offset, DQuat::from_euler(glam::EulerRot::YXZ, a, b, c), DVec2::new(w, h))
                })
                .collect();
            let eps = 1e-6;
            let lists = occluder_lists(&shapes, offset, eps, reach);
            for a in 0..shapes.len() {
                // The BVH finds exactly what the rule over all pairs finds ...
                let all_pairs: Vec<u32> = (0..shapes.len())
                    .filter(|&b| b != a && may_occlude(&shapes[a], &shapes[b], eps, reach))
                    .map(|b| b as u32)
                    .collect();
                prop_assert_eq!(&lists[a], &all_pairs);
                // ... and the rule never misses a pair that sampling proves.
                for b in 0..shapes.len() {
                    if b != a && sampled(&shapes[a], &shapes[b], eps, reach) {
                        prop_assert!(lists[a].contains(&(b as u32)), "{} misses occluder {}", a, b);
                    }
                }
            }
        }
    }
}
