//! Choosing a camera from the command line: a glTF camera by name, or
//! `"eye=x,y,z;target=x,y,z;fov=60"` (optionally `up=x,y,z`, `near=0.05`, `far=500`), as
//! `ppr-scene-gpu`'s `camera_spec` reads it; a level without cameras needs a description.

use ppr_runtime::Camera;
use ppr_scene_gpu::{CameraPick, LevelData};

/// The projection choices of a command line, applied to whichever camera is picked.
pub use ppr_scene_gpu::ProjectionChoice;

use crate::TestbedError;

/// Picks the camera `spec` names in `level`: `None` is the level's first camera, text with
/// `=` is parsed as `eye=...;target=...;fov=...`, anything else is a camera name.
///
/// # Errors
/// [`TestbedError::CameraSpec`] when the level has no camera (and none was described),
/// the name is unknown (the error lists the level's cameras), or the text does not parse.
pub fn pick_camera(
    level: &LevelData,
    spec: Option<&str>,
    choice: ProjectionChoice,
) -> Result<Camera, TestbedError> {
    match ppr_scene_gpu::pick_camera(level, spec, choice)? {
        CameraPick::Level(camera) => Ok(camera.to_runtime_camera(choice)),
        CameraPick::Described(camera) => Ok(camera),
        CameraPick::None => Err(TestbedError::CameraSpec {
            text: String::new(),
            reason: "the level has no camera; pass one as \"eye=x,y,z;target=x,y,z;fov=60\"".into(),
        }),
    }
}

/// Parses `"eye=x,y,z;target=x,y,z;fov=60"` (degrees; `up`, `near` and `far` optional).
///
/// # Errors
/// [`TestbedError::CameraSpec`] naming the key that is missing or malformed.
pub fn parse_camera(text: &str, choice: ProjectionChoice) -> Result<Camera, TestbedError> {
    Ok(ppr_scene_gpu::parse_camera(text, choice)?)
}
