//! The screen box of the pixels that may reflect into a shape, for the projection pass to
//! skip a shape in the tiles outside it.
//!
//! A point `p` in front of the plane is reflected into the rectangle when the ray from the
//! camera to its mirror image crosses the rectangle, i.e. when `p` lies in the pyramid
//! from the *mirrored* camera through the rectangle, beyond it. That pyramid is the
//! positive hull, in homogeneous coordinates, of the rectangle's four corners `(r, 1)` and
//! of the four directions `(r − e', 0)` from the mirrored camera `e'` through them. Its
//! boundary is five faces (the rectangle and four unbounded sides); each is clipped
//! against the view frustum's side planes in clip space (Sutherland–Hodgman on homogeneous
//! vectors, which handles the points at infinity), and the box of what is left, projected,
//! bounds every pixel whose position can reflect into the rectangle, at any depth. The
//! near and far planes are not clipped against: the box is conservative.
//!
//! That holds while the camera is outside the pyramid (every ray through it then enters
//! through a face). A camera inside it (in front of the plane, straight over the
//! rectangle: a player standing on a mirror floor) sees the pyramid around itself, so
//! every pixel may reflect into the shape and the box is the whole screen.

use glam::{DMat4, DVec3, DVec4, Mat4};

use crate::plan::ScreenRect;
use crate::shapes::ShapeSource;

/// Pixels added on every side, for the f32 rounding of per-pixel positions.
const MARGIN_PX: f64 = 1.0;

/// The screen box (inclusive min, exclusive max) of the pixels that may reflect into
/// `shape` for a camera at `eye` with `clip_from_rel`; empty (`min == max`) when no
/// pixel can.
pub fn source_rect(shape: &ShapeSource, eye: DVec3, clip_from_rel: &Mat4, [w, h]: [u32; 2]) -> ScreenRect {
    let full = ScreenRect { min: [0, 0], max: [w, h] };
    let m = DMat4::from_cols_array(&clip_from_rel.to_cols_array().map(f64::from));
    let n = shape.normal.as_dvec3();
    if eye_over_rectangle(shape, eye) {
        return full;
    }
    let mirrored_eye = 2.0 * shape.plane_dist_from(eye) * n;
    let corners = shape.corners().map(|c| c - eye);
    let point = |r: DVec3| m * r.extend(1.0);
    let direction = |r: DVec3| m * (r - mirrored_eye).extend(0.0);
    let c = corners.map(point);
    let d = corners.map(direction);
    let mut faces: Vec<Vec<DVec4>> = vec![c.to_vec()];
    for i in 0..4 {
        let j = (i + 1) % 4;
        faces.push(vec![c[i], c[j], d[j], d[i]]);
    }
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    for face in faces {
        for v in clip_to_view(face) {
            let scale = v.abs().max_element();
            // Only the zero vector survives the side planes with w = 0 (and NaN is skipped).
            if v.w.partial_cmp(&(1e-12 * scale)) != Some(std::cmp::Ordering::Greater) {
                continue;
            }
            let px = [(v.x / v.w * 0.5 + 0.5) * f64::from(w), (0.5 - v.y / v.w * 0.5) * f64::from(h)];
            for a in 0..2 {
                lo[a] = lo[a].min(px[a]);
                hi[a] = hi[a].max(px[a]);
            }
        }
    }
    if lo[0] > hi[0] {
        return ScreenRect { min: [0, 0], max: [0, 0] };
    }
    if !lo.iter().chain(&hi).all(|x| x.is_finite()) {
        return full;
    }
    let clamp = |x: f64, max: u32| x.clamp(0.0, f64::from(max)) as u32;
    ScreenRect {
        min: [clamp((lo[0] - MARGIN_PX).floor(), w), clamp((lo[1] - MARGIN_PX).floor(), h)],
        max: [clamp((hi[0] + MARGIN_PX).ceil(), w), clamp((hi[1] + MARGIN_PX).ceil(), h)],
    }
}

/// Whether `eye` lies in the shape's mirrored pyramid: in front of the plane, its foot on
/// the plane inside the rectangle (with a relative margin, so that a camera on the
/// pyramid's boundary counts as inside).
fn eye_over_rectangle(shape: &ShapeSource, eye: DVec3) -> bool {
    let height = -shape.plane_dist_from(eye);
    let rel = eye - shape.center;
    let margin = 1e-4 * (1.0 + rel.length());
    let inside = |axis: glam::Vec3, half: f32| rel.dot(axis.as_dvec3()).abs() <= f64::from(half) + margin;
    height > 0.0 && inside(shape.axis_u, shape.half_extents[0]) && inside(shape.axis_v, shape.half_extents[1])
}

/// Clips a polygon of homogeneous clip-space vectors (its positive hull) against the
/// frustum's four side planes.
fn clip_to_view(mut poly: Vec<DVec4>) -> Vec<DVec4> {
    let planes: [fn(&DVec4) -> f64; 4] = [|v| v.w + v.x, |v| v.w - v.x, |v| v.w + v.y, |v| v.w - v.y];
    for plane in planes {
        if poly.is_empty() {
            break;
        }
        let mut out = Vec::with_capacity(poly.len() + 2);
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let (fa, fb) = (plane(&a), plane(&b));
            if fa >= 0.0 {
                out.push(a);
            }
            if (fa >= 0.0) != (fb >= 0.0) {
                out.push(a + (b - a) * (fa / (fa - fb)));
            }
        }
        poly = out;
    }
    poly
}

#[cfg(test)]
mod tests {
    use glam::{Quat, Vec3};
    use ppr_format::ReflectorKind;

    use super::*;
    use crate::camera::{Camera, Projection};

    fn floor(half: f32) -> ShapeSource {
        ShapeSource {
            id: 0,
            kind: ReflectorKind::Opaque,
            enabled: true,
            center: DVec3::ZERO,
            axis_u: Vec3::X,
            axis_v: Vec3::NEG_Z,
            normal: Vec3::Y,
            half_extents: [half, half],
            parallel_group: 0,
            normal_map: false,
            roughness: 0.0,
        }
    }

    /// Brute force: pixel centres whose ray, at some depth, holds a point that the floor
    /// reflects into its rectangle.
    fn reflecting_pixels(shape: &ShapeSource, camera: &Camera, [w, h]: [u32; 2]) -> Vec<[u32; 2]> {
        let clip_from_rel = camera.clip_from_relative(w as f32 / h as f32);
        let rel_from_clip = clip_from_rel.inverse();
        let n = shape.normal;
        let d = shape.plane_dist_from(camera.position) as f32;
        let c = (shape.center - camera.position).as_vec3();
        let mut out = Vec::new();
        for y in 0..h {
            for x in 0..w {
                let ndc = [(x as f32 + 0.5) / w as f32 * 2.0 - 1.0, 1.0 - (y as f32 + 0.5) / h as f32 * 2.0];
                let near = rel_from_clip.project_point3(Vec3::new(ndc[0], ndc[1], 0.0));
                let far = rel_from_clip.project_point3(Vec3::new(ndc[0], ndc[1], 0.5));
                let dir = (far - near).normalize();
                let hits = (0..240).any(|k| {
                    let p = near + dir * (0.05 * 1.04f32.powi(k));
                    let dist = p.dot(n) - d;
                    if dist <= 0.0 {
                        return false;
                    }
                    let m = p - 2.0 * dist * n;
                    let hit = m * (d / m.dot(n)) - c;
                    hit.dot(shape.axis_u).abs() <= shape.half_extents[0]
                        && hit.dot(shape.axis_v).abs() <= shape.half_extents[1]
                });
                if hits {
                    out.push([x, y]);
                }
            }
        }
        out
    }

    #[test]
    fn the_box_holds_every_reflecting_pixel_and_is_tight() {
        let projection = Projection::default();
        let cameras = [
            Camera::look_at(DVec3::new(0.0, 1.6, 4.0), DVec3::new(0.0, 0.5, 0.0), Vec3::Y, projection),
            Camera::look_at(DVec3::new(3.0, 0.3, 3.0), DVec3::new(-1.0, 0.8, -2.0), Vec3::Y, projection),
            Camera { position: DVec3::new(0.2, 5.0, 0.1), rotation: Quat::from_rotation_x(-1.5), projection },
        ];
        let size = [64, 40];
        for (i, camera) in cameras.iter().enumerate() {
            let shape = floor(0.8);
            let rect = source_rect(&shape, camera.position, &camera.clip_from_relative(1.6), size);
            let pixels = reflecting_pixels(&shape, camera, size);
            assert!(!pixels.is_empty(), "camera {i}: the floor reflects something");
            for p in &pixels {
                assert!(
                    p[0] >= rect.min[0] && p[0] < rect.max[0] && p[1] >= rect.min[1] && p[1] < rect.max[1],
                    "camera {i}: pixel {p:?} outside {rect:?}"
                );
            }
            // Tight: within the margin plus one pixel of the brute-force box.
            let lo = [0, 1].map(|a| pixels.iter().map(|p| p[a]).min().unwrap_or(0));
            let hi = [0, 1].map(|a| pixels.iter().map(|p| p[a] + 1).max().unwrap_or(0));
            for a in 0..2 {
                assert!(
                    rect.min[a] + 3 >= lo[a] && rect.max[a] <= hi[a] + 3,
                    "camera {i}: {rect:?} vs {lo:?}..{hi:?}"
                );
            }
        }
    }

    /// Standing on a mirror floor (an 8 × 6 m room's), looking along it: the walls at the
    /// top of the view reflect into the floor at the camera's feet, so every row may
    /// reflect. The box from the pyramid's faces alone lost the top third of the rows.
    #[test]
    fn a_camera_over_the_rectangle_gets_the_whole_screen() {
        let projection = Projection { far: Some(60.0), ..Projection::default() };
        let camera =
            Camera::look_at(DVec3::new(0.5, 0.4, 2.5), DVec3::new(-1.0, 0.2, -3.0), Vec3::Y, projection);
        let mut shape = floor(4.0);
        shape.half_extents = [4.0, 3.0];
        let size = [160, 90];
        let rect = source_rect(&shape, camera.position, &camera.clip_from_relative(16.0 / 9.0), size);
        let pixels = reflecting_pixels(&shape, &camera, size);
        assert!(pixels.iter().any(|p| p[1] == 0), "the top row reflects into the floor");
        for p in &pixels {
            assert!(
                p[0] >= rect.min[0] && p[0] < rect.max[0] && p[1] >= rect.min[1] && p[1] < rect.max[1],
                "pixel {p:?} outside {rect:?}"
            );
        }
    }

    #[test]
    fn a_reflector_whose_mirror_pyramid_leaves_the_view_has_an_empty_box() {
        // The floor lies behind a camera that looks away from it: its pyramid runs from
        // the floor away from the view.
        let camera = Camera::look_at(
            DVec3::new(0.0, 1.0, 5.0),
            DVec3::new(0.0, 1.0, 10.0),
            Vec3::Y,
            Projection::default(),
        );
        let shape = floor(0.5);
        let rect = source_rect(&shape, camera.position, &camera.clip_from_relative(1.0), [32, 32]);
        assert_eq!(reflecting_pixels(&shape, &camera, [32, 32]), Vec::<[u32; 2]>::new());
        assert_eq!(rect.area(), 0, "{rect:?}");
    }
}
