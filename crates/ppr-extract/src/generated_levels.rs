//! Levels built in code for tests and measurements: a furnished box room, grids of such
//! rooms, and copies of any level side by side (the same room inside ever larger levels).

use glam::{DQuat, DVec3};

use crate::{Level, MaterialInfo};

/// A furnished room: its size and how finely its surfaces are tessellated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoomSpec {
    /// Floor size along x and z, and wall height, metres.
    pub size: DVec3,
    /// Cells per metre along each surface (two triangles per cell; at least one cell per side).
    pub cells_per_m: f64,
    /// Angle between the left wall's two triangles, degrees (0: a flat wall; 1: the 1°
    /// kink of a sloppy export).
    pub left_wall_kink_deg: f64,
}

impl Default for RoomSpec {
    /// A 6 × 5 m room, 3 m high, one cell per metre.
    fn default() -> Self {
        Self { size: DVec3::new(6.0, 3.0, 5.0), cells_per_m: 1.0, left_wall_kink_deg: 0.0 }
    }
}

/// A polished material, so both candidate rules keep every surface.
pub fn polished() -> MaterialInfo {
    MaterialInfo { name: "polished".into(), roughness: 0.05, ..MaterialInfo::gltf_default() }
}

/// A `w × h` rectangle at `origin` spanned by unit `u` and `v` (facing `u × v`), cut into
/// cells of about `1 / cells_per_m`; cells where `keep(s, t)` (their centre, in [0, 1]²) is
/// false are left out.
pub fn quad(
    out: &mut Vec<[DVec3; 3]>,
    origin: DVec3,
    [u, v]: [DVec3; 2],
    [w, h]: [f64; 2],
    cells_per_m: f64,
    keep: &dyn Fn(f64, f64) -> bool,
) {
    let nu = ((w * cells_per_m).round() as usize).max(1);
    let nv = ((h * cells_per_m).round() as usize).max(1);
    let p = |i: usize, j: usize| origin + u * (w * i as f64 / nu as f64) + v * (h * j as f64 / nv as f64);
    for i in 0..nu {
        for j in 0..nv {
            if keep((i as f64 + 0.5) / nu as f64, (j as f64 + 0.5) / nv as f64) {
                out.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
                out.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
            }
        }
    }
}

/// An axis-aligned box's six faces, outward, around `center` with half sizes `half`.
pub fn cuboid(out: &mut Vec<[DVec3; 3]>, center: DVec3, half: DVec3, cells_per_m: f64) {
    let lo = center - half;
    let s = half * 2.0;
    let all = &|_: f64, _: f64| true;
    let (x, y, z) = (DVec3::X, DVec3::Y, DVec3::Z);
    quad(out, lo, [z, x], [s.z, s.x], cells_per_m, all); // bottom, facing -y
    quad(out, lo + y * s.y, [x, z], [s.x, s.z], cells_per_m, all); // top, +y
    quad(out, lo, [x, y], [s.x, s.y], cells_per_m, all); // front, -z
    quad(out, lo + z * s.z, [y, x], [s.y, s.x], cells_per_m, all); // back, +z
    quad(out, lo, [y, z], [s.y, s.z], cells_per_m, all); // left, -x
    quad(out, lo + x * s.x, [z, y], [s.z, s.y], cells_per_m, all); // right, +x
}

/// The triangles of one room with its floor's corner at `origin`: floor, ceiling and walls
/// facing inwards, a window cut into the back wall, an L-shaped rug, a table, a shelf and
/// a mirror on the right wall.
pub fn room_triangles(spec: &RoomSpec, origin: DVec3) -> Vec<[DVec3; 3]> {
    let RoomSpec { size, cells_per_m: c, left_wall_kink_deg } = *spec;
    let (x, y, z) = (DVec3::X, DVec3::Y, DVec3::Z);
    let all = &|_: f64, _: f64| true;
    let mut t = Vec::new();
    quad(&mut t, origin, [z, x], [size.z, size.x], c, all); // floor, facing +y
    quad(&mut t, origin + y * size.y, [x, z], [size.x, size.z], c, all); // ceiling, -y
    // Back wall (z = 0, facing +z) with a window in its middle.
    let window = |s: f64, t: f64| !((0.35..0.65).contains(&s) && (0.4..0.8).contains(&t));
    quad(&mut t, origin, [x, y], [size.x, size.y], c, &window);
    quad(&mut t, origin + z * size.z, [y, x], [size.y, size.x], c, all); // front wall, -z
    quad(&mut t, origin + x * size.x, [z, y], [size.z, size.y], c, all); // right wall, -x
    // Left wall (x = 0, facing +x): two triangles; the lower one hinged on the shared
    // diagonal by the kink angle.
    let (a, b, cc, d) = (origin, origin + y * size.y, origin + y * size.y + z * size.z, origin + z * size.z);
    let turn = DQuat::from_axis_angle((cc - a).normalize(), left_wall_kink_deg.to_radians());
    t.push([a, b, cc]);
    t.push([a, cc, a + turn * (d - a)]);
    // An L-shaped rug 1 cm above the floor.
    let rug = |s: f64, t: f64| s < 0.4 || t < 0.4;
    quad(&mut t, origin + DVec3::new(0.5, 0.01, 0.5), [z, x], [2.0, 2.0], c.max(2.0), &rug);
    // A table and a shelf (boxes), a mirror on the right wall.
    cuboid(&mut t, origin + DVec3::new(size.x * 0.6, 0.4, size.z * 0.5), DVec3::new(0.8, 0.4, 0.5), c);
    cuboid(&mut t, origin + DVec3::new(size.x * 0.3, 1.6, size.z - 0.2), DVec3::new(0.6, 0.02, 0.15), c);
    quad(&mut t, origin + DVec3::new(size.x - 0.01, 1.0, size.z * 0.3), [z, y], [1.0, 1.2], c, all);
    t
}

/// `nx × nz` rooms on a grid with `spacing` metres between room corners.
pub fn room_grid(spec: &RoomSpec, nx: usize, nz: usize, spacing: f64) -> Vec<[DVec3; 3]> {
    let mut t = Vec::new();
    for i in 0..nx {
        for k in 0..nz {
            t.extend(room_triangles(spec, DVec3::new(i as f64 * spacing, 0.0, k as f64 * spacing)));
        }
    }
    t
}

/// `count` copies of `level` in a row along x, `spacing` metres apart, sources and
/// materials shared.
pub fn copies(level: &Level, count: usize, spacing: f64) -> Level {
    let mut out = level.clone();
    out.triangles = (0..count)
        .flat_map(|k| {
            let offset = DVec3::X * (k as f64 * spacing);
            level.triangles.iter().map(move |t| crate::LevelTriangle {
                positions: t.positions.map(|p| p + offset),
                source: t.source,
            })
        })
        .collect();
    out.uvs = (0..count).flat_map(|_| level.uvs.iter().copied()).collect();
    out
}

/// A level of `triangles` with the [`polished`] material.
pub fn level_of(name: &str, triangles: &[[DVec3; 3]]) -> Level {
    Level::from_triangles(name, triangles, polished())
}
