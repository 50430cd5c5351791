//! Building level geometry from quads and boxes, one primitive per material.

use glam::{DMat4, DVec3, Vec3};
use ppr_testbed::level::{Mesh, MeshPrimitive, Vertex};
use ppr_testbed::{Level, Material};

/// Geometry gathered per material, turned into one mesh at the end.
#[derive(Default)]
pub struct QuadBuilder {
    prims: Vec<MeshPrimitive>,
}

impl QuadBuilder {
    /// Adds a material; returns its primitive slot.
    pub fn material(&mut self, level: &mut Level, material: Material) -> usize {
        let index = level.add_material(material);
        self.prims.push(MeshPrimitive { material: index, ..MeshPrimitive::default() });
        self.prims.len() - 1
    }

    /// The quad `center ± u ± v`, facing `u × v`.
    pub fn quad(&mut self, slot: usize, center: DVec3, u: DVec3, v: DVec3) {
        let prim = &mut self.prims[slot];
        let normal = u.cross(v).normalize().as_vec3();
        let base = prim.vertices.len() as u32;
        for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            let p = (center + u * su + v * sv).as_vec3();
            prim.vertices.push(Vertex {
                position: p.to_array(),
                normal: normal.to_array(),
                uv: [(su as f32 + 1.0) * 0.5, (1.0 - sv as f32) * 0.5],
            });
        }
        prim.indices.extend([base, base + 1, base + 2, base, base + 2, base + 3]);
    }

    /// An axis-aligned box with outward faces.
    pub fn cuboid(&mut self, slot: usize, center: DVec3, half: DVec3) {
        for (n, u, v) in [
            (DVec3::X, DVec3::NEG_Z, DVec3::Y),
            (DVec3::NEG_X, DVec3::Z, DVec3::Y),
            (DVec3::Y, DVec3::X, DVec3::NEG_Z),
            (DVec3::NEG_Y, DVec3::X, DVec3::Z),
            (DVec3::Z, DVec3::X, DVec3::Y),
            (DVec3::NEG_Z, DVec3::NEG_X, DVec3::Y),
        ] {
            self.quad(slot, center + n * half, u * half, v * half);
        }
    }

    /// Puts everything into `level` as one mesh placed at the origin.
    pub fn finish(self, level: &mut Level, name: &str) {
        let primitives: Vec<MeshPrimitive> =
            self.prims.into_iter().filter(|p| !p.indices.is_empty()).collect();
        let mesh = level.add_mesh(Mesh { name: name.into(), primitives });
        level.add_instance(name, mesh, DMat4::IDENTITY);
    }
}

/// A small palette of matte colours for scenery.
pub fn scenery_color(k: usize) -> [f32; 3] {
    const C: [[f32; 3]; 6] = [
        [0.8, 0.2, 0.15],
        [0.15, 0.6, 0.2],
        [0.2, 0.3, 0.85],
        [0.9, 0.8, 0.2],
        [0.75, 0.75, 0.75],
        [0.6, 0.2, 0.7],
    ];
    C[k % C.len()]
}

/// Unit vector helper for camera targets.
pub fn v3(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// `Vec3::Y`, the up direction of every generated camera.
pub const UP: Vec3 = Vec3::Y;
