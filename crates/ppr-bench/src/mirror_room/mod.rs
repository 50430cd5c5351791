//! Closed mirror rooms (issue 14): a box room with boxes inside and a corridor between two
//! facing mirror walls, every surface a tinted mirror, with cameras inside. Scenes of the
//! bench by name (`mirror-room`, `mirror-room-<boxes>`, `mirror-corridor`).
//!
//! The reflector set is the generator's own geometry (one exact rectangle per panel), not
//! an extraction: the family tests the reflection techniques and the reference, so no
//! rectangle fit or extraction setting can change what is measured, and every reflector
//! pixel is on exactly one rectangle.

pub mod one_frame;
pub mod panels;
pub mod room_cameras;

use glam::DVec3;
use ppr_extract::occluders::occluder_lists;
use ppr_extract::parallel::parallel_groups;
use ppr_format::ReflectorSet;
use ppr_testbed::Level;

use crate::cameras::NamedCamera;
use crate::mirror_room::panels::MirrorPanels;
use crate::scaling::quad_builder::scenery_color;
use crate::scene::{BenchScene, SceneOptions};

/// One member of the family.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MirrorRoom {
    /// An 8 × 3 × 6 m room with this many boxes standing inside (the room has 2).
    BoxesInBox { boxes: usize },
    /// A 3 m wide, 3 m high, 16 m long corridor: two facing mirror walls, mirror floor,
    /// ceiling and end walls, two boxes on the floor.
    Corridor,
}

/// Most boxes a room takes (they stay clear of the cameras).
pub const MAX_BOXES: usize = 12;

impl MirrorRoom {
    /// The member `name` stands for: `mirror-room` (2 boxes), `mirror-room-<n>` (n boxes,
    /// 0 to [`MAX_BOXES`]) or `mirror-corridor`.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "mirror-room" => Some(Self::BoxesInBox { boxes: 2 }),
            "mirror-corridor" => Some(Self::Corridor),
            _ => {
                let n: usize = name.strip_prefix("mirror-room-")?.parse().ok()?;
                (n <= MAX_BOXES).then_some(Self::BoxesInBox { boxes: n })
            }
        }
    }

    /// The scene name of this member.
    pub fn name(self) -> String {
        match self {
            Self::BoxesInBox { boxes: 2 } => "mirror-room".into(),
            Self::BoxesInBox { boxes } => format!("mirror-room-{boxes}"),
            Self::Corridor => "mirror-corridor".into(),
        }
    }
}

/// A generated mirror room: the level, its reflectors and the cameras inside it.
#[derive(Clone, Debug)]
pub struct GeneratedRoom {
    pub level: Level,
    pub reflectors: ReflectorSet,
    pub cameras: Vec<NamedCamera>,
}

/// Walls in muted tints, boxes in the scenery palette: every reflection shows which
/// surface it comes from.
fn wall_color(k: usize) -> [f32; 3] {
    const C: [[f32; 3]; 6] = [
        [0.55, 0.35, 0.3],
        [0.3, 0.45, 0.55],
        [0.6, 0.6, 0.55],
        [0.3, 0.3, 0.32],
        [0.35, 0.5, 0.35],
        [0.5, 0.4, 0.55],
    ];
    C[k % C.len()]
}

/// Deterministic value in [0, 1) for box placement.
fn hash01(k: usize) -> f64 {
    let mut x = (k as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    x ^= x >> 31;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x ^= x >> 29;
    (x % 100_000) as f64 / 100_000.0
}

/// Generates `room`.
pub fn generate(room: MirrorRoom) -> GeneratedRoom {
    let mut level = Level::new();
    let name = room.name();
    let mut panels = MirrorPanels::new(&format!("generated:{name}"));
    let (room_center, room_half, boxes) = match room {
        MirrorRoom::BoxesInBox { boxes } => {
            let mut list = vec![
                (DVec3::new(-1.5, 0.6, -0.8), DVec3::splat(0.6)),
                (DVec3::new(1.6, 0.9, -1.2), DVec3::new(0.5, 0.9, 0.4)),
            ];
            for k in 2..boxes.max(2) {
                // On a 4 × 3 grid of cells over the back of the room, jittered, clear of
                // the cameras (which stand at z > 1.5).
                let (i, j) = (k % 4, (k / 4) % 3);
                let half = DVec3::new(0.2 + 0.25 * hash01(3 * k), 0.2 + 0.6 * hash01(3 * k + 1), 0.25);
                let x = -3.0 + 2.0 * i as f64 + 0.4 * (hash01(3 * k + 2) - 0.5);
                let z = -2.4 + 1.2 * j as f64;
                list.push((DVec3::new(x, half.y, z), half));
            }
            list.truncate(boxes);
            (DVec3::new(0.0, 1.5, 0.0), DVec3::new(4.0, 1.5, 3.0), list)
        }
        MirrorRoom::Corridor => (
            DVec3::new(0.0, 1.5, 0.0),
            DVec3::new(1.5, 1.5, 8.0),
            vec![
                (DVec3::new(-0.8, 0.4, -3.0), DVec3::new(0.35, 0.4, 0.35)),
                (DVec3::new(0.7, 0.7, 2.5), DVec3::new(0.3, 0.7, 0.3)),
            ],
        ),
    };
    panels.cuboid(&mut level, "room", room_center, room_half, true, false, &wall_color);
    for (b, (center, half)) in boxes.iter().enumerate() {
        let color = |k: usize| scenery_color(b + k);
        panels.cuboid(&mut level, &format!("box {b}"), *center, *half, false, true, &color);
    }
    let mut set = panels.finish(&mut level, &name);
    let normals: Vec<DVec3> = set.reflectors.iter().map(|r| r.normal).collect();
    for (r, g) in set.reflectors.iter_mut().zip(parallel_groups(&normals, 1f64.to_radians().cos())) {
        r.parallel_group = g;
    }
    // Every panel may hide every other: the reach is the room's diagonal.
    let reach = 2.0 * room_half.length();
    let lists = occluder_lists(&set.reflectors, room_center, 1e-4, reach);
    for (r, list) in set.reflectors.iter_mut().zip(lists) {
        r.occluders = list;
    }
    let cameras = room_cameras::cameras(room);
    GeneratedRoom { level, reflectors: set, cameras }
}

/// The bench scene of `room`: every surface is a reflector (the reflector mask takes any
/// surface on a rectangle), the cameras are the room's own.
pub fn bench_scene(room: MirrorRoom, options: &SceneOptions) -> BenchScene {
    let g = generate(room);
    let mut notes = vec![format!(
        "generated closed mirror room: {} reflectors (the panels themselves) from {} triangles",
        g.reflectors.reflectors.len(),
        g.level.triangle_count()
    )];
    let mut scene = BenchScene::from_parts(&room.name(), g.level, g.reflectors, options, &mut notes);
    scene.cameras = g.cameras;
    scene.cameras.truncate(options.max_cameras.max(1));
    scene.cameras_derived = false;
    scene.any_surface = true;
    scene
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for room in
            [MirrorRoom::BoxesInBox { boxes: 2 }, MirrorRoom::BoxesInBox { boxes: 7 }, MirrorRoom::Corridor]
        {
            assert_eq!(MirrorRoom::from_name(&room.name()), Some(room));
        }
        assert_eq!(MirrorRoom::from_name("mirror-room-99"), None);
        assert_eq!(MirrorRoom::from_name("demo"), None);
    }

    #[test]
    fn rooms_are_closed_and_valid() {
        for boxes in 0..=MAX_BOXES {
            let g = generate(MirrorRoom::BoxesInBox { boxes });
            assert_eq!(g.reflectors.reflectors.len(), 6 + 5 * boxes);
            g.reflectors.validate().expect("valid set");
            g.level.validate().expect("valid level");
        }
        let g = generate(MirrorRoom::Corridor);
        assert_eq!(g.reflectors.reflectors.len(), 16);
        // Two facing mirror walls.
        let walls: Vec<_> =
            g.reflectors.reflectors.iter().filter(|r| r.normal.x.abs() > 0.99 && r.area() > 40.0).collect();
        assert_eq!(walls.len(), 2);
        assert!((walls[0].normal + walls[1].normal).length() < 1e-9);
    }
}
