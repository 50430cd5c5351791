//! The mirrored view of a planar reflector: the camera reflected about the plane, with an
//! oblique near plane (Lengyel's oblique frustum clipping) so that nothing on the far side
//! of the mirror is drawn.
//!
//! Everything is camera-relative and computed in `f64`: the plane is moved to the camera's
//! frame (`d_rel = n · (p₀ − c)`) before anything is multiplied.

use glam::{DMat4, DVec3, DVec4};
use ppr_runtime::{Camera, DepthMode};

/// A plane given by a point on it and its unit normal (the reflecting side), world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MirrorPlane {
    /// A point on the plane.
    pub point: DVec3,
    /// Unit normal pointing to the reflecting side.
    pub normal: DVec3,
}

impl MirrorPlane {
    /// Signed distance of `p` from the plane (positive on the reflecting side).
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        (p - self.point).dot(self.normal)
    }

    /// Reflects a world point about the plane.
    pub fn reflect_point(&self, p: DVec3) -> DVec3 {
        p - 2.0 * self.signed_distance(p) * self.normal
    }

    /// The reflection about the plane as an affine matrix acting on positions relative to
    /// `origin` (its own inverse; determinant −1).
    pub fn reflection_relative_to(&self, origin: DVec3) -> DMat4 {
        let n = self.normal;
        let d_rel = n.dot(self.point - origin);
        let linear = glam::DMat3::IDENTITY - 2.0 * glam::DMat3::from_cols(n * n.x, n * n.y, n * n.z);
        let mut m = DMat4::from_mat3(linear);
        m.w_axis = (2.0 * d_rel * n).extend(1.0);
        m
    }
}

/// Clip-from-relative matrices of a mirrored view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MirroredView {
    /// Clip-from-relative: positions relative to the real camera go through the reflection,
    /// the camera's view rotation and the oblique projection.
    pub clip_from_rel: DMat4,
    /// Inverse of `clip_from_rel`: mirrored clip space to (real, unmirrored) relative positions.
    pub rel_from_clip: DMat4,
}

/// Geometry closer than this to the mirror plane (metres, on the reflected side) is not
/// drawn in the mirrored view: the mirror's own surface must not hide its reflection.
pub const MIRROR_SURFACE_MARGIN: f64 = 1e-3;
/// Added to [`MIRROR_SURFACE_MARGIN`] per metre between the camera and the plane.
pub const MIRROR_SURFACE_MARGIN_PER_METRE: f64 = 1e-4;

/// What the near plane of a mirrored view is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MirrorClipping {
    /// The mirror plane itself (oblique frustum): nothing behind the mirror is drawn. The
    /// exact reference always uses this.
    #[default]
    Oblique,
    /// The camera's own near plane: geometry behind the mirror shows up in the reflection.
    /// Only useful to show what the oblique plane removes.
    CameraNearPlane,
}

/// The camera's view seen through `plane`, for a viewport of aspect `aspect` (width / height).
///
/// Returns `None` when the camera is not strictly on the reflecting side of the plane or the
/// plane does not cross the view frustum beyond the camera (nothing to reflect).
pub fn mirrored_view(
    camera: &Camera,
    aspect: f64,
    plane: &MirrorPlane,
    clipping: MirrorClipping,
) -> Option<MirroredView> {
    let n = plane.normal;
    let d_rel = n.dot(plane.point - camera.position);
    if d_rel >= -1e-6 {
        return None;
    }
    let view = camera.view_from_relative().as_dmat4();
    // Keep mirrored geometry on the far side of the plane: (−n)·r + d_rel ≥ ε. The margin
    // ε clips the mirror's own surface (and anything lying on it, like a double-sided
    // pane) which would otherwise cover the reflection.
    // The view matrix is a pure rotation, so planes transform like points.
    let margin = MIRROR_SURFACE_MARGIN + MIRROR_SURFACE_MARGIN_PER_METRE * -d_rel;
    let clip_plane = (view.transform_vector3(-n)).extend(d_rel - margin);
    let oblique = oblique_projection(camera, aspect, clip_plane)?;
    let projection = match clipping {
        MirrorClipping::Oblique => oblique,
        MirrorClipping::CameraNearPlane => camera.projection.clip_from_view(aspect as f32).as_dmat4(),
    };
    let clip_from_rel = projection * view * plane.reflection_relative_to(camera.position);
    Some(MirroredView { clip_from_rel, rel_from_clip: clip_from_rel.inverse() })
}

/// The camera's projection with its near plane replaced by `clip_plane` (view space, kept
/// side `clip_plane · v ≥ 0`), for wgpu's `[0, 1]` depth, standard or reversed.
///
/// The far plane is tilted through the frustum corner farthest along the clip plane's
/// normal (Lengyel 2005), which keeps the whole original frustum beyond the new near plane
/// inside `[0, 1]`. With an infinite far plane that corner is at infinity.
///
/// Returns `None` if the clip plane does not cross the frustum beyond the camera.
pub fn oblique_projection(camera: &Camera, aspect: f64, clip_plane: DVec4) -> Option<DMat4> {
    let p = camera.projection;
    let base = p.clip_from_view(aspect as f32).as_dmat4();
    let tan = (f64::from(p.fov_y) * 0.5).tan();
    let (sx, sy) = (clip_plane.x.signum(), clip_plane.y.signum());
    let corner = match p.far {
        Some(far) => {
            let f = f64::from(far);
            DVec4::new(sx * aspect * tan * f, sy * tan * f, -f, 1.0)
        }
        None => DVec4::new(sx * aspect * tan, sy * tan, -1.0, 0.0),
    };
    let rows = base.transpose();
    let w_row = rows.w_axis;
    let c_dot_q = clip_plane.dot(corner);
    if c_dot_q <= 1e-12 {
        return None;
    }
    let a = w_row.dot(corner) / c_dot_q;
    let z_row = match p.depth {
        DepthMode::Standard => a * clip_plane,
        DepthMode::Reversed => w_row - a * clip_plane,
    };
    Some(DMat4::from_cols(rows.x_axis, rows.y_axis, z_row, w_row).transpose())
}

#[cfg(test)]
mod tests {
    use glam::{DVec3, Vec3};
    use ppr_runtime::{Camera, DepthMode, Projection};

    use super::*;

    fn floor() -> MirrorPlane {
        MirrorPlane { point: DVec3::new(1e5, 0.0, 3.0), normal: DVec3::Y }
    }

    fn camera(depth: DepthMode, far: Option<f32>) -> Camera {
        let projection = Projection { depth, far, ..Projection::default() };
        Camera::look_at(DVec3::new(1e5, 2.0, 5.0), DVec3::new(1e5, 0.0, 0.0), Vec3::Y, projection)
    }

    fn depth_of(view: &MirroredView, cam: &Camera, world: DVec3) -> f64 {
        let c = view.clip_from_rel * (world - cam.position).extend(1.0);
        c.z / c.w
    }

    #[test]
    fn reflection_is_an_involution_with_negative_determinant() {
        let origin = DVec3::new(1e5, 2.0, 5.0);
        let m = floor().reflection_relative_to(origin);
        assert!((m.determinant() + 1.0).abs() < 1e-12);
        assert!((m * m).abs_diff_eq(glam::DMat4::IDENTITY, 1e-12));
        let p = DVec3::new(1e5 + 1.0, 0.7, 2.0);
        let mirrored = m.transform_point3(p - origin) + origin;
        assert!((mirrored - floor().reflect_point(p)).length() < 1e-9);
        assert!((mirrored.y + 0.7).abs() < 1e-9);
    }

    #[test]
    fn oblique_near_plane_lies_on_the_mirror_for_every_depth_convention() {
        for depth in [DepthMode::Standard, DepthMode::Reversed] {
            for far in [Some(100.0), None] {
                let cam = camera(depth, far);
                let view =
                    mirrored_view(&cam, 1.5, &floor(), MirrorClipping::Oblique).expect("floor is visible");
                let near = if depth == DepthMode::Standard { 0.0 } else { 1.0 };
                // Points just beyond the margin are at the near plane (seen through the
                // mirror they are on the plane too); points on the mirror are clipped.
                let margin = MIRROR_SURFACE_MARGIN + MIRROR_SURFACE_MARGIN_PER_METRE * 2.0;
                for p in [DVec3::new(1e5, margin, 0.0), DVec3::new(1e5 + 1.0, margin, -2.0)] {
                    let z = depth_of(&view, &cam, p);
                    assert!((z - near).abs() < 1e-6, "{depth:?} {far:?}: plane point depth {z}");
                }
                let on_mirror = depth_of(&view, &cam, DVec3::new(1e5, 0.0, -1.0));
                let clipped = if depth == DepthMode::Standard { on_mirror < 0.0 } else { on_mirror > 1.0 };
                assert!(clipped, "{depth:?} {far:?}: the mirror's own surface is drawn ({on_mirror})");
                // A point above the floor is reflected below it: inside the depth range.
                let above = depth_of(&view, &cam, DVec3::new(1e5, 1.0, -1.0));
                assert!((0.0..=1.0).contains(&above) && (above - near).abs() > 1e-4, "{depth:?}: {above}");
                // A point below the floor is reflected above it: in front of the near plane.
                let below = depth_of(&view, &cam, DVec3::new(1e5, -0.5, -1.0));
                let clipped = if depth == DepthMode::Standard { below < 0.0 } else { below > 1.0 };
                assert!(clipped, "{depth:?} {far:?}: below-floor point not clipped ({below})");
            }
        }
    }

    #[test]
    fn oblique_depth_grows_with_distance_behind_the_mirror() {
        let cam = camera(DepthMode::Standard, Some(100.0));
        let view = mirrored_view(&cam, 1.0, &floor(), MirrorClipping::Oblique).expect("visible");
        let near = depth_of(&view, &cam, DVec3::new(1e5, 0.5, 0.0));
        let far = depth_of(&view, &cam, DVec3::new(1e5, 2.0, 0.0));
        assert!(near < far, "{near} !< {far}");
    }

    #[test]
    fn no_mirrored_view_from_behind_the_plane() {
        let mut cam = camera(DepthMode::Standard, Some(100.0));
        cam.position.y = -1.0;
        assert!(mirrored_view(&cam, 1.0, &floor(), MirrorClipping::Oblique).is_none());
    }
}
