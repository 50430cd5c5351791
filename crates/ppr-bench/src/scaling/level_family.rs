//! The scaling family: stairways of mirror steps, tiled floors with puddles, facades of
//! windows and rooms turned every way (`room_maze.rs`), each with any number of reflectors over the same overall extent (so the screen
//! area that reflects stays about the same while the shape count grows), with parallel
//! groups and occluder lists built like the extractor's.

use glam::{DVec2, DVec3};
use ppr_extract::occluders::occluder_lists;
use ppr_extract::parallel::parallel_groups;
use ppr_format::{Reflector, ReflectorKind, ReflectorSet};
use ppr_runtime::{Camera, Projection};
use ppr_testbed::{Level, Material};

use crate::scaling::quad_builder::{QuadBuilder, UP, scenery_color, v3};

/// One family of generated levels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum LevelFamily {
    /// Mirror treads of a straight stairway (one parallel group, occluders: steps above).
    Stairway,
    /// Puddles on a tiled floor, one per tile (one plane).
    TiledFloor,
    /// Windows of a building facade (one plane).
    Facade,
    /// Rooms and corridors turned every way, every panel a mirror on both faces (many
    /// planes and orientations; `room_maze.rs`).
    Rooms,
}

impl LevelFamily {
    pub const ALL: [Self; 4] = [Self::Stairway, Self::TiledFloor, Self::Facade, Self::Rooms];

    pub fn as_str(self) -> &'static str {
        match self {
            Self::Stairway => "stairway",
            Self::TiledFloor => "tiled-floor",
            Self::Facade => "facade",
            Self::Rooms => "rooms",
        }
    }

    /// A bench scene name `<family>-<count>` (`stairway-10000`): the family and its count.
    pub fn from_scene_name(name: &str) -> Option<(Self, usize)> {
        let (family, count) = name.rsplit_once('-')?;
        let family = Self::ALL.into_iter().find(|f| f.as_str() == family)?;
        let count: usize = count.parse().ok()?;
        (1..=100_000).contains(&count).then_some((family, count))
    }
}

/// A generated level, its reflector set and the camera that sees all of it.
#[derive(Clone, Debug)]
pub struct GeneratedLevel {
    pub family: LevelFamily,
    pub level: Level,
    pub reflectors: ReflectorSet,
    pub camera: Camera,
}

/// Cheap deterministic hash to vary sizes.
fn hash01(k: usize) -> f64 {
    let mut x = (k as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0x5851_F42D_4C95_7F2D;
    x ^= x >> 29;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x ^= x >> 32;
    (x % 10_000) as f64 / 10_000.0
}

/// Columns and rows of a grid holding `count` cells, about `aspect` times wider than tall.
fn grid(count: usize, aspect: f64) -> (usize, usize) {
    let cols = ((count as f64 * aspect).sqrt().ceil() as usize).max(1);
    (cols, count.div_ceil(cols).max(1))
}

fn projection() -> Projection {
    Projection { fov_y: 60f32.to_radians(), near: 0.05, far: Some(200.0), ..Projection::default() }
}

/// Generates `family` with exactly `count` reflectors (at least one).
pub fn generate(family: LevelFamily, count: usize) -> GeneratedLevel {
    let count = count.max(1);
    if family == LevelFamily::Rooms {
        return crate::scaling::room_maze::room_maze(count);
    }
    let mut level = Level::new();
    let mut q = QuadBuilder::default();
    let mirror = q.material(&mut level, Material::polished("mirror", [0.35, 0.35, 0.38]));
    let ground = q.material(&mut level, Material::matte("ground", [0.35, 0.3, 0.25]));
    let scenery: Vec<usize> = (0..6)
        .map(|k| q.material(&mut level, Material::matte(format!("scenery_{k}"), scenery_color(k))))
        .collect();
    let mut set = ReflectorSet::new(format!("generated:{}:{count}", family.as_str()));
    let add =
        |set: &mut ReflectorSet, q: &mut QuadBuilder, center: DVec3, u: DVec3, v: DVec3, half: DVec2| {
            let id = set.next_id();
            set.reflectors.push(Reflector::new(
                id,
                format!("{}-{id}", family.as_str()),
                ReflectorKind::Opaque,
                center,
                u.cross(v),
                u,
                half,
            ));
            q.quad(mirror, center, u * half.x, v * half.y);
        };
    let (camera, reach) = match family {
        LevelFamily::TiledFloor => {
            // 16 m × 16 m floor; one puddle (50–90 % of its tile) per tile.
            let (cols, rows) = grid(count, 1.0);
            let (cw, cd) = (16.0 / cols as f64, 16.0 / rows as f64);
            q.quad(ground, v3(0.0, -0.002, 0.0), DVec3::X * 9.0, DVec3::NEG_Z * 9.0);
            for k in 0..count {
                let (i, j) = (k % cols, k / cols);
                let c = v3(-8.0 + (i as f64 + 0.5) * cw, 0.0, -8.0 + (j as f64 + 0.5) * cd);
                let s = 0.25 + 0.2 * hash01(k);
                add(&mut set, &mut q, c, DVec3::X, DVec3::NEG_Z, DVec2::new(cw * s, cd * s));
            }
            for (k, &m) in scenery.iter().enumerate() {
                let x = -6.0 + 2.4 * k as f64;
                q.cuboid(
                    m,
                    v3(x, 1.0 + 0.3 * k as f64, -9.5 + hash01(k + 50)),
                    v3(0.6, 1.0 + 0.3 * k as f64, 0.6),
                );
            }
            (Camera::look_at(v3(0.0, 3.5, 13.0), v3(0.0, 0.0, -1.0), UP, projection()), 1.0)
        }
        LevelFamily::Facade => {
            // 20 m × 16 m wall at z = 0 facing +z, windows in a grid.
            let (cols, rows) = grid(count, 1.25);
            let (cw, ch) = (20.0 / cols as f64, 16.0 / rows as f64);
            q.quad(ground, v3(0.0, 0.0, 6.0), DVec3::X * 14.0, DVec3::NEG_Z * 8.0);
            q.quad(scenery[4], v3(0.0, 8.0, -0.01), DVec3::X * 10.5, DVec3::Y * 8.5);
            for k in 0..count {
                let (i, j) = (k % cols, k / cols);
                let c = v3(-10.0 + (i as f64 + 0.5) * cw, 0.2 + (j as f64 + 0.5) * ch, 0.0);
                add(&mut set, &mut q, c, DVec3::X, DVec3::Y, DVec2::new(cw * 0.35, ch * 0.35));
            }
            for (k, &m) in scenery.iter().enumerate() {
                let x = -9.0 + 3.6 * k as f64;
                q.cuboid(m, v3(x, 1.5 + 0.8 * k as f64, 11.0), v3(1.2, 1.5 + 0.8 * k as f64, 1.2));
            }
            (Camera::look_at(v3(-7.0, 1.8, 16.0), v3(1.0, 7.0, 0.0), UP, projection()), 1.0)
        }
        LevelFamily::Rooms => unreachable!("generated by room_maze above"),
        LevelFamily::Stairway => {
            // 6 m wide, rising 6 m over a 12 m run towards −z; every tread a mirror.
            let (rise, run) = (6.0 / count as f64, 12.0 / count as f64);
            q.quad(ground, v3(0.0, 0.0, 4.0), DVec3::X * 10.0, DVec3::NEG_Z * 4.0);
            for k in 0..count {
                let y = (k + 1) as f64 * rise;
                let zc = -(k as f64 + 0.5) * run;
                add(&mut set, &mut q, v3(0.0, y, zc), DVec3::X, DVec3::NEG_Z, DVec2::new(3.0, run * 0.5));
                // Riser (matte) below the tread's front edge.
                q.quad(
                    ground,
                    v3(0.0, y - rise * 0.5, -(k as f64) * run),
                    DVec3::X * 3.0,
                    DVec3::Y * (rise * 0.5),
                );
            }
            for (k, &m) in scenery.iter().enumerate() {
                let z = -1.0 - 2.0 * k as f64;
                let h = 1.0 + (k as f64 + 1.0) * 1.0;
                q.cuboid(m, v3(4.2, h, z), v3(0.5, h, 0.5));
            }
            (
                Camera::look_at(v3(-7.0, 11.0, 8.0), v3(0.5, 2.5, -6.0), UP, projection()),
                3.0 * (12.0 / count as f64),
            )
        }
    };
    q.finish(&mut level, family.as_str());
    let normals: Vec<DVec3> = set.reflectors.iter().map(|r| r.normal).collect();
    for (r, g) in set.reflectors.iter_mut().zip(parallel_groups(&normals, 1f64.to_radians().cos())) {
        r.parallel_group = g;
    }
    let lists = occluder_lists(&set.reflectors, DVec3::ZERO, 1e-4, reach);
    for (r, list) in set.reflectors.iter_mut().zip(lists) {
        r.occluders = list;
    }
    GeneratedLevel { family, level, reflectors: set, camera }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grids_hold_the_count() {
        for n in [1, 2, 10, 99, 100, 1000, 10_000] {
            let (c, r) = grid(n, 1.25);
            assert!(c * r >= n && (c - 1) * r < n + r, "{n}: {c}x{r}");
        }
    }

    #[test]
    fn scene_names_name_a_family_and_a_count() {
        for family in LevelFamily::ALL {
            let name = format!("{}-{}", family.as_str(), 1000);
            assert_eq!(LevelFamily::from_scene_name(&name), Some((family, 1000)), "{name}");
        }
        assert_eq!(LevelFamily::from_scene_name("tiled-floor-7"), Some((LevelFamily::TiledFloor, 7)));
        for bad in ["stairway", "stairway-0", "stairway-x", "floor-10", "mirror-room-2", "stairway-1000000"] {
            assert_eq!(LevelFamily::from_scene_name(bad), None, "{bad}");
        }
    }
}
