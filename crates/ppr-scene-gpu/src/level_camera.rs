//! A camera of the level file: a viewpoint for tools, turned into the runtime's `Camera`.

use glam::{DMat4, DVec3, Quat, Vec3};
use ppr_runtime::{Camera, Projection};

use crate::camera_spec::ProjectionChoice;

/// A camera defined in the level file (a viewpoint for tools).
#[derive(Clone, Debug, PartialEq)]
pub struct LevelCamera {
    /// Name of the camera (or of its node when the camera has none).
    pub name: String,
    /// World-from-view transform of its node (looks down local -Z, +Y up).
    pub world: DMat4,
    /// Vertical field of view, radians.
    pub yfov: f32,
    /// Near plane distance, metres.
    pub znear: f32,
    /// Far plane distance, metres; `None` for infinite.
    pub zfar: Option<f32>,
}

impl LevelCamera {
    /// World-space position of the camera.
    pub fn position(&self) -> DVec3 {
        self.world.w_axis.truncate()
    }

    /// The node's position and rotation, decomposed in `f64` (the walkthrough's cameras).
    pub fn position_rotation(&self) -> (DVec3, Quat) {
        let (_, rotation, translation) = self.world.to_scale_rotation_translation();
        (translation, rotation.as_quat().normalize())
    }

    /// The runtime camera for this viewpoint: the file's field of view and near plane,
    /// the depth convention and far plane of `projection` (its fov and near are replaced).
    pub fn to_camera(&self, projection: Projection) -> Camera {
        let m = self.world.as_mat4();
        let (_, rotation, _) = m.to_scale_rotation_translation();
        let rotation = orthonormal_rotation(m, rotation);
        Camera {
            position: self.position(),
            rotation,
            projection: Projection { fov_y: self.yfov, near: self.znear, ..projection },
        }
    }

    /// The runtime camera of this viewpoint with the file's field of view, near and far
    /// planes and the depth convention of `choice` (rotation as [`LevelCamera::to_camera`]).
    pub fn to_runtime_camera(&self, choice: ProjectionChoice) -> Camera {
        self.to_camera(choice.projection_of(self))
    }

    /// The same runtime camera with the rotation of [`LevelCamera::position_rotation`]
    /// (decomposed in `f64`): the walkthrough's.
    pub fn to_runtime_camera_f64(&self, choice: ProjectionChoice) -> Camera {
        let (position, rotation) = self.position_rotation();
        Camera { position, rotation, projection: choice.projection_of(self) }
    }
}

/// The rotation of a matrix with its scale (and any shear) removed, from its -Z and +Y axes.
fn orthonormal_rotation(m: glam::Mat4, fallback: Quat) -> Quat {
    let back = m.z_axis.truncate().normalize_or_zero();
    let up = m.y_axis.truncate();
    if back == Vec3::ZERO {
        return fallback;
    }
    let right = up.cross(back).normalize_or_zero();
    if right == Vec3::ZERO {
        return fallback;
    }
    let up = back.cross(right);
    Quat::from_mat3(&glam::Mat3::from_cols(right, up, back)).normalize()
}
