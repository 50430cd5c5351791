//! The camera a frame is rendered with: f64 position, f32 rotation and projection.
//!
//! Everything on the GPU is camera-relative: positions are `world - camera.position`,
//! computed in f64 on the CPU and only then rounded to f32, so a level far from the
//! origin keeps its precision.

use glam::camera::rh::proj::directx;
use glam::camera::rh::view::look_to_quat;
use glam::{DMat4, DVec3, Mat4, Quat, Vec3, Vec4};

/// Which way depth runs in clip space (wgpu's z is in `[0, 1]`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum DepthMode {
    /// Near plane at z = 0, far plane at z = 1; the depth buffer is cleared to 1.
    #[default]
    Standard,
    /// Near plane at z = 1, far plane at z = 0; the depth buffer is cleared to 0.
    Reversed,
}

/// A perspective projection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    /// Vertical field of view in radians, in `(0, π)`.
    pub fov_y: f32,
    /// Distance of the near plane, metres (> 0).
    pub near: f32,
    /// Distance of the far plane, metres; `None` for an infinite far plane.
    pub far: Option<f32>,
    /// Standard or reversed Z.
    pub depth: DepthMode,
    /// The game's own clip-from-view matrix (wgpu clip space, z in `[0, 1]`), used instead
    /// of the one `fov_y`, `near` and `far` give, whatever the viewport's aspect: TAA
    /// jitter, off-centre and oblique-near-plane projections. `depth` must say which way
    /// its depth runs. A perspective matrix: reflections are mirrored about the camera's
    /// position.
    pub matrix: Option<Mat4>,
}

impl Default for Projection {
    fn default() -> Self {
        Self {
            fov_y: 60f32.to_radians(),
            near: 0.05,
            far: Some(500.0),
            depth: DepthMode::Standard,
            matrix: None,
        }
    }
}

impl Projection {
    /// Clip-from-view matrix for a viewport of the given aspect ratio (width / height).
    pub fn clip_from_view(&self, aspect: f32) -> Mat4 {
        if let Some(m) = self.matrix {
            return m;
        }
        match (self.far, self.depth) {
            (Some(far), DepthMode::Standard) => directx::perspective(self.fov_y, aspect, self.near, far),
            // Swapping near and far maps the near plane to 1 and the far plane to 0.
            (Some(far), DepthMode::Reversed) => directx::perspective(self.fov_y, aspect, far, self.near),
            (None, DepthMode::Standard) => directx::perspective_infinite(self.fov_y, aspect, self.near),
            (None, DepthMode::Reversed) => {
                directx::perspective_infinite_reverse(self.fov_y, aspect, self.near)
            }
        }
    }

    /// The depth value a cleared depth buffer holds (nothing rendered there).
    pub fn far_depth(&self) -> f32 {
        match self.depth {
            DepthMode::Standard => 1.0,
            DepthMode::Reversed => 0.0,
        }
    }

    /// The depth comparison a rasteriser uses with this projection.
    pub fn depth_compare(&self) -> wgpu::CompareFunction {
        match self.depth {
            DepthMode::Standard => wgpu::CompareFunction::Less,
            DepthMode::Reversed => wgpu::CompareFunction::Greater,
        }
    }
}

/// Why a game's matrices make no [`Camera`].
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum CameraError {
    /// The view matrix is not a rotation and a translation.
    #[error(
        "the view matrix is not rigid (scale {scale:?}, or shear, or not invertible): pass a rotation and translation only"
    )]
    NotRigid { scale: [f64; 3] },
}

/// A camera: where it is (f64), where it looks, and how it projects.
///
/// The view looks down its local -Z with +Y up (glTF and glam convention).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// World-space position, metres.
    pub position: DVec3,
    /// World-from-view rotation.
    pub rotation: Quat,
    /// The projection.
    pub projection: Projection,
}

impl Camera {
    /// A camera at `eye` looking at `target` with `up` as the approximate up direction.
    pub fn look_at(eye: DVec3, target: DVec3, up: Vec3, projection: Projection) -> Self {
        let forward = (target - eye).as_vec3().normalize();
        let rotation = look_to_quat(forward, up).inverse();
        Self { position: eye, rotation, projection }
    }

    /// The camera of a game's view matrix (view-from-world, f64 so that a level far from
    /// the origin keeps its precision) and projection matrix (`clip_from_view`, see
    /// [`Projection::matrix`]), with `depth` saying which way the projection's depth runs.
    ///
    /// # Errors
    /// [`CameraError::NotRigid`] when the view matrix scales, shears or is not invertible:
    /// the runtime needs a camera position and a rotation.
    pub fn from_matrices(view: DMat4, clip_from_view: Mat4, depth: DepthMode) -> Result<Self, CameraError> {
        let world_from_view = view.inverse();
        let (scale, rotation, position) = world_from_view.to_scale_rotation_translation();
        let rigid = world_from_view.is_finite()
            && (scale - glam::DVec3::ONE).abs().max_element() < 1e-5
            && (DMat4::from_rotation_translation(rotation, position) - world_from_view)
                .to_cols_array()
                .iter()
                .all(|d| d.abs() < 1e-6 * (1.0 + position.length()));
        if !rigid {
            return Err(CameraError::NotRigid { scale: scale.to_array() });
        }
        let projection = Projection { depth, matrix: Some(clip_from_view), ..Projection::default() };
        Ok(Self { position, rotation: rotation.as_quat().normalize(), projection })
    }

    /// View-from-relative matrix: a pure rotation (positions are already camera-relative).
    pub fn view_from_relative(&self) -> Mat4 {
        Mat4::from_quat(self.rotation.inverse())
    }

    /// Clip-from-relative matrix for the given aspect ratio.
    pub fn clip_from_relative(&self, aspect: f32) -> Mat4 {
        self.projection.clip_from_view(aspect) * self.view_from_relative()
    }

    /// Camera-relative position of a world point, computed in f64 and rounded once.
    pub fn relative(&self, world: DVec3) -> Vec3 {
        (world - self.position).as_vec3()
    }

    /// The direction the camera looks in (world space).
    pub fn forward(&self) -> Vec3 {
        self.rotation * Vec3::NEG_Z
    }

    /// Projects a camera-relative point to clip space.
    pub fn project_relative(&self, p: Vec3, aspect: f32) -> Vec4 {
        self.clip_from_relative(aspect) * p.extend(1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_depth(projection: Projection, near_expected: f32, far_expected: f32) {
        let cam =
            Camera::look_at(DVec3::new(1e5, 2.0, -3.0), DVec3::new(1e5, 2.0, -10.0), Vec3::Y, projection);
        let near = cam.project_relative(Vec3::new(0.0, 0.0, -projection.near), 1.5);
        assert!((near.z / near.w - near_expected).abs() < 1e-5, "{projection:?} near {near}");
        let far = projection.far.unwrap_or(1e9);
        let far = cam.project_relative(Vec3::new(0.0, 0.0, -far), 1.5);
        assert!((far.z / far.w - far_expected).abs() < 1e-4, "{projection:?} far {far}");
    }

    #[test]
    fn depth_conventions_map_near_and_far() {
        let p = Projection::default();
        check_depth(p, 0.0, 1.0);
        check_depth(Projection { depth: DepthMode::Reversed, ..p }, 1.0, 0.0);
        check_depth(Projection { far: None, ..p }, 0.0, 1.0);
        check_depth(Projection { far: None, depth: DepthMode::Reversed, ..p }, 1.0, 0.0);
    }

    #[test]
    fn a_camera_from_matrices_projects_as_the_camera_they_came_from() {
        let projection = Projection { depth: DepthMode::Reversed, far: None, ..Projection::default() };
        let cam = Camera::look_at(
            DVec3::new(1e5, 2.0, -3.0),
            DVec3::new(1e5 + 4.0, 1.0, -9.0),
            Vec3::Y,
            projection,
        );
        let view = DMat4::from_rotation_translation(cam.rotation.as_dquat(), cam.position).inverse();
        let aspect = 16.0 / 9.0;
        let jitter = Mat4::from_translation(Vec3::new(0.5 / 960.0, -0.5 / 540.0, 0.0));
        let clip = jitter * projection.clip_from_view(aspect);
        let from = Camera::from_matrices(view, clip, DepthMode::Reversed).expect("rigid view");
        assert!((from.position - cam.position).length() < 1e-9, "{:?}", from.position);
        let p = Vec3::new(1.0, -0.5, -4.0);
        let expected = jitter * cam.project_relative(p, aspect);
        // The projection matrix is the game's, whatever the aspect.
        for a in [aspect, 1.0] {
            let got = from.project_relative(p, a);
            assert!((got - expected).abs().max_element() < 1e-5, "{got} vs {expected}");
        }
        assert_eq!(from.projection.far_depth(), 0.0);
        let scaled = view * DMat4::from_scale(DVec3::splat(2.0));
        assert!(matches!(
            Camera::from_matrices(scaled, clip, DepthMode::Standard),
            Err(CameraError::NotRigid { .. })
        ));
    }

    #[test]
    fn look_at_faces_the_target_and_keeps_up() {
        let cam = Camera::look_at(DVec3::ZERO, DVec3::new(3.0, 0.0, 4.0), Vec3::Y, Projection::default());
        assert!((cam.forward() - Vec3::new(0.6, 0.0, 0.8)).length() < 1e-6);
        assert!((cam.rotation * Vec3::Y - Vec3::Y).length() < 1e-6);
    }
}
