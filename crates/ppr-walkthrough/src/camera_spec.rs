//! The `--camera` argument: a camera of the level by name, or
//! `"eye=x,y,z;target=x,y,z;fov=60"` (optionally `up=`, `near=`, `far=`), read by
//! `ppr-scene-gpu`'s `camera_spec` as `ppr-render` reads it, so a headless frame and the
//! testbed's frame can be asked for the same view; a level without cameras is seen whole.

use anyhow::Result;
use glam::{DVec3, Vec3};
use ppr_runtime::{Camera, Projection};
use ppr_scene_gpu::CameraPick;
/// Depth convention and far plane applied to whichever camera is picked, and the parser of
/// `eye=...;target=...;fov=...`.
pub use ppr_scene_gpu::{ProjectionChoice, parse_camera};

use crate::gltf_level::{LevelCamera, LevelData};

/// The runtime camera of a level camera, with its field of view and near/far planes.
pub fn level_camera(camera: &LevelCamera, choice: ProjectionChoice) -> Camera {
    camera.to_runtime_camera_f64(choice)
}

/// The camera `spec` names: `None` is the level's first camera (or a view of the whole
/// level when it has none); text with `=` is parsed; anything else is a camera name.
///
/// # Errors
/// An unknown name (the error lists the level's cameras) or text that does not parse.
pub fn pick_camera(level: &LevelData, spec: Option<&str>, choice: ProjectionChoice) -> Result<Camera> {
    Ok(match ppr_scene_gpu::pick_camera(level, spec, choice)? {
        CameraPick::Level(camera) => level_camera(camera, choice),
        CameraPick::Described(camera) => camera,
        CameraPick::None => overview_camera(level, choice),
    })
}

/// A camera outside the level's bounds looking at their centre.
pub fn overview_camera(level: &LevelData, choice: ProjectionChoice) -> Camera {
    let (lo, hi) = level.bounds().unwrap_or((DVec3::splat(-1.0), DVec3::splat(1.0)));
    let centre = (lo + hi) * 0.5;
    let radius = ((hi - lo).length() * 0.5).max(1.0);
    let eye = centre + DVec3::new(0.0, 0.5, 1.2).normalize() * radius * 1.5;
    let projection = Projection {
        near: (radius * 1e-3).max(0.01) as f32,
        far: (!choice.infinite_far).then_some((radius * 10.0) as f32),
        depth: choice.depth,
        ..Projection::default()
    };
    Camera::look_at(eye, centre, Vec3::Y, projection)
}

#[cfg(test)]
mod tests {
    use ppr_runtime::DepthMode;

    use super::*;

    #[test]
    fn parses_eye_target_fov() {
        let c = parse_camera("eye=0,1,5; target=0,1,0; fov=90; far=50", ProjectionChoice::default())
            .expect("parses");
        assert_eq!(c.position, DVec3::new(0.0, 1.0, 5.0));
        assert!((c.forward() - Vec3::NEG_Z).length() < 1e-6);
        assert!((c.projection.fov_y - 90f32.to_radians()).abs() < 1e-6);
        assert_eq!(c.projection.far, Some(50.0));
        let infinite = ProjectionChoice { depth: DepthMode::Reversed, infinite_far: true };
        let c = parse_camera("eye=0,1,5;target=0,1,0;far=50", infinite).expect("parses");
        assert_eq!((c.projection.far, c.projection.depth), (None, DepthMode::Reversed));
    }

    #[test]
    fn refuses_bad_text() {
        for bad in [
            "eye=0,1;target=0,0,0",
            "eye=0,0,0;target=0,0,0",
            "target=1,0,0",
            "eye=0,0,1;target=0,0,0;zoom=2",
        ] {
            assert!(parse_camera(bad, ProjectionChoice::default()).is_err(), "{bad}");
        }
    }
}
