//! The `--camera` argument: a camera of the level by name, or
//! `"eye=x,y,z;target=x,y,z;fov=60"` (optionally `up=`, `near=`, `far=`), as `ppr-render`
//! takes it, so a headless frame and the testbed's frame can be asked for the same view.

use anyhow::{Context, Result, anyhow, bail};
use glam::{DVec3, Vec3};
use ppr_runtime::{Camera, DepthMode, Projection};

use crate::gltf_level::{LevelCamera, LevelData};

/// Depth convention and far plane, applied to whichever camera is picked.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ProjectionChoice {
    pub depth: DepthMode,
    /// Replace the far plane by an infinite one.
    pub infinite_far: bool,
}

/// The runtime camera of a level camera, with its field of view and near/far planes.
pub fn level_camera(camera: &LevelCamera, choice: ProjectionChoice) -> Camera {
    let (position, rotation) = camera.position_rotation();
    let far = if choice.infinite_far { None } else { camera.zfar };
    Camera {
        position,
        rotation,
        projection: Projection {
            fov_y: camera.yfov,
            near: camera.znear,
            far,
            depth: choice.depth,
            matrix: None,
        },
    }
}

/// The camera `spec` names: `None` is the level's first camera (or a view of the whole
/// level when it has none); text with `=` is parsed; anything else is a camera name.
///
/// # Errors
/// An unknown name (the error lists the level's cameras) or text that does not parse.
pub fn pick_camera(level: &LevelData, spec: Option<&str>, choice: ProjectionChoice) -> Result<Camera> {
    match spec {
        None => Ok(level
            .cameras
            .first()
            .map_or_else(|| overview_camera(level, choice), |c| level_camera(c, choice))),
        Some(text) if text.contains('=') => parse_camera(text, choice),
        Some(name) => level.camera(name).map(|c| level_camera(c, choice)).ok_or_else(|| {
            let names: Vec<&str> = level.cameras.iter().map(|c| c.name.as_str()).collect();
            anyhow!("no camera {name:?} in the level (it has: {})", names.join(", "))
        }),
    }
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

/// Parses `"eye=x,y,z;target=x,y,z;fov=60"` (degrees; `up`, `near`, `far` optional).
///
/// # Errors
/// A missing or malformed key, a degenerate view or projection.
pub fn parse_camera(text: &str, choice: ProjectionChoice) -> Result<Camera> {
    let mut eye = None;
    let mut target = None;
    let mut up = Vec3::Y;
    let mut projection = Projection { depth: choice.depth, ..Projection::default() };
    for part in text.split(';').map(str::trim).filter(|p| !p.is_empty()) {
        let (key, value) = part.split_once('=').ok_or_else(|| anyhow!("`{part}` is not key=value"))?;
        let number = |v: &str| v.trim().parse::<f64>().with_context(|| format!("`{key}`: {v:?}"));
        let vector = |v: &str| -> Result<DVec3> {
            let xs = v.split(',').map(number).collect::<Result<Vec<_>>>()?;
            match xs.as_slice() {
                [x, y, z] => Ok(DVec3::new(*x, *y, *z)),
                _ => bail!("`{key}` needs three numbers x,y,z"),
            }
        };
        match key.trim() {
            "eye" => eye = Some(vector(value)?),
            "target" => target = Some(vector(value)?),
            "up" => up = vector(value)?.as_vec3(),
            "fov" => projection.fov_y = (number(value)? as f32).to_radians(),
            "near" => projection.near = number(value)? as f32,
            "far" => projection.far = Some(number(value)? as f32),
            other => bail!("unknown key `{other}` (expected eye, target, up, fov, near, far)"),
        }
    }
    if choice.infinite_far {
        projection.far = None;
    }
    let eye = eye.ok_or_else(|| anyhow!("camera {text:?}: `eye` is missing"))?;
    let target = target.ok_or_else(|| anyhow!("camera {text:?}: `target` is missing"))?;
    if (target - eye).length() < 1e-9 {
        bail!("camera {text:?}: `eye` and `target` are the same point");
    }
    if !(projection.fov_y > 0.0 && projection.fov_y < std::f32::consts::PI) {
        bail!("camera {text:?}: `fov` must be in (0, 180) degrees");
    }
    if !(projection.near > 0.0 && projection.near.is_finite())
        || projection.far.is_some_and(|f| f <= projection.near)
    {
        bail!("camera {text:?}: `near` must be positive and below `far`");
    }
    Ok(Camera::look_at(eye, target, up, projection))
}

#[cfg(test)]
mod tests {
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
