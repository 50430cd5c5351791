//! An independent CPU ray tracer of a built-in level (f64, nearest hit over every
//! triangle, the G-buffer's lighting: one sun plus ambient, unlit materials as their base
//! colour) and the CPU glossy reflection the tests crate's analytic scene uses (GGX
//! microfacet normals, alpha = roughness², tan θ = alpha √(ξ/(1−ξ)), Hammersley points,
//! rays leaving below the surface left out).

use glam::{DVec3, Vec3};
use ppr_testbed::renderer::DEFAULT_BACKGROUND;
use ppr_testbed::{Level, Lighting};

/// Samples of the GGX lobe per pixel (as `ppr-tests`' `GLOSSY_SAMPLES`).
pub const GLOSSY_SAMPLES: u32 = 256;

struct Triangle {
    v0: DVec3,
    e1: DVec3,
    e2: DVec3,
    material: usize,
}

/// The level's triangles in world space with its lighting.
pub struct CpuTracer<'a> {
    level: &'a Level,
    triangles: Vec<Triangle>,
    light: DVec3,
    intensity: f64,
    ambient: DVec3,
}

impl<'a> CpuTracer<'a> {
    pub fn new(level: &'a Level, lighting: &Lighting) -> Self {
        let mut triangles = Vec::new();
        for inst in &level.instances {
            for prim in &level.meshes[inst.mesh].primitives {
                let p = |i: u32| {
                    inst.world.transform_point3(Vec3::from(prim.vertices[i as usize].position).as_dvec3())
                };
                for t in prim.indices.chunks_exact(3) {
                    let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
                    triangles.push(Triangle { v0: a, e1: b - a, e2: c - a, material: prim.material });
                }
            }
        }
        let (l, a) = lighting.uniform_vectors();
        Self {
            level,
            triangles,
            light: DVec3::new(f64::from(l[0]), f64::from(l[1]), f64::from(l[2])),
            intensity: f64::from(l[3]),
            ambient: DVec3::new(f64::from(a[0]), f64::from(a[1]), f64::from(a[2])),
        }
    }

    /// Linear colour seen along the ray from `o` in direction `d` (unit).
    pub fn trace(&self, o: DVec3, d: DVec3) -> DVec3 {
        let mut best: Option<(f64, &Triangle)> = None;
        for t in &self.triangles {
            // Möller–Trumbore.
            let p = d.cross(t.e2);
            let det = t.e1.dot(p);
            if det.abs() < 1e-14 {
                continue;
            }
            let inv = 1.0 / det;
            let s = o - t.v0;
            let u = s.dot(p) * inv;
            if !(0.0..=1.0).contains(&u) {
                continue;
            }
            let q = s.cross(t.e1);
            let v = d.dot(q) * inv;
            if v < 0.0 || u + v > 1.0 {
                continue;
            }
            let dist = t.e2.dot(q) * inv;
            if dist > 1e-6 && best.is_none_or(|(b, _)| dist < b) {
                best = Some((dist, t));
            }
        }
        let Some((_, t)) = best else {
            return DVec3::new(DEFAULT_BACKGROUND[0], DEFAULT_BACKGROUND[1], DEFAULT_BACKGROUND[2]);
        };
        let m = &self.level.materials[t.material];
        let base =
            DVec3::new(f64::from(m.base_color[0]), f64::from(m.base_color[1]), f64::from(m.base_color[2]));
        if m.unlit {
            return base;
        }
        let mut n = t.e1.cross(t.e2).normalize();
        if n.dot(d) > 0.0 {
            n = -n;
        }
        let lambert = n.dot(self.light).max(0.0) * self.intensity;
        let emissive =
            DVec3::new(f64::from(m.emissive[0]), f64::from(m.emissive[1]), f64::from(m.emissive[2]));
        base * (self.ambient + DVec3::splat(lambert)) + emissive
    }

    /// The glossy reflection seen along `dir` at `hit` on a surface of normal `n`.
    pub fn glossy(&self, roughness: f64, hit: DVec3, n: DVec3, dir: DVec3) -> DVec3 {
        let alpha = roughness * roughness;
        let (t, b) = n.any_orthonormal_pair();
        let (mut sum, mut count) = (DVec3::ZERO, 0u32);
        for k in 0..GLOSSY_SAMPLES {
            let xi = (f64::from(k) + 0.5) / f64::from(GLOSSY_SAMPLES);
            let phi = std::f64::consts::TAU * f64::from(k.reverse_bits()) / 2f64.powi(32);
            let tan = alpha * (xi / (1.0 - xi)).sqrt();
            let h = (n + tan * (phi.cos() * t + phi.sin() * b)).normalize();
            let r = dir - 2.0 * dir.dot(h) * h;
            if r.dot(n) > 0.0 {
                sum += self.trace(hit + n * 1e-9, r);
                count += 1;
            }
        }
        if count == 0 { DVec3::ZERO } else { sum / f64::from(count) }
    }
}
