//! The scaling family of rooms and corridors (issue 13): open rooms (floor, ceiling, three
//! walls) and corridor segments (floor, ceiling, two walls) on a 3D grid over a fixed
//! extent, each turned to its own orientation, every panel a mirror on both faces. So walls,
//! floors and ceilings face every way, as in a real level extracted with every planar
//! surface a reflector, and about half of them face any camera.

use glam::{DQuat, DVec2, DVec3};
use ppr_extract::occluders::occluder_lists;
use ppr_extract::parallel::parallel_groups;
use ppr_format::{Reflector, ReflectorKind, ReflectorSet};
use ppr_runtime::{Camera, Projection};
use ppr_testbed::{Level, Material};

use crate::scaling::level_family::{GeneratedLevel, LevelFamily};
use crate::scaling::quad_builder::{QuadBuilder, UP, scenery_color, v3};

/// Side of the square the modules stand on, metres (as the other families' 16 m).
const EXTENT: f64 = 16.0;
/// Thickness of a panel between its two mirror faces, in module half sizes.
const PANEL_THICKNESS: f64 = 0.03;

/// Deterministic value in [0, 1).
fn hash01(k: usize) -> f64 {
    let mut x = (k as u64).wrapping_mul(0xD6E8_FEB8_6659_FD93) ^ 0x2545_F491_4F6C_DD1D;
    x ^= x >> 32;
    x = x.wrapping_mul(0xD6E8_FEB8_6659_FD93);
    x ^= x >> 32;
    (x % 1_000_000) as f64 / 1_000_000.0
}

/// The panels of module `k` in its own frame (unit cube `[-1, 1]³`): (centre, u, v) half
/// vectors, `u × v` pointing into the module. Even modules are rooms (one side open),
/// odd ones corridors (two sides open).
fn module_panels(k: usize) -> Vec<(DVec3, DVec3, DVec3)> {
    let (x, y, z) = (DVec3::X, DVec3::Y, DVec3::Z);
    let mut p = vec![
        (-y, x, -z), // floor, facing +y
        (y, x, z),   // ceiling, facing -y
        (-x, -z, y), // left wall, facing +x
        (x, z, y),   // right wall, facing -x
    ];
    if k.is_multiple_of(2) {
        p.push((-z, x, y)); // back wall, facing +z
    }
    p
}

/// Generates the family with exactly `count` reflectors (at least one).
pub fn room_maze(count: usize) -> GeneratedLevel {
    let count = count.max(1);
    // About nine reflectors per module (rooms 10, corridors 8).
    let modules = count.div_ceil(9).max(1);
    // Storeys: about half the cube root of the module count (a building, not a tower).
    let storeys = ((modules as f64).cbrt() * 0.5).round().max(1.0) as usize;
    let side = ((modules as f64 / storeys as f64).sqrt().ceil() as usize).max(1);
    let (nx, nz) = (side, side);
    let cell = EXTENT / nx as f64;
    let layers = modules.div_ceil(nx * nz).max(1);
    // A module's half size: turned any way, it stays inside its cell (half diagonal √3).
    let half = cell * 0.5 / 3f64.sqrt() * 0.95;

    let mut level = Level::new();
    let mut q = QuadBuilder::default();
    let mirror = q.material(&mut level, Material::polished("mirror", [0.55, 0.55, 0.6]));
    let tinted: Vec<usize> = (0..6)
        .map(|k| q.material(&mut level, Material::polished(format!("tinted_{k}"), scenery_color(k))))
        .collect();
    let ground = q.material(&mut level, Material::matte("ground", [0.35, 0.3, 0.25]));
    q.quad(ground, v3(0.0, -0.05, 0.0), DVec3::X * (EXTENT * 0.6), DVec3::NEG_Z * (EXTENT * 0.6));
    let mut set = ReflectorSet::new(format!("generated:{}:{count}", LevelFamily::Rooms.as_str()));
    'modules: for k in 0..modules {
        let (i, j, l) = (k % nx, (k / nx) % nz, k / (nx * nz));
        let center = v3(
            -EXTENT * 0.5 + (i as f64 + 0.5) * cell,
            (l as f64 + 0.5) * cell,
            -EXTENT * 0.5 + (j as f64 + 0.5) * cell,
        );
        // The first module upright (its floor faces a camera above), the others any way.
        let turn = if k == 0 {
            DQuat::IDENTITY
        } else {
            DQuat::from_euler(
                glam::EulerRot::YXZ,
                std::f64::consts::TAU * hash01(3 * k),
                std::f64::consts::PI * (hash01(3 * k + 1) - 0.5),
                std::f64::consts::TAU * hash01(3 * k + 2),
            )
        };
        for (p, (c, u, v)) in module_panels(k).into_iter().enumerate() {
            let material = if p == 0 { tinted[k % tinted.len()] } else { mirror };
            let n = u.cross(v);
            // The inner face towards the module's centre, the outer one a panel's thickness
            // further out, facing out.
            for (face_center, fu, fv) in [(c, u, v), (c - n * PANEL_THICKNESS, v, u)] {
                if set.reflectors.len() == count {
                    break 'modules;
                }
                let center_w = center + turn * (face_center * half);
                let (u_w, v_w) = (turn * (fu * half), turn * (fv * half));
                let id = set.next_id();
                set.reflectors.push(Reflector::new(
                    id,
                    format!("rooms-{id}"),
                    ReflectorKind::Opaque,
                    center_w,
                    u_w.cross(v_w).normalize(),
                    u_w.normalize(),
                    DVec2::new(u_w.length(), v_w.length()),
                ));
                q.quad(material, center_w, u_w, v_w);
            }
        }
    }
    q.finish(&mut level, LevelFamily::Rooms.as_str());
    // Parallel groups and occluder lists as the extractor builds them (a module's panels
    // hide each other and its neighbours').
    let normals: Vec<DVec3> = set.reflectors.iter().map(|r| r.normal).collect();
    for (r, g) in set.reflectors.iter_mut().zip(parallel_groups(&normals, 1f64.to_radians().cos())) {
        r.parallel_group = g;
    }
    let lists = occluder_lists(&set.reflectors, DVec3::ZERO, 1e-4, 1.5 * cell);
    for (r, list) in set.reflectors.iter_mut().zip(lists) {
        r.occluders = list;
    }
    let top = layers as f64 * cell;
    let camera = Camera::look_at(
        v3(-7.0, top + 5.0, 11.0),
        v3(0.0, top * 0.3, -1.5),
        UP,
        Projection { fov_y: 60f32.to_radians(), near: 0.05, far: Some(200.0), ..Projection::default() },
    );
    GeneratedLevel { family: LevelFamily::Rooms, level, reflectors: set, camera }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn panels_face_into_their_module() {
        for k in 0..2 {
            for (c, u, v) in module_panels(k) {
                assert!(u.cross(v).dot(-c) > 0.0, "module {k}: panel at {c} faces out");
            }
        }
    }
}
