//! A small room with a floor mirror, two cameras on it and their frames: the views the API
//! tests render (`it/api.rs`) and the bound upload's test (`it/bound_upload.rs`).

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
