//! Choosing a camera from the command line: a glTF camera by name, or
//! `"eye=x,y,z;target=x,y,z;fov=60"` (optionally `up=x,y,z`, `near=0.05`, `far=500`).

use glam::{DVec3, Vec3};
use ppr_runtime::{Camera, DepthMode, Projection};

use crate::TestbedError;
use crate::level::{Level, LevelCamera};

/// The projection choices of a command line, applied to whichever camera is picked.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ProjectionChoice {
    /// Standard or reversed Z.
    pub depth: DepthMode,
    /// Replace the far plane by an infinite one.
    pub infinite_far: bool,
}

impl LevelCamera {
    /// The runtime camera of this viewpoint with the file's field of view, near and far
    /// planes and the given depth convention.
    pub fn to_runtime_camera(&self, choice: ProjectionChoice) -> Camera {
        let far = if choice.infinite_far { None } else { self.zfar };
        self.to_camera(Projection {
            fov_y: self.yfov,
            near: self.znear,
            far,
            depth: choice.depth,
            matrix: None,
        })
    }
}

/// Picks the camera `spec` names in `level`: `None` is the level's first camera, text with
/// `=` is parsed as `eye=...;target=...;fov=...`, anything else is a camera name.
///
/// # Errors
/// [`TestbedError::CameraSpec`] when the level has no camera (and none was described),
/// the name is unknown (the error lists the level's cameras), or the text does not parse.
pub fn pick_camera(
    level: &Level,
    spec: Option<&str>,
    choice: ProjectionChoice,
) -> Result<Camera, TestbedError> {
    let names = || level.cameras.iter().map(|c| c.name.as_str()).collect::<Vec<_>>().join(", ");
    match spec {
        None => level.cameras.first().map(|c| c.to_runtime_camera(choice)).ok_or_else(|| {
            TestbedError::CameraSpec {
                text: String::new(),
                reason: "the level has no camera; pass one as \"eye=x,y,z;target=x,y,z;fov=60\"".into(),
            }
        }),
        Some(text) if text.contains('=') => parse_camera(text, choice),
        Some(name) => {
            level.camera(name).map(|c| c.to_runtime_camera(choice)).ok_or_else(|| TestbedError::CameraSpec {
                text: name.to_owned(),
                reason: format!("no such camera (the level has: {})", names()),
            })
        }
    }
}

/// Parses `"eye=x,y,z;target=x,y,z;fov=60"` (degrees; `up`, `near` and `far` optional).
///
/// # Errors
/// [`TestbedError::CameraSpec`] naming the key that is missing or malformed.
pub fn parse_camera(text: &str, choice: ProjectionChoice) -> Result<Camera, TestbedError> {
    let fail = |reason: String| TestbedError::CameraSpec { text: text.to_owned(), reason };
    let mut eye = None;
    let mut target = None;
    let mut up = Vec3::Y;
    let mut projection = Projection { depth: choice.depth, ..Projection::default() };
    for part in text.split(';').map(str::trim).filter(|p| !p.is_empty()) {
        let (key, value) = part.split_once('=').ok_or_else(|| fail(format!("`{part}` is not key=value")))?;
        let number = |v: &str| v.trim().parse::<f64>().map_err(|e| fail(format!("`{key}`: {v:?}: {e}")));
        let vector = |v: &str| -> Result<DVec3, TestbedError> {
            let xs: Vec<f64> = v.split(',').map(number).collect::<Result<_, _>>()?;
            match xs.as_slice() {
                [x, y, z] => Ok(DVec3::new(*x, *y, *z)),
                _ => Err(fail(format!("`{key}` needs three numbers x,y,z"))),
            }
        };
        match key.trim() {
            "eye" => eye = Some(vector(value)?),
            "target" => target = Some(vector(value)?),
            "up" => up = vector(value)?.as_vec3(),
            "fov" => projection.fov_y = (number(value)? as f32).to_radians(),
            "near" => projection.near = number(value)? as f32,
            "far" => projection.far = Some(number(value)? as f32),
            other => {
                return Err(fail(format!(
                    "unknown key `{other}` (expected eye, target, up, fov, near, far)"
                )));
            }
        }
    }
    if choice.infinite_far {
        projection.far = None;
    }
    let eye = eye.ok_or_else(|| fail("`eye` is missing".into()))?;
    let target = target.ok_or_else(|| fail("`target` is missing".into()))?;
    if (target - eye).length() < 1e-9 {
        return Err(fail("`eye` and `target` are the same point".into()));
    }
    if !(projection.fov_y > 0.0 && projection.fov_y < std::f32::consts::PI) {
        return Err(fail("`fov` must be in (0, 180) degrees".into()));
    }
    let near_ok = projection.near.is_finite() && projection.near > 0.0;
    if !near_ok || projection.far.is_some_and(|f| f <= projection.near) {
        return Err(fail("`near` must be positive and below `far`".into()));
    }
    Ok(Camera::look_at(eye, target, up, projection))
}
