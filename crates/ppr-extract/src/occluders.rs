//! Potential occluders: per reflector, the other reflectors that may stand between a camera
//! and it.
//!
//! # The rule, and why it is conservative
//!
//! At run time a pixel of reflector A is tested with a ray from the camera (on A's
//! reflecting side) to a point of A's rectangle; another reflector B occludes it when the
//! ray meets B first. Every point of such a ray other than its end lies strictly on A's
//! reflecting side, so only the part of B that is strictly in front of A's plane matters.
//! A camera far enough away can put any such B in front of any point of A, however far B
//! is from A, so by default nothing is left out for being far:
//!
//! **B may occlude A iff some point of B is strictly in front of A's plane (signed
//! distance > ε, the distance tolerance, so coplanar neighbours are not occluders)** and,
//! only when a reach `r` is asked for, within distance `r` of A's rectangle.
//!
//! # The cap, and what it keeps
//!
//! The projection pass tests every listed occluder for every pixel a shape reflects, and in
//! a large level each floor has thousands of shapes in front of it (every wall of every
//! room), so lists are capped ([`OccluderRule::max_per_list`]). When more shapes qualify,
//! the list keeps those that look largest from A: ranked by `area(B) / (d² + area(B))`,
//! with `d` the exact distance from A's rectangle to the part of B in front of it (a
//! solid-angle measure bounded by 1; ties by index). A small shape far away is what a cap
//! drops first; a large wall far away outranks a small one. [`OccluderLists::capped`]
//! counts the lists that reached the cap, and the summary reports it.
//!
//! # The search
//!
//! An obvhs BVH over the shapes' boxes (`f32`, rounded outwards relative to a local
//! origin), each node knowing the largest area below it. Per shape A, a best-first search
//! over nodes ordered by an upper bound of the rank (largest area below, over the
//! box-to-box distance) skips nodes wholly behind A's plane or beyond the reach, and stops
//! when no node can beat the worst of a full list. With no cap it visits every node in
//! front: the exact set of the rule.
//!
//! A test compares this with a brute-force check over all pairs of random shape soups that
//! samples points on B densely: every pair the sampling finds must be listed.

use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::time::Duration;

use glam::{DVec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::builder::build_bvh2;
use ppr_format::Reflector;

pub use crate::occluder_geometry::{may_occlude, occlusion_distance};
use crate::occluder_geometry::{occlusion_distance_of, within_reach};
use crate::parallel_map::map_ranges;

/// What the occluder lists hold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OccluderRule {
    /// Points within this distance of a reflector's plane are not in front of it, metres.
    pub epsilon: f64,
    /// How far from a reflector occluders are looked for, metres (infinite: anywhere).
    pub reach: f64,
    /// Most occluders per list (`usize::MAX`: no cap).
    pub max_per_list: usize,
}

/// Occluder lists and what the cap did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OccluderLists {
    /// Per shape, the indices of its occluders, ascending.
    pub lists: Vec<Vec<u32>>,
    /// Lists that reached the cap (more shapes may qualify than they hold).
    pub capped: usize,
}

/// Every occluder within `reach` of every shape, no cap (indices into `shapes`, ascending).
/// `origin` is a point near the shapes (bounding boxes are stored in `f32` relative to it).
pub fn occluder_lists(shapes: &[Reflector], origin: DVec3, epsilon: f64, reach: f64) -> Vec<Vec<u32>> {
    ranked_occluder_lists(shapes, origin, &OccluderRule { epsilon, reach, max_per_list: usize::MAX }).lists
}

/// The occluder lists of `rule` (see the module docs), on one thread.
pub fn ranked_occluder_lists(shapes: &[Reflector], origin: DVec3, rule: &OccluderRule) -> OccluderLists {
    ranked_occluder_lists_threaded(shapes, origin, rule, 1)
}

/// [`ranked_occluder_lists`] on up to `threads` threads; the same lists for any count.
pub fn ranked_occluder_lists_threaded(
    shapes: &[Reflector],
    origin: DVec3,
    rule: &OccluderRule,
    threads: usize,
) -> OccluderLists {
    if shapes.is_empty() {
        return OccluderLists::default();
    }
    let boxes: Vec<Aabb> = shapes.iter().map(|s| outward_aabb(&s.corners(), 0.0, origin)).collect();
    let bvh = build_bvh2(&boxes, obvhs::BvhBuildParams::fast_build(), &mut Duration::default());
    let areas: Vec<f64> = shapes.iter().map(Reflector::area).collect();
    let corners: Vec<[DVec3; 4]> = shapes.iter().map(Reflector::corners).collect();
    let corner_boxes: Vec<(DVec3, DVec3)> = corners.iter().map(|c| corner_box(c, origin)).collect();
    let node_area = largest_area_below(&bvh, &areas);
    let extents = Extents { areas: &areas, boxes: &corner_boxes, corners: &corners };
    let lists = map_ranges(shapes.len(), threads, |range| {
        let mut search = Search::default();
        range.map(|a| search.run(a, &shapes[a], shapes, &extents, &bvh, &node_area, origin, rule)).collect()
    });
    let capped = lists.iter().filter(|l| l.len() >= rule.max_per_list).count();
    OccluderLists { lists, capped }
}

/// Per shape, its area and its box relative to the origin (`f64`).
#[derive(Clone, Copy)]
struct Extents<'a> {
    areas: &'a [f64],
    boxes: &'a [(DVec3, DVec3)],
    corners: &'a [[DVec3; 4]],
}

/// The box of `corners`, relative to `origin`.
fn corner_box(corners: &[DVec3], origin: DVec3) -> (DVec3, DVec3) {
    let lo = corners.iter().fold(DVec3::splat(f64::INFINITY), |m, &p| m.min(p)) - origin;
    let hi = corners.iter().fold(DVec3::splat(f64::NEG_INFINITY), |m, &p| m.max(p)) - origin;
    (lo, hi)
}

/// Upper bound of the rank of anything in the box `[bmin, bmax]` with largest area `area`,
/// for the shape with box `[lo, hi]` and plane `normal · x = offset`; `None` when nothing
/// in the box is in front of the plane beyond `rule.epsilon` or within the reach.
#[allow(clippy::too_many_arguments)]
fn rank_bound(
    (bmin, bmax): (DVec3, DVec3),
    area: f64,
    (lo, hi): (DVec3, DVec3),
    normal: DVec3,
    offset: f64,
    rule: &OccluderRule,
) -> Option<f64> {
    // The box corner farthest along the normal.
    let far = DVec3::select(normal.cmpge(DVec3::ZERO), bmax, bmin);
    let rounding = 1e-12 * (far.length() + offset.abs());
    if far.dot(normal) - offset <= rule.epsilon - rounding {
        return None;
    }
    let gap = (bmin - hi).max(lo - bmax).max(DVec3::ZERO);
    let d = gap.length() * (1.0 - 1e-9);
    if d > rule.reach * (1.0 + 1e-9) {
        return None;
    }
    Some(rank(area, d) * (1.0 + 1e-9))
}

/// Per BVH node, the largest shape area below it.
fn largest_area_below(bvh: &Bvh2, areas: &[f64]) -> Vec<f64> {
    let mut order = Vec::with_capacity(bvh.nodes.len());
    let mut stack = vec![0u32];
    while let Some(n) = stack.pop() {
        order.push(n);
        let node = &bvh.nodes[n as usize];
        if node.prim_count == 0 {
            stack.push(node.first_index);
            stack.push(node.first_index + 1);
        }
    }
    let mut below = vec![0.0f64; bvh.nodes.len()];
    for &n in order.iter().rev() {
        let node = &bvh.nodes[n as usize];
        below[n as usize] = if node.prim_count == 0 {
            below[node.first_index as usize].max(below[node.first_index as usize + 1])
        } else {
            (node.first_index..node.first_index + node.prim_count)
                .map(|k| areas[bvh.primitive_indices[k as usize] as usize])
                .fold(0.0, f64::max)
        };
    }
    below
}

/// The rank of an occluder of area `area` at distance `d`: larger is kept first.
fn rank(area: f64, d: f64) -> f64 {
    let denom = d * d + area;
    if denom > 0.0 { area / denom } else { 0.0 }
}

/// A candidate or a node, ordered by rank, then by lower index first.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Ranked {
    rank: f64,
    index: u32,
}

impl Eq for Ranked {}
impl Ord for Ranked {
    fn cmp(&self, other: &Self) -> Ordering {
        self.rank.total_cmp(&other.rank).then(other.index.cmp(&self.index))
    }
}
impl PartialOrd for Ranked {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Reused buffers of the per-shape search.
#[derive(Default)]
struct Search {
    nodes: BinaryHeap<Ranked>,
    /// The best occluders so far, worst on top.
    best: BinaryHeap<std::cmp::Reverse<Ranked>>,
}

impl Search {
    #[allow(clippy::too_many_arguments)]
    fn run(
        &mut self,
        a: usize,
        shape: &Reflector,
        shapes: &[Reflector],
        extents: &Extents,
        bvh: &Bvh2,
        node_area: &[f64],
        origin: DVec3,
        rule: &OccluderRule,
    ) -> Vec<u32> {
        self.nodes.clear();
        self.best.clear();
        let own = extents.boxes[a];
        let (normal, offset) = (shape.normal, shape.normal.dot(shape.center - origin));
        let bound = |n: u32| -> Option<f64> {
            let b = &bvh.nodes[n as usize].aabb;
            rank_bound((b.min.as_dvec3(), b.max.as_dvec3()), node_area[n as usize], own, normal, offset, rule)
        };
        if let Some(r) = bound(0) {
            self.nodes.push(Ranked { rank: r, index: 0 });
        }
        let full = |best: &BinaryHeap<std::cmp::Reverse<Ranked>>| best.len() >= rule.max_per_list;
        while let Some(top) = self.nodes.pop() {
            if full(&self.best) && self.best.peek().is_some_and(|w| top.rank < w.0.rank) {
                break;
            }
            let node = &bvh.nodes[top.index as usize];
            if node.prim_count == 0 {
                for child in [node.first_index, node.first_index + 1] {
                    if let Some(r) = bound(child) {
                        self.nodes.push(Ranked { rank: r, index: child });
                    }
                }
                continue;
            }
            for k in node.first_index..node.first_index + node.prim_count {
                let b = bvh.primitive_indices[k as usize] as usize;
                if b == a {
                    continue;
                }
                // Cheap rejections on B's own box before the exact distance.
                let Some(r) = rank_bound(extents.boxes[b], extents.areas[b], own, normal, offset, rule)
                else {
                    continue;
                };
                if full(&self.best) && self.best.peek().is_some_and(|w| r < w.0.rank) {
                    continue;
                }
                let Some(d) = occlusion_distance_of(
                    shape,
                    &extents.corners[a],
                    &shapes[b],
                    &extents.corners[b],
                    rule.epsilon,
                ) else {
                    continue;
                };
                if !within_reach(shape, &shapes[b], d, rule.reach) {
                    continue;
                }
                let candidate = Ranked { rank: rank(extents.areas[b], d), index: b as u32 };
                if !full(&self.best) {
                    self.best.push(std::cmp::Reverse(candidate));
                } else if self.best.peek().is_some_and(|w| candidate > w.0) {
                    self.best.pop();
                    self.best.push(std::cmp::Reverse(candidate));
                }
            }
        }
        let mut list: Vec<u32> = self.best.drain().map(|r| r.0.index).collect();
        list.sort_unstable();
        list
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DQuat, DVec2};
    use ppr_format::ReflectorKind;
    use proptest::prelude::*;

    fn shape(center: DVec3, rot: DQuat, half: DVec2) -> Reflector {
        Reflector::new(0, "s", ReflectorKind::Opaque, center, rot * DVec3::Y, rot * DVec3::X, half)
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
