//! Cameras inside the generated mirror rooms: views across the room, onto a box and along
//! the floor; in the corridor, along it and onto one of the facing mirrors.

use glam::{DVec3, Vec3};
use ppr_runtime::{Camera, Projection};

use crate::cameras::NamedCamera;
use crate::mirror_room::MirrorRoom;

fn projection() -> Projection {
    Projection { fov_y: 60f32.to_radians(), near: 0.05, far: Some(60.0), ..Projection::default() }
}

fn camera(name: &str, eye: [f64; 3], target: [f64; 3]) -> NamedCamera {
    NamedCamera {
        name: name.into(),
        camera: Camera::look_at(DVec3::from(eye), DVec3::from(target), Vec3::Y, projection()),
    }
}

/// The cameras of `room`, the most telling first.
pub fn cameras(room: MirrorRoom) -> Vec<NamedCamera> {
    match room {
        MirrorRoom::BoxesInBox { .. } => vec![
            camera("corner", [3.2, 1.7, 2.4], [-2.0, 0.6, -1.5]),
            camera("box", [-3.0, 1.4, 2.2], [-1.5, 0.6, -0.8]),
            camera("low", [0.5, 0.4, 2.5], [-1.0, 0.2, -3.0]),
        ],
        MirrorRoom::Corridor => vec![
            camera("along", [0.4, 1.6, 7.0], [-0.3, 1.2, -8.0]),
            camera("side", [1.0, 1.6, 0.0], [-1.5, 1.3, -2.5]),
            camera("down", [0.0, 2.4, 5.0], [0.0, 0.0, -2.0]),
        ],
    }
}
