//! A small room with a floor mirror, two cameras on it and their frames: the views the API
//! tests render (`it/api.rs`) and the bound upload's test (`it/bound_upload.rs`); a
//! stairway of mirror treads beside mirror shelves and its cameras (`it/parallel_trees.rs`,
//! `it/path_blockers.rs`, the stability tests).

use glam::{DVec3, Vec3};
use ppr_runtime::{Camera, Projection};

use crate::harness::GpuFrame;
use crate::scene::{Albedo, AnalyticScene};

/// The views' size.
pub const SIZE: [u32; 2] = [128, 96];

/// A floor mirror in a small room (tiles active over the lower part of the screen only).
pub fn room() -> AnalyticScene {
    let mut s = AnalyticScene::default();
    s.quad(
        DVec3::new(0.0, -0.001, -4.0),
        DVec3::X,
        DVec3::NEG_Z,
        [8.0, 8.0],
        Albedo::Solid(Vec3::splat(0.25)),
    );
    s.quad(DVec3::new(0.0, 2.5, -8.0), DVec3::X, DVec3::Y, [6.0, 2.5], Albedo::Waves(0.25));
    s.cuboid(DVec3::new(-1.2, 0.0, -4.6), DVec3::new(-0.2, 1.0, -3.8), Vec3::new(0.9, 0.15, 0.1));
    s.mirror("floor mirror", DVec3::new(0.0, 0.0, -3.0), DVec3::X, DVec3::NEG_Z, [1.5, 1.2]);
    s
}

/// A camera at `eye` looking into the room.
pub fn room_camera(eye: DVec3) -> Camera {
    Camera::look_at(eye, DVec3::new(0.0, 0.5, -5.0), Vec3::Y, Projection::default())
}

/// `s`'s set, two cameras on it and their frames (a split screen's two views).
pub fn two_views_of(s: &AnalyticScene) -> (ppr_format::ReflectorSet, [Camera; 2], Vec<GpuFrame>) {
    let cams = [room_camera(DVec3::new(0.3, 1.6, 2.0)), room_camera(DVec3::new(-1.5, 2.4, 1.0))];
    let frames = cams.iter().map(|c| GpuFrame::upload(&s.render(c, SIZE))).collect();
    (s.reflector_set(), cams, frames)
}

/// The room with a water layer beside its floor mirror: its validated set, two cameras
/// and their frames.
pub fn pond_views() -> (ppr_format::ValidatedSet, [Camera; 2], Vec<GpuFrame>) {
    let mut s = room();
    s.water("pond", DVec3::new(1.6, 0.002, -5.5), DVec3::X, DVec3::NEG_Z, [1.0, 0.8]);
    let (set, cams, frames) = two_views_of(&s);
    (crate::harness::validated(&set), cams, frames)
}

/// A stairway of `n` mirror treads with matte risers, mirror shelves beside it at other
/// heights (the same family: one normal), a patterned wall and boxes to reflect.
pub fn stairway(n: usize) -> AnalyticScene {
    let mut s = AnalyticScene::default();
    let (rise, run) = (2.0 / n as f64, 4.0 / n as f64);
    s.quad(
        DVec3::new(0.0, -0.001, -3.0),
        DVec3::X,
        DVec3::NEG_Z,
        [6.0, 6.0],
        Albedo::Solid(Vec3::splat(0.3)),
    );
    s.quad(DVec3::new(0.0, 2.5, -6.0), DVec3::X, DVec3::Y, [6.0, 2.5], Albedo::Waves(0.3));
    s.cuboid(DVec3::new(-0.6, 2.2, -3.5), DVec3::new(0.2, 2.9, -2.9), Vec3::new(0.9, 0.2, 0.1));
    s.cuboid(DVec3::new(1.8, 0.0, -2.0), DVec3::new(2.4, 1.6, -1.4), Vec3::new(0.1, 0.3, 0.9));
    for i in 0..n {
        let y = (i + 1) as f64 * rise;
        let z = -1.0 - i as f64 * run;
        s.quad(DVec3::new(0.0, y - 0.5 * rise, z), DVec3::X, DVec3::Y, [1.2, 0.5 * rise], Albedo::Waves(0.6));
        s.mirror(
            &format!("tread {i}"),
            DVec3::new(0.0, y, z - 0.5 * run),
            DVec3::X,
            DVec3::NEG_Z,
            [1.2, 0.5 * run],
        );
    }
    for k in 0..6 {
        let c = DVec3::new(-2.6 + 0.2 * k as f64, 0.3 + 0.25 * k as f64, -1.5 - 0.5 * k as f64);
        s.mirror(&format!("shelf {k}"), c, DVec3::X, DVec3::NEG_Z, [0.5, 0.3]);
    }
    s
}

/// Three views of [`stairway`]: from the front above, from the side, from low on the right.
pub fn stairway_cameras() -> Vec<Camera> {
    let look = |eye: DVec3, at: DVec3, fov: f32| {
        Camera::look_at(eye, at, Vec3::Y, Projection { fov_y: fov, ..Default::default() })
    };
    vec![
        look(DVec3::new(0.3, 2.6, 1.5), DVec3::new(0.0, 0.8, -3.0), 1.1),
        look(DVec3::new(-2.5, 3.2, 0.0), DVec3::new(0.5, 0.8, -3.0), 1.0),
        look(DVec3::new(2.0, 1.4, 0.5), DVec3::new(-0.5, 1.0, -4.0), 1.0),
    ]
}
