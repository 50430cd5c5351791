//! Where on screen a projection test's writes may land, for the hidden-shape pass
//! (`shaders/hidden_shapes.wgsl`): the projected quadrilateral of its rectangle, as its
//! bounding box and four edge functions in pixels.
//!
//! A write lands at the pixel holding the projection of a reflection point, which lies in
//! the rectangle: within the quadrilateral (the projection of a rectangle wholly in front
//! of the camera is convex), up to f32 rounding. The pass tests a pixel by its centre, at
//! most half a diagonal from any point of the pixel, so the edges are widened by
//! [`EDGE_MARGIN_PX`] and the box by a pixel. A rectangle with a corner behind the camera
//! has no bounded projection: its region is the whole screen.

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec2, Vec4};

use crate::shapes::ShapeSource;

/// How far outside an edge (pixels) a pixel centre still counts as in the region: half a
/// pixel's diagonal (0.71) plus room for the rounding of the reflection point.
pub const EDGE_MARGIN_PX: f32 = 1.5;

/// A test's region, as the WGSL `HiddenRegion` holds it.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct HiddenRegion {
    /// Bounding box (min x, min y, max x, max y, exclusive) in pixels; `x` = `u32::MAX`:
    /// the test is never skipped ([`HiddenRegion::KEEP`]).
    pub rect: [u32; 4],
    /// Edge functions `(a, b, c, 0)`: a pixel centre `(x, y)` is in the region when
    /// `a x + b y + c ≥ −EDGE_MARGIN_PX` for all four (distances in pixels; all zero: no
    /// edge).
    pub edges: [[f32; 4]; 4],
}

impl HiddenRegion {
    /// A test the pass never skips (a parallel tree: its members' planes differ).
    pub const KEEP: Self = Self { rect: [u32::MAX; 4], edges: [[0.0; 4]; 4] };

    /// The region of `shape` for a camera at the origin of `clip_from_rel`'s space
    /// (`eye` in world space), on a `w × h` viewport.
    pub fn of(shape: &ShapeSource, eye: glam::DVec3, clip_from_rel: &Mat4, [w, h]: [u32; 2]) -> Self {
        let clip: [Vec4; 4] = shape.corners().map(|c| *clip_from_rel * (c - eye).as_vec3().extend(1.0));
        let full = Self { rect: [0, 0, w, h], edges: [[0.0; 4]; 4] };
        if clip.iter().any(|c| !(c.w > 1e-6)) {
            return full;
        }
        let size = Vec2::new(w as f32, h as f32);
        let px = clip.map(|c| (c.truncate().truncate() / c.w * Vec2::new(0.5, -0.5) + 0.5) * size);
        if px.iter().any(|p| !p.is_finite()) {
            return full;
        }
        let (lo, hi) = px
            .iter()
            .fold((Vec2::splat(f32::MAX), Vec2::splat(f32::MIN)), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        let clamp = |v: f32, max: u32| v.clamp(0.0, max as f32) as u32;
        let rect =
            [clamp(lo.x.floor(), w), clamp(lo.y.floor(), h), clamp(hi.x.ceil(), w), clamp(hi.y.ceil(), h)];
        // Twice the signed area: the winding that puts the inside on the left or right.
        let area: f32 = (0..4).map(|i| px[i].perp_dot(px[(i + 1) % 4])).sum();
        let mut edges = [[0.0; 4]; 4];
        if area.abs() > 1e-6 {
            for (i, e) in edges.iter_mut().enumerate() {
                let (a, b) = (px[i], px[(i + 1) % 4]);
                let d = b - a;
                let len = d.length();
                if len > 1e-6 {
                    // Inside: (p − a) on the side of the interior, distance in pixels.
                    let n = Vec2::new(-d.y, d.x) * area.signum() / len;
                    *e = [n.x, n.y, -n.dot(a), 0.0];
                }
            }
        }
        Self { rect, edges }
    }

    /// Whether the pixel centre `(x, y)` lies in the region (the shader's test, for tests).
    pub fn contains(&self, x: f32, y: f32) -> bool {
        let [x0, y0, x1, y1] = self.rect;
        let (px, py) = (x.floor(), y.floor());
        px + 1.0 >= x0 as f32
            && py + 1.0 >= y0 as f32
            && px < x1 as f32 + 1.0
            && py < y1 as f32 + 1.0
            && self.edges.iter().all(|e| e[0] * x + e[1] * y + e[2] >= -EDGE_MARGIN_PX)
    }
}

#[cfg(test)]
mod tests {
    use glam::{DVec3, Vec3};
    use ppr_format::ReflectorKind;

    use super::*;
    use crate::{Camera, Projection};

    fn shape(center: DVec3, u: Vec3, v: Vec3, half: [f32; 2]) -> ShapeSource {
        ShapeSource {
            id: 0,
            kind: ReflectorKind::Opaque,
            enabled: true,
            center,
            axis_u: u.normalize(),
            axis_v: v.normalize(),
            normal: u.cross(v).normalize(),
            half_extents: half,
            parallel_group: 0,
            normal_map: false,
            roughness: 0.0,
        }
    }

    /// Every pixel a point of the rectangle projects into is in the region, and pixels far
    /// from the quadrilateral (inside its bounding box) are not.
    #[test]
    fn the_region_holds_the_projected_rectangle_and_little_else() {
        let camera = Camera::look_at(
            DVec3::new(0.3, 1.6, 1.0),
            DVec3::new(0.0, 1.0, -5.0),
            Vec3::Y,
            Projection::default(),
        );
        let size = [200u32, 120u32];
        let clip = camera.clip_from_relative(size[0] as f32 / size[1] as f32);
        let turned = Vec3::new(1.0, 0.0, 1.0).normalize();
        let s = shape(DVec3::new(2.0, 1.0, -6.0), turned, Vec3::new(0.0, 1.0, 0.3), [1.5, 0.6]);
        let r = HiddenRegion::of(&s, camera.position, &clip, size);
        let mut inside = 0;
        for i in 0..=60 {
            for j in 0..=60 {
                let (a, b) = (i as f64 / 30.0 - 1.0, j as f64 / 30.0 - 1.0);
                let p = s.center + s.axis_u.as_dvec3() * a * 1.5 + s.axis_v.as_dvec3() * b * 0.6;
                let c = clip * (p - camera.position).as_vec3().extend(1.0);
                let ndc = c.truncate().truncate() / c.w;
                let px = (ndc * Vec2::new(0.5, -0.5) + 0.5) * Vec2::new(200.0, 120.0);
                let centre = px.floor() + 0.5;
                assert!(r.contains(centre.x, centre.y), "({a}, {b}) at {px} outside {r:?}");
                inside += 1;
            }
        }
        assert!(inside > 0);
        // The bounding box's corners lie outside the turned, sheared quadrilateral.
        let [x0, y0, x1, y1] = r.rect;
        let corners = [(x0, y0), (x1 - 1, y0), (x0, y1 - 1), (x1 - 1, y1 - 1)];
        let outside = corners.iter().filter(|&&(x, y)| !r.contains(x as f32 + 0.5, y as f32 + 0.5)).count();
        assert!(outside >= 2, "{outside} of the box's corners outside: {r:?}");
        // Behind the camera: the whole screen.
        let behind = shape(DVec3::new(0.3, 0.0, 1.0), Vec3::X, Vec3::new(0.0, 0.0, -1.0), [1.0, 3.0]);
        assert_eq!(HiddenRegion::of(&behind, camera.position, &clip, size).rect, [0, 0, 200, 120]);
    }
}
