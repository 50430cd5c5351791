//! Choosing a camera from the command line (`--camera` of `ppr-render` and the
//! walkthrough): a camera of the level by name, or `"eye=x,y,z;target=x,y,z;fov=60"`
//! (optionally `up=x,y,z`, `near=0.05`, `far=500`).

use glam::{DVec3, Vec3};
use ppr_runtime::{Camera, DepthMode, Projection};

use crate::error::CameraSpecError;
use crate::level_data::{LevelCamera, LevelData};

/// The projection choices of a command line, applied to whichever camera is picked.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ProjectionChoice {
    /// Standard or reversed Z.
    pub depth: DepthMode,
    /// Replace the far plane by an infinite one.
    pub infinite_far: bool,
}

impl ProjectionChoice {
    /// The projection of `camera` (its field of view, near and far planes) with these choices.
    pub fn projection_of(self, camera: &LevelCamera) -> Projection {
        Projection {
            fov_y: camera.yfov,
            near: camera.znear,
            far: if self.infinite_far { None } else { camera.zfar },
            depth: self.depth,
            matrix: None,
        }
    }
}

/// What a camera spec picks in a level.
#[derive(Debug)]
pub enum CameraPick<'a> {
    /// A camera of the level file (the first when no spec was given).
    Level(&'a LevelCamera),
    /// A camera described by the text.
    Described(Camera),
    /// No spec was given and the level has no camera.
    None,
}

/// Picks the camera `spec` names in `level`: `None` is the level's first camera, text with
/// `=` is parsed as `eye=...;target=...;fov=...`, anything else is a camera name.
///
/// # Errors
/// A name the level has no camera of (the error lists the level's cameras), or text that
/// does not parse ([`parse_camera`]).
pub fn pick_camera<'a>(
    level: &'a LevelData,
    spec: Option<&str>,
    choice: ProjectionChoice,
) -> Result<CameraPick<'a>, CameraSpecError> {
    match spec {
        None => Ok(level.cameras.first().map_or(CameraPick::None, CameraPick::Level)),
        Some(text) if text.contains('=') => parse_camera(text, choice).map(CameraPick::Described),
        Some(name) => level.camera(name).map(CameraPick::Level).ok_or_else(|| {
            let names: Vec<&str> = level.cameras.iter().map(|c| c.name.as_str()).collect();
            CameraSpecError {
                text: name.to_owned(),
                reason: format!("no such camera (the level has: {})", names.join(", ")),
            }
        }),
    }
}

/// Parses `"eye=x,y,z;target=x,y,z;fov=60"` (degrees; `up`, `near` and `far` optional).
///
/// # Errors
/// [`CameraSpecError`] naming the key that is missing or malformed, or the degenerate view
/// or projection.
pub fn parse_camera(text: &str, choice: ProjectionChoice) -> Result<Camera, CameraSpecError> {
    let fail = |reason: String| CameraSpecError { text: text.to_owned(), reason };
    let mut eye = None;
    let mut target = None;
    let mut up = Vec3::Y;
    let mut projection = Projection { depth: choice.depth, ..Projection::default() };
    for part in text.split(';').map(str::trim).filter(|p| !p.is_empty()) {
        let (key, value) = part.split_once('=').ok_or_else(|| fail(format!("`{part}` is not key=value")))?;
        let number = |v: &str| v.trim().parse::<f64>().map_err(|e| fail(format!("`{key}`: {v:?}: {e}")));
        let vector = |v: &str| -> Result<DVec3, CameraSpecError> {
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
