//! Random test scenes: mirrors among boxes in a room, puddles on a floor, random cameras,
//! parallel groups by normal (deterministic, seeded).

use glam::{DVec3, Vec3};
use ppr_runtime::{Camera, Projection};

use crate::scene::{Albedo, AnalyticScene};

/// xorshift64*: deterministic test randomness (`unit`: uniform in [0, 1)).
pub struct Rng(pub u64);
impl Rng {
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// Puddles: many small coplanar mirrors on the floor (one plane, one parallel group), the
/// case where a tile test that gives up on tiles straddling the plane culls nothing.
pub fn puddle_floor(rng: &mut Rng) -> AnalyticScene {
    let mut s = AnalyticScene::default();
    s.quad(
        DVec3::new(0.0, -0.001, 0.0),
        DVec3::X,
        DVec3::NEG_Z,
        [12.0, 12.0],
        Albedo::Solid(Vec3::splat(0.3)),
    );
    s.quad(DVec3::new(0.0, 3.0, -10.0), DVec3::X, DVec3::Y, [12.0, 3.0], Albedo::Waves(0.3));
    for _ in 0..3 {
        let c = DVec3::new(rng.range(-4.0, 4.0), 0.0, rng.range(-8.0, 0.0));
        let colour = Vec3::new(rng.unit() as f32, rng.unit() as f32, rng.unit() as f32);
        s.cuboid(c - DVec3::new(0.4, 0.0, 0.4), c + DVec3::new(0.4, rng.range(0.5, 2.0), 0.4), colour);
    }
    for i in 0..24 {
        let c =
            DVec3::new(-5.0 + (i % 6) as f64 * 2.0 + rng.range(-0.3, 0.3), 0.0, -9.0 + (i / 6) as f64 * 2.5);
        s.mirror(
            &format!("puddle {i}"),
            c,
            DVec3::X,
            DVec3::NEG_Z,
            [rng.range(0.3, 0.8), rng.range(0.3, 0.8)],
        );
    }
    s
}

/// A random soup of mirrors (a stairway of parallel steps when `parallel`, else all
/// orientations different) among boxes, inside a room of coloured walls.
pub fn random_scene(rng: &mut Rng, parallel: bool) -> AnalyticScene {
    let mut s = AnalyticScene::default();
    s.quad(DVec3::new(0.0, -0.01, 0.0), DVec3::X, DVec3::NEG_Z, [12.0, 12.0], Albedo::Waves(0.2));
    s.quad(DVec3::new(0.0, 3.0, -10.0), DVec3::X, DVec3::Y, [12.0, 3.0], Albedo::Waves(0.3));
    for _ in 0..4 {
        let c = DVec3::new(rng.range(-5.0, 5.0), 0.0, rng.range(-8.0, 2.0));
        let size = DVec3::new(rng.range(0.3, 1.5), rng.range(0.3, 2.5), rng.range(0.3, 1.5));
        let colour = Vec3::new(rng.unit() as f32, rng.unit() as f32, rng.unit() as f32);
        s.cuboid(
            c - DVec3::new(size.x, 0.0, size.z) * 0.5,
            c + DVec3::new(size.x * 0.5, size.y, size.z * 0.5),
            colour,
        );
    }
    let count = 5 + (rng.unit() * 4.0) as usize;
    for i in 0..count {
        let name = format!("mirror {i}");
        if parallel {
            // Stairway steps: all facing up, at rising heights.
            let c = DVec3::new(rng.range(-3.0, 3.0), 0.1 + 0.2 * i as f64, rng.range(-6.0, 0.0));
            s.mirror(&name, c, DVec3::X, DVec3::NEG_Z, [rng.range(1.0, 2.5), rng.range(0.6, 1.5)]);
        } else {
            // Distinct orientations: tilted about a random axis by a distinct angle.
            let yaw = rng.range(0.0, std::f64::consts::TAU);
            let tilt = 0.15 + 0.3 * i as f64;
            let n = DVec3::new(tilt.sin() * yaw.cos(), tilt.cos(), tilt.sin() * yaw.sin()).normalize();
            let u = n.cross(DVec3::Y).try_normalize().unwrap_or(DVec3::X);
            let v = n.cross(u);
            let c = DVec3::new(rng.range(-3.0, 3.0), rng.range(0.1, 1.5), rng.range(-6.0, 0.0));
            s.mirror(&name, c, u, v, [rng.range(1.0, 2.5), rng.range(0.6, 1.5)]);
        }
    }
    s
}

pub fn random_camera(rng: &mut Rng) -> Camera {
    let eye = DVec3::new(rng.range(-3.0, 3.0), rng.range(1.0, 4.0), rng.range(3.0, 6.0));
    let target = DVec3::new(rng.range(-2.0, 2.0), rng.range(0.0, 1.0), rng.range(-6.0, -2.0));
    Camera::look_at(
        eye,
        target,
        Vec3::Y,
        Projection { fov_y: rng.range(0.6, 1.4) as f32, ..Default::default() },
    )
}

/// The set of a scene, with parallel groups by normal.
pub fn grouped_set(scene: &AnalyticScene) -> ppr_format::ReflectorSet {
    let mut set = scene.reflector_set();
    let mut normals: Vec<DVec3> = Vec::new();
    for r in &mut set.reflectors {
        let g = normals.iter().position(|n| n.dot(r.normal) > 1.0 - 1e-9).unwrap_or_else(|| {
            normals.push(r.normal);
            normals.len() - 1
        });
        r.parallel_group = g as u32;
    }
    set
}
