//! Simple meshes built in code (cuboids, quads) for synthetic test levels.

use glam::Vec3;

use crate::level::{MeshPrimitive, Vertex};

/// An axis-aligned cuboid centred on the origin with the given half sizes, outward normals
/// and counter-clockwise front faces; each face has UVs over `[0, 1]²`.
pub fn cuboid(half: Vec3, material: usize) -> MeshPrimitive {
    let mut prim = MeshPrimitive { material, ..MeshPrimitive::default() };
    for (normal, u_axis, v_axis) in [
        (Vec3::X, Vec3::NEG_Z, Vec3::Y),
        (Vec3::NEG_X, Vec3::Z, Vec3::Y),
        (Vec3::Y, Vec3::X, Vec3::NEG_Z),
        (Vec3::NEG_Y, Vec3::X, Vec3::Z),
        (Vec3::Z, Vec3::X, Vec3::Y),
        (Vec3::NEG_Z, Vec3::NEG_X, Vec3::Y),
    ] {
        let center = normal * half;
        let u = u_axis * half;
        let v = v_axis * half;
        add_quad(&mut prim, center, u, v, normal);
    }
    prim
}

/// A rectangle in the XZ plane facing +Y, centred on the origin, with the given half sizes
/// along X and Z (a floor); UVs cover `[0, uv_repeat]²`.
pub fn floor_quad(half_x: f32, half_z: f32, uv_repeat: f32, material: usize) -> MeshPrimitive {
    let mut prim = MeshPrimitive { material, ..MeshPrimitive::default() };
    add_quad(&mut prim, Vec3::ZERO, Vec3::X * half_x, Vec3::NEG_Z * half_z, Vec3::Y);
    for v in &mut prim.vertices {
        v.uv = [v.uv[0] * uv_repeat, v.uv[1] * uv_repeat];
    }
    prim
}

/// Appends the quad `center ± u ± v` facing `normal` (`u × v` must point along `normal`).
fn add_quad(prim: &mut MeshPrimitive, center: Vec3, u: Vec3, v: Vec3, normal: Vec3) {
    let base = u32::try_from(prim.vertices.len()).expect("synthetic meshes are small");
    for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        let p = center + u * su + v * sv;
        prim.vertices.push(Vertex {
            position: p.to_array(),
            normal: normal.to_array(),
            uv: [(su + 1.0) * 0.5, (1.0 - sv) * 0.5],
        });
    }
    prim.indices.extend([base, base + 1, base + 2, base, base + 2, base + 3]);
}
