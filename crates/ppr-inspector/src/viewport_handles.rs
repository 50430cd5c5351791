//! Handles on the selected rectangle: where they are, and the placement a drag gives.
//! Coordinates are in the rectangle's own (u, v) frame at the start of the drag.

use glam::{DVec2, DVec3};
use ppr_format::Reflector;

use crate::reflector_geometry::{Placement, placement_of};

/// Smallest half extent a handle drag makes, metres (a numeric field can go lower and be refused).
pub const MIN_HALF_EXTENT: f64 = 1e-3;

/// A handle of the selected rectangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Handle {
    /// Moves the rectangle in its plane.
    Center,
    /// A corner (signs along u and v); the opposite corner stays.
    Corner(i8, i8),
    /// The middle of an edge: along u (`true`) or v, on side `±1`; the opposite edge stays.
    Edge(bool, i8),
    /// Turns the rectangle about its normal.
    Rotate,
}

/// Every handle of `r` with its world position.
pub fn handle_positions(r: &Reflector) -> Vec<(Handle, DVec3)> {
    let at =
        |x: f64, y: f64| r.center + r.axis_u * (x * r.half_extents.x) + r.axis_v * (y * r.half_extents.y);
    let mut out = vec![(Handle::Center, r.center)];
    for (su, sv) in [(-1, -1), (1, -1), (1, 1), (-1, 1)] {
        out.push((Handle::Corner(su, sv), at(f64::from(su), f64::from(sv))));
    }
    for s in [-1, 1] {
        out.push((Handle::Edge(true, s), at(f64::from(s), 0.0)));
        out.push((Handle::Edge(false, s), at(0.0, f64::from(s))));
    }
    let reach = r.half_extents.x + 0.25 * r.half_extents.min_element().max(0.05);
    out.push((Handle::Rotate, r.center + r.axis_u * reach));
    out
}

/// Where the ray (origin, unit `dir`) meets `r`'s plane, in `r`'s (u, v) frame.
pub fn plane_hit(r: &Reflector, origin: DVec3, dir: DVec3) -> Option<DVec2> {
    let denom = r.normal.dot(dir);
    if denom.abs() < 1e-9 {
        return None;
    }
    let t = r.normal.dot(r.center - origin) / denom;
    if !(t > 0.0 && t.is_finite()) {
        return None;
    }
    let d = origin + dir * t - r.center;
    Some(DVec2::new(d.dot(r.axis_u), d.dot(r.axis_v)))
}

/// The placement after dragging `handle` of `start` from `grab` to `now` (both in the
/// start rectangle's frame).
pub fn dragged_placement(start: &Reflector, handle: Handle, grab: DVec2, now: DVec2) -> Placement {
    let p = placement_of(start);
    let h = start.half_extents;
    let delta = now - grab;
    let lift = |q: DVec2| start.center + start.axis_u * q.x + start.axis_v * q.y;
    let span = |moving: f64, fixed: f64| {
        let (lo, hi) = (moving.min(fixed), moving.max(fixed));
        let half = ((hi - lo) * 0.5).max(MIN_HALF_EXTENT);
        ((lo + hi) * 0.5, half)
    };
    match handle {
        Handle::Center => Placement { center: lift(delta), ..p },
        Handle::Corner(su, sv) => {
            let (su, sv) = (f64::from(su), f64::from(sv));
            let (cx, hx) = span(su * h.x + delta.x, -su * h.x);
            let (cy, hy) = span(sv * h.y + delta.y, -sv * h.y);
            Placement { center: lift(DVec2::new(cx, cy)), half_extents: DVec2::new(hx, hy), ..p }
        }
        Handle::Edge(true, s) => {
            let s = f64::from(s);
            let (cx, hx) = span(s * h.x + delta.x, -s * h.x);
            Placement { center: lift(DVec2::new(cx, 0.0)), half_extents: DVec2::new(hx, h.y), ..p }
        }
        Handle::Edge(false, s) => {
            let s = f64::from(s);
            let (cy, hy) = span(s * h.y + delta.y, -s * h.y);
            Placement { center: lift(DVec2::new(0.0, cy)), half_extents: DVec2::new(h.x, hy), ..p }
        }
        Handle::Rotate => {
            let turn = now.y.atan2(now.x) - grab.y.atan2(grab.x);
            // The frame's angle grows from u towards normal × reference; u × v decides the sign.
            let sign = if start.axis_v.dot(start.normal.cross(start.axis_u)) >= 0.0 { 1.0 } else { -1.0 };
            Placement { angle_deg: p.angle_deg + sign * turn.to_degrees(), ..p }
        }
    }
}

#[cfg(test)]
mod tests {
    use ppr_format::ReflectorKind;

    use super::*;
    use crate::reflector_geometry::place;

    fn rect() -> Reflector {
        Reflector::new(1, "r", ReflectorKind::Opaque, DVec3::ZERO, DVec3::Y, DVec3::X, DVec2::new(2.0, 1.0))
    }

    #[test]
    fn corner_drag_keeps_the_opposite_corner() {
        let r = rect();
        let p = dragged_placement(&r, Handle::Corner(1, 1), DVec2::new(2.0, 1.0), DVec2::new(3.0, 2.0));
        assert!((p.half_extents - DVec2::new(2.5, 1.5)).length() < 1e-12);
        let moved = place(&r, &p);
        let fixed = moved.center - moved.axis_u * moved.half_extents.x - moved.axis_v * moved.half_extents.y;
        assert!((fixed - DVec3::new(-2.0, 0.0, 1.0)).length() < 1e-12, "{fixed}");
    }

    #[test]
    fn edge_center_and_rotate_drags() {
        let r = rect();
        let p = dragged_placement(&r, Handle::Edge(true, -1), DVec2::new(-2.0, 0.0), DVec2::new(-1.0, 0.3));
        assert!((p.half_extents - DVec2::new(1.5, 1.0)).length() < 1e-12);
        assert!((p.center - DVec3::new(0.5, 0.0, 0.0)).length() < 1e-12);
        let p = dragged_placement(&r, Handle::Center, DVec2::ZERO, DVec2::new(1.0, 1.0));
        assert!((p.center - DVec3::new(1.0, 0.0, -1.0)).length() < 1e-12);
        let p = dragged_placement(&r, Handle::Rotate, DVec2::new(2.0, 0.0), DVec2::new(0.0, 2.0));
        let turned = place(&r, &p);
        assert!(
            (turned.axis_u - r.axis_v).length() < 1e-9,
            "u turned a quarter towards v: {}",
            turned.axis_u
        );
        let p = dragged_placement(&r, Handle::Edge(false, 1), DVec2::new(0.0, 1.0), DVec2::new(0.0, -5.0));
        assert!(p.half_extents.y > 0.0);
    }

    #[test]
    fn plane_hit_in_the_frame() {
        let r = rect();
        let hit = plane_hit(&r, DVec3::new(1.0, 2.0, -0.5), DVec3::NEG_Y).expect("hit");
        assert!((hit - DVec2::new(1.0, 0.5)).length() < 1e-12);
        assert!(plane_hit(&r, DVec3::new(1.0, 2.0, -0.5), DVec3::Y).is_none());
    }
}
