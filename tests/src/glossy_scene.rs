//! The glossy tests' scene: a floor mirror, rough or not, in a room with textured walls and
//! two boxes, and the camera that looks at it.

use glam::{DVec3, Vec3};
use ppr_runtime::{Camera, Projection};

use glam::Vec4;

use crate::harness::{Comparison, compare};
use crate::masks::interior;
use crate::scene::{Albedo, AnalyticScene, Frame};

/// The frame size of the glossy tests.
pub const SIZE: [u32; 2] = [160, 120];

pub fn camera() -> Camera {
    Camera::look_at(DVec3::new(0.3, 1.9, 2.8), DVec3::new(-0.2, 0.4, -5.0), Vec3::Y, Projection::default())
}

/// A floor mirror (rough when `roughness` > 0) in a room with textured walls and a box.
pub fn scene(roughness: f64) -> AnalyticScene {
    let mut s = AnalyticScene::default();
    s.mirror("floor", DVec3::new(0.0, 0.0, -3.0), DVec3::X, DVec3::NEG_Z, [4.0, 5.0]);
    s.roughen("floor", roughness);
    s.quad(DVec3::new(0.0, 2.5, -8.0), DVec3::X, DVec3::Y, [6.0, 2.5], Albedo::Waves(0.25));
    for side in [-1.0, 1.0] {
        s.quad(
            DVec3::new(4.5 * side, 2.5, -4.0),
            DVec3::Z,
            DVec3::Y,
            [6.0, 2.5],
            Albedo::Gradient(Vec3::new(0.9, 0.6, 0.2), Vec3::new(0.2, 0.5, 0.9)),
        );
    }
    s.cuboid(DVec3::new(-1.2, 0.0, -4.6), DVec3::new(-0.4, 1.4, -3.8), Vec3::new(0.1, 0.8, 0.2));
    s.cuboid(DVec3::new(0.8, 0.0, -6.0), DVec3::new(1.6, 0.8, -5.2), Vec3::new(0.9, 0.2, 0.1));
    s
}

/// The output against `reference` over the floor's on-screen pixels, a pixel in from the
/// mask's border (the images saved into `dir`).
pub fn against(dir: &str, name: &str, frame: &Frame, out: &[Vec4], reference: &[Vec3]) -> Comparison {
    let f = Frame { reference: reference.to_vec(), ..frame.clone_images() };
    let mask = interior(&f, 1, |i| f.mirror[i].is_some() && f.on_screen[i]);
    crate::harness::save_comparison(dir, name, &f, out, |i| mask[i]);
    compare(&f, out, |i| mask[i])
}
