//! One floor mirror seen from straight above, sized so that its screen rectangle covers a
//! chosen share of the screen: the level of the indirect-dispatch threshold.

use glam::{DVec2, DVec3};
use ppr_format::{Reflector, ReflectorKind, ReflectorSet};
use ppr_runtime::{Camera, Projection};
use ppr_testbed::{Level, Material};

use crate::scaling::level_family::{GeneratedLevel, LevelFamily};
use crate::scaling::quad_builder::{QuadBuilder, scenery_color, v3};

/// Height of the camera above the mirror.
const HEIGHT: f64 = 10.0;

/// A mirror whose screen rectangle covers `coverage` (0..1] of a 16:9 view from 10 m above.
pub fn coverage_level(coverage: f64) -> GeneratedLevel {
    let projection =
        Projection { fov_y: 60f32.to_radians(), near: 0.05, far: Some(100.0), ..Projection::default() };
    let half_h = HEIGHT * (f64::from(projection.fov_y) * 0.5).tan();
    let half_w = half_h * 16.0 / 9.0;
    let s = coverage.clamp(1e-4, 1.0).sqrt();
    let mut level = Level::new();
    let mut q = QuadBuilder::default();
    let mirror = q.material(&mut level, Material::polished("mirror", [0.35, 0.35, 0.38]));
    let ground = q.material(&mut level, Material::matte("ground", [0.35, 0.3, 0.25]));
    q.quad(ground, v3(0.0, -0.01, 0.0), DVec3::X * 30.0, DVec3::NEG_Z * 30.0);
    let half = DVec2::new(half_w * s * 0.999, half_h * s * 0.999);
    q.quad(mirror, DVec3::ZERO, DVec3::X * half.x, DVec3::NEG_Z * half.y);
    for k in 0..6 {
        let m = q.material(&mut level, Material::matte(format!("box_{k}"), scenery_color(k)));
        let a = k as f64 * 1.047;
        q.cuboid(m, v3(4.0 * a.cos(), 1.0, 3.0 * a.sin()), v3(0.5, 1.0, 0.5));
    }
    q.finish(&mut level, "coverage");
    let mut set = ReflectorSet::new("generated:coverage");
    set.reflectors.push(Reflector::new(
        0,
        "floor mirror",
        ReflectorKind::Opaque,
        DVec3::ZERO,
        DVec3::Y,
        DVec3::X,
        half,
    ));
    // Straight down, with +z as the screen's "down" direction.
    let camera = Camera::look_at(v3(0.0, HEIGHT, 0.0), DVec3::ZERO, glam::Vec3::NEG_Z, projection);
    GeneratedLevel { family: LevelFamily::TiledFloor, level, reflectors: set, camera }
}
