//! Views through a chain of planar mirrors (the exact reference's later bounces): the
//! camera reflected about each plane in turn, clipped obliquely at the last plane's image.
//!
//! A view seen through mirrors `P₁ … Pₖ` draws a world point `X` at its virtual image
//! `R₁ ∘ … ∘ Rₖ (X)`; the near plane is the image of `Pₖ` through `P₁ … Pₖ₋₁`. As in
//! [`crate::mirror_camera`], everything is relative to the real camera and in `f64`.

use glam::{DMat4, DVec4};
use ppr_format::ReflectorSet;
use ppr_runtime::Camera;

use crate::mirror_camera::{
    MIRROR_SURFACE_MARGIN, MIRROR_SURFACE_MARGIN_PER_METRE, MirrorClipping, MirrorPlane, MirroredView,
    oblique_projection,
};
use crate::reflector_planes::ReflectorPlane;

/// A view through a chain of mirrors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChainedView {
    /// Its clip-from-relative matrices.
    pub view: MirroredView,
    /// The chain's reflection on camera-relative positions (`R₁ … Rₖ`; determinant ±1).
    pub reflection: DMat4,
}

/// The view through `plane` seen in the view whose chain reflection is `before` (the
/// identity for the camera's own view).
///
/// Returns `None` when the camera is not strictly on the reflecting side of the plane's
/// image or that image does not cross the view frustum beyond the camera.
pub fn mirrored_view_through(
    camera: &Camera,
    aspect: f64,
    before: &DMat4,
    plane: &MirrorPlane,
    clipping: MirrorClipping,
) -> Option<ChainedView> {
    let point = before.transform_point3(plane.point - camera.position);
    let normal = before.transform_vector3(plane.normal);
    let d_rel = normal.dot(point);
    if d_rel >= -1e-6 {
        return None;
    }
    let view = camera.view_from_relative().as_dmat4();
    let margin = MIRROR_SURFACE_MARGIN + MIRROR_SURFACE_MARGIN_PER_METRE * -d_rel;
    let clip_plane = view.transform_vector3(-normal).extend(d_rel - margin);
    let oblique = oblique_projection(camera, aspect, clip_plane)?;
    let projection = match clipping {
        MirrorClipping::Oblique => oblique,
        MirrorClipping::CameraNearPlane => camera.projection.clip_from_view(aspect as f32).as_dmat4(),
    };
    let reflection = *before * plane.reflection_relative_to(camera.position);
    let clip_from_rel = projection * view * reflection;
    Some(ChainedView {
        view: MirroredView { clip_from_rel, rel_from_clip: clip_from_rel.inverse() },
        reflection,
    })
}

/// Whether some member of `group` may show in the view whose clip-from-relative matrix is
/// `clip_from_rel` (conservative: `false` only when every member's rectangle is outside
/// one side of that view's clip volume, its oblique near plane included).
pub fn may_show_in(
    set: &ReflectorSet,
    group: &ReflectorPlane,
    camera: &Camera,
    clip_from_rel: &DMat4,
) -> bool {
    group.members.iter().any(|&i| {
        let corners = set.reflectors[i].corners().map(|c| *clip_from_rel * (c - camera.position).extend(1.0));
        let all = |f: &dyn Fn(&DVec4) -> bool| corners.iter().all(f);
        !(all(&|c| c.w <= 0.0)
            || all(&|c| c.x > c.w)
            || all(&|c| c.x < -c.w)
            || all(&|c| c.y > c.w)
            || all(&|c| c.y < -c.w)
            || all(&|c| c.z < 0.0)
            || all(&|c| c.z > c.w))
    })
}

#[cfg(test)]
mod tests {
    use glam::{DVec3, Vec3};
    use ppr_runtime::{Camera, Projection};

    use super::*;
    use crate::mirror_camera::mirrored_view;

    fn wall(x: f64, normal: f64) -> MirrorPlane {
        MirrorPlane { point: DVec3::new(x, 1.0, 0.0), normal: DVec3::new(normal, 0.0, 0.0) }
    }

    fn camera() -> Camera {
        Camera::look_at(DVec3::new(0.5, 1.0, 0.0), DVec3::new(3.0, 1.0, 0.2), Vec3::Y, Projection::default())
    }

    #[test]
    fn one_mirror_matches_the_mirrored_view() {
        let cam = camera();
        let one =
            mirrored_view_through(&cam, 1.5, &DMat4::IDENTITY, &wall(2.0, -1.0), MirrorClipping::Oblique)
                .expect("the wall faces the camera");
        let direct = mirrored_view(&cam, 1.5, &wall(2.0, -1.0), MirrorClipping::Oblique).expect("visible");
        assert!(one.view.clip_from_rel.abs_diff_eq(direct.clip_from_rel, 1e-12));
    }

    #[test]
    fn two_facing_mirrors_give_a_translation() {
        // Walls at x = -1 (facing +x) and x = 2 (facing -x): through the far wall then the
        // near one, a point is moved by twice the corridor width along -x... or +x: either
        // way a pure translation of 6 m with determinant +1.
        let cam = camera();
        let far =
            mirrored_view_through(&cam, 1.5, &DMat4::IDENTITY, &wall(2.0, -1.0), MirrorClipping::Oblique)
                .expect("far wall");
        let back =
            mirrored_view_through(&cam, 1.5, &far.reflection, &wall(-1.0, 1.0), MirrorClipping::Oblique)
                .expect("the near wall's image lies beyond the far wall");
        assert!((back.reflection.determinant() - 1.0).abs() < 1e-12);
        let moved = back.reflection.transform_point3(DVec3::ZERO) - DVec3::ZERO;
        assert!((moved.length() - 6.0).abs() < 1e-9 && moved.y.abs() < 1e-12, "{moved}");
        // The far wall cannot be seen in itself.
        assert!(
            mirrored_view_through(&cam, 1.5, &far.reflection, &wall(2.0, -1.0), MirrorClipping::Oblique)
                .is_none()
        );
    }
}
