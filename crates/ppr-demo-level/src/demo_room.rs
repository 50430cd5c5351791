//! The demo room's content: where every surface, prop and camera goes (see the map in `main.rs`).
//!
//! Naming rule: `ppr-extract` (like other name-driven tools) makes every triangle of a node
//! or mesh whose name contains `mirror`, `glass`, `water`, `puddle`, `chrome` or `polished`
//! a candidate, so those words name only nodes and meshes that are entirely reflective;
//! frames, bases, rims and step sides live in nodes and meshes named without them.

use glam::{DVec2, DVec3};

use crate::demo_materials::DemoMaterials;
use crate::exact_trig::{rotation_x_degrees, rotation_y_degrees, sin_cos_degrees};
use crate::ground_truth::{NonReflectorSpec, ReflectorKind, ReflectorSpec};
use crate::level_builder::{LevelBuilder, NodeId, NodeSpec, NodeTransform};
use crate::mesh_data::{BoxFace, MeshData};
use crate::ppr_extras::{PprExtras, PprOverride};

/// Room interior: x in `[-ROOM_HALF_X, ROOM_HALF_X]`, z in `[-ROOM_HALF_Z, ROOM_HALF_Z]`.
pub const ROOM_HALF_X: f64 = 8.0;
pub const ROOM_HALF_Z: f64 = 6.0;
pub const ROOM_HEIGHT: f64 = 5.0;

/// The level, ready to be written, with what the ground truth needs to know about it.
pub struct DemoRoom {
    pub builder: LevelBuilder,
    pub reflectors: Vec<ReflectorSpec>,
    pub non_reflectors: Vec<NonReflectorSpec>,
}

/// Builds the whole room.
pub fn build_demo_room() -> DemoRoom {
    let mut builder = LevelBuilder::new();
    let materials = DemoMaterials::add_to(&mut builder);
    let mut room = DemoRoom { builder, reflectors: Vec::new(), non_reflectors: Vec::new() };

    add_room_shell(&mut room, &materials);
    add_mirror_wall(&mut room, &materials);
    add_glass_panel(&mut room, &materials);
    add_mirror_stairs(&mut room, &materials);
    add_tilted_mirror(&mut room, &materials);
    add_water_basin(&mut room, &materials);
    add_pond(&mut room, &materials);
    add_polished_floor(&mut room, &materials);
    add_brushed_metal_panel(&mut room, &materials);
    add_puddles(&mut room, &materials);
    add_props(&mut room, &materials);
    add_table(&mut room, &materials);
    add_cameras(&mut room);
    room
}

impl DemoRoom {
    fn reflector(&mut self, node: NodeId, primitive: usize, kind: ReflectorKind) {
        self.reflectors.push(ReflectorSpec { node, primitive, kind, splits: Vec::new() });
    }
}

/// A box standing on the origin (bottom face left out), `size` = (x, y, z).
fn standing_box(size: DVec3) -> MeshData {
    let half = DVec3::new(size.x * 0.5, 0.0, size.z * 0.5);
    MeshData::cuboid(-half, half + DVec3::Y * size.y, &BoxFace::ALL_BUT_BOTTOM, 1.0)
}

/// A box from `min` to `max` with all faces.
fn block(min: [f64; 3], max: [f64; 3]) -> MeshData {
    MeshData::cuboid(DVec3::from_array(min), DVec3::from_array(max), &BoxFace::ALL, 1.0)
}

/// Floor (tiles, 1 m checker) and four inward-facing brick walls; no ceiling.
fn add_room_shell(room: &mut DemoRoom, materials: &DemoMaterials) {
    let (hx, hz, h) = (ROOM_HALF_X, ROOM_HALF_Z, ROOM_HEIGHT);
    let b = &mut room.builder;
    let floor = MeshData::quad(DVec3::new(-hx, 0.0, -hz), DVec3::Z * 2.0 * hz, DVec3::X * 2.0 * hx, 2.0);
    let walls = MeshData::merged(&[
        // back (z = -6, facing +Z), front (z = +6, facing -Z), left (x = -8, facing +X), right (x = +8, facing -X)
        MeshData::quad(DVec3::new(-hx, 0.0, -hz), DVec3::X * 2.0 * hx, DVec3::Y * h, 1.0),
        MeshData::quad(DVec3::new(hx, 0.0, hz), DVec3::NEG_X * 2.0 * hx, DVec3::Y * h, 1.0),
        MeshData::quad(DVec3::new(-hx, 0.0, hz), DVec3::NEG_Z * 2.0 * hz, DVec3::Y * h, 1.0),
        MeshData::quad(DVec3::new(hx, 0.0, -hz), DVec3::Z * 2.0 * hz, DVec3::Y * h, 1.0),
    ]);
    let floor_geometry = b.add_geometry(&floor);
    let floor_mesh = b.add_mesh("room_floor", &[(floor_geometry, materials.floor_tiles)]);
    let walls_geometry = b.add_geometry(&walls);
    let walls_mesh = b.add_mesh("room_walls", &[(walls_geometry, materials.brick_wall)]);
    let group = b.add_node(NodeSpec::group("room", None, NodeTransform::IDENTITY));
    b.add_node(NodeSpec::instance("room_floor", Some(group), floor_mesh, NodeTransform::IDENTITY));
    b.add_node(NodeSpec::instance("room_walls", Some(group), walls_mesh, NodeTransform::IDENTITY));
}

/// 6 × 3 m mirror, 5 cm in front of the back wall, facing +Z, with a dark frame (its own
/// node: see the naming rule above).
fn add_mirror_wall(room: &mut DemoRoom, materials: &DemoMaterials) {
    let b = &mut room.builder;
    let mirror = MeshData::quad(DVec3::new(-3.0, 0.0, 0.0), DVec3::X * 6.0, DVec3::Y * 3.0, 1.0);
    let (w, back, front) = (0.12, -0.05, 0.03);
    let frame = MeshData::merged(&[
        block([-3.0 - w, -w, back], [3.0 + w, 0.0, front]),
        block([-3.0 - w, 3.0, back], [3.0 + w, 3.0 + w, front]),
        block([-3.0 - w, 0.0, back], [-3.0, 3.0, front]),
        block([3.0, 0.0, back], [3.0 + w, 3.0, front]),
    ]);
    let mirror_geometry = b.add_geometry(&mirror);
    let mirror_mesh = b.add_mesh("mirror_wall", &[(mirror_geometry, materials.mirror)]);
    let frame_geometry = b.add_geometry(&frame);
    let frame_mesh = b.add_mesh("back_wall_frame", &[(frame_geometry, materials.frame_dark)]);
    let at = NodeTransform::at(DVec3::new(0.0, 0.5, -ROOM_HALF_Z + 0.05));
    let node = b.add_node(NodeSpec::instance("mirror_wall", None, mirror_mesh, at));
    b.add_node(NodeSpec::instance("back_wall_frame", None, frame_mesh, at));
    room.reflector(node, 0, ReflectorKind::Opaque);
}

/// 3 × 2.5 m glass pane at z = -3.5 (2.45 m in front of the mirror), x in [0, 3], in a
/// frame with two feet (its own node: see the naming rule above).
fn add_glass_panel(room: &mut DemoRoom, materials: &DemoMaterials) {
    let b = &mut room.builder;
    let pane = MeshData::quad(DVec3::new(-1.5, 0.0, 0.0), DVec3::X * 3.0, DVec3::Y * 2.5, 1.0);
    let (w, d) = (0.05, 0.03);
    let frame = MeshData::merged(&[
        block([-1.5 - w, -w, -d], [1.5 + w, 0.0, d]),
        block([-1.5 - w, 2.5, -d], [1.5 + w, 2.5 + w, d]),
        block([-1.5 - w, 0.0, -d], [-1.5, 2.5, d]),
        block([1.5, 0.0, -d], [1.5 + w, 2.5, d]),
        block([-1.55, -0.08, -0.2], [-1.35, -w, 0.2]),
        block([1.35, -0.08, -0.2], [1.55, -w, 0.2]),
    ]);
    let pane_geometry = b.add_geometry(&pane);
    let pane_mesh = b.add_mesh("glass_panel", &[(pane_geometry, materials.glass)]);
    let frame_geometry = b.add_geometry(&frame);
    let frame_mesh = b.add_mesh("pane_frame", &[(frame_geometry, materials.frame_dark)]);
    let at = NodeTransform::at(DVec3::new(1.5, 0.08, -3.5));
    let node = b.add_node(NodeSpec::instance("glass_panel", None, pane_mesh, at));
    b.add_node(NodeSpec::instance("pane_frame", None, frame_mesh, at));
    room.reflector(node, 0, ReflectorKind::Transparent);
}

/// Five solid steps against the left wall (x in [-8, -6]), 1 m deep along z, rising towards
/// the back; one mesh `stair_step` (mirror top at local y = 0, stone sides down to y = -1)
/// instanced by five nodes scaled to their height.
fn add_mirror_stairs(room: &mut DemoRoom, materials: &DemoMaterials) {
    let b = &mut room.builder;
    let top = MeshData::quad(DVec3::new(-1.0, 0.0, -0.5), DVec3::Z, DVec3::X * 2.0, 1.0);
    let sides =
        MeshData::cuboid(DVec3::new(-1.0, -1.0, -0.5), DVec3::new(1.0, 0.0, 0.5), &BoxFace::SIDES, 1.0);
    let top_geometry = b.add_geometry(&top);
    let sides_geometry = b.add_geometry(&sides);
    let mesh =
        b.add_mesh("stair_step", &[(top_geometry, materials.mirror), (sides_geometry, materials.stone)]);
    let group = b.add_node(NodeSpec::group("stairs", None, NodeTransform::IDENTITY));
    let steps = [
        ("step_1", 0.25, 3.0),
        ("step_2", 0.5, 2.0),
        ("step_3", 0.75, 1.0),
        ("step_4", 1.0, 0.0),
        ("step_5", 1.25, -1.0),
    ];
    for (name, height, z) in steps {
        let transform = NodeTransform::at(DVec3::new(-ROOM_HALF_X + 1.0, height, z))
            .with_scale(DVec3::new(1.0, height, 1.0));
        let node = room.builder.add_node(NodeSpec::instance(name, Some(group), mesh, transform));
        room.reflector(node, 0, ReflectorKind::Opaque);
    }
}

/// 1.5 × 2 m framed mirror on a stone base at (5, 0, -2), turned -30° around Y (to face the
/// room centre) and leaning 20° back: `leaning_stand` (turn) > `leaning_stand_tilt` (tilt
/// about the base's top edge) > `tilted_mirror` + `tilted_frame`.
fn add_tilted_mirror(room: &mut DemoRoom, materials: &DemoMaterials) {
    let b = &mut room.builder;
    let base = standing_box(DVec3::new(1.8, 0.15, 0.75));
    let mirror = MeshData::quad(DVec3::new(-0.75, 0.06, 0.0), DVec3::X * 1.5, DVec3::Y * 2.0, 1.0);
    let (back, mid, front) = (-0.04, -0.005, 0.015);
    let frame = MeshData::merged(&[
        block([-0.81, 0.0, back], [0.81, 2.12, mid]),
        block([-0.81, 0.0, mid], [0.81, 0.06, front]),
        block([-0.81, 2.06, mid], [0.81, 2.12, front]),
        block([-0.81, 0.06, mid], [-0.75, 2.06, front]),
        block([0.75, 0.06, mid], [0.81, 2.06, front]),
    ]);
    let base_geometry = b.add_geometry(&base);
    let base_mesh = b.add_mesh("leaning_stand_base", &[(base_geometry, materials.stone)]);
    let mirror_geometry = b.add_geometry(&mirror);
    let mirror_mesh = b.add_mesh("tilted_mirror", &[(mirror_geometry, materials.mirror)]);
    let frame_geometry = b.add_geometry(&frame);
    let frame_mesh = b.add_mesh("tilted_frame", &[(frame_geometry, materials.frame_dark)]);
    let stand = b.add_node(NodeSpec::group(
        "leaning_stand",
        None,
        NodeTransform::at(DVec3::new(5.0, 0.0, -2.0)).with_rotation(rotation_y_degrees(-30.0)),
    ));
    b.add_node(NodeSpec::instance(
        "leaning_stand_base",
        Some(stand),
        base_mesh,
        NodeTransform::at(DVec3::new(0.0, 0.0, -0.15)),
    ));
    let tilt = b.add_node(NodeSpec::group(
        "leaning_stand_tilt",
        Some(stand),
        NodeTransform::at(DVec3::new(0.0, 0.15, 0.0)).with_rotation(rotation_x_degrees(-20.0)),
    ));
    let mirror_node =
        b.add_node(NodeSpec::instance("tilted_mirror", Some(tilt), mirror_mesh, NodeTransform::IDENTITY));
    b.add_node(NodeSpec::instance("tilted_frame", Some(tilt), frame_mesh, NodeTransform::IDENTITY));
    room.reflector(mirror_node, 0, ReflectorKind::Opaque);
}

/// Stone basin (outer 3.4 × 2.4 m, rim 0.5 m high) centred at (4.5, 0, 3) holding a 3 × 2 m
/// water surface at y = 0.4, marked as water through node extras.
fn add_water_basin(room: &mut DemoRoom, materials: &DemoMaterials) {
    let b = &mut room.builder;
    let rim = MeshData::merged(&[
        standing_box_at([-1.6, 0.0, 0.0], [0.2, 0.5, 2.4]),
        standing_box_at([1.6, 0.0, 0.0], [0.2, 0.5, 2.4]),
        standing_box_at([0.0, 0.0, -1.1], [3.0, 0.5, 0.2]),
        standing_box_at([0.0, 0.0, 1.1], [3.0, 0.5, 0.2]),
    ]);
    let water = MeshData::quad(DVec3::new(-1.5, 0.4, -1.0), DVec3::Z * 2.0, DVec3::X * 3.0, 1.0);
    let rim_geometry = b.add_geometry(&rim);
    let rim_mesh = b.add_mesh("basin_rim", &[(rim_geometry, materials.stone)]);
    let water_geometry = b.add_geometry(&water);
    let water_mesh = b.add_mesh("water_surface", &[(water_geometry, materials.water)]);
    let group =
        b.add_node(NodeSpec::group("stone_basin", None, NodeTransform::at(DVec3::new(4.5, 0.0, 3.0))));
    b.add_node(NodeSpec::instance("basin_rim", Some(group), rim_mesh, NodeTransform::IDENTITY));
    let water_node = b.add_node(
        NodeSpec::instance("water_surface", Some(group), water_mesh, NodeTransform::IDENTITY)
            .with_extras(PprExtras { ppr: PprOverride { reflector: true, kind: Some("water") } }),
    );
    room.reflector(water_node, 0, ReflectorKind::Water);
}

/// A low stone-rimmed pond (outer 2.4 × 1.8 m, rim 0.18 m high) between the stairs and
/// `puddle_c`, centred at (-4.6, 0, -2.35), holding a 2.0 × 1.4 m water surface at
/// y = 0.12: a second water plane at another height than the basin's, and a rough one
/// (`rough_water`, roughness 0.15: its reflection blurs with distance).
fn add_pond(room: &mut DemoRoom, materials: &DemoMaterials) {
    let b = &mut room.builder;
    let rim = MeshData::merged(&[
        standing_box_at([-1.1, 0.0, 0.0], [0.2, 0.18, 1.8]),
        standing_box_at([1.1, 0.0, 0.0], [0.2, 0.18, 1.8]),
        standing_box_at([0.0, 0.0, -0.8], [2.0, 0.18, 0.2]),
        standing_box_at([0.0, 0.0, 0.8], [2.0, 0.18, 0.2]),
    ]);
    let water = MeshData::quad(DVec3::new(-1.0, 0.12, -0.7), DVec3::Z * 1.4, DVec3::X * 2.0, 1.0);
    let rim_geometry = b.add_geometry(&rim);
    let rim_mesh = b.add_mesh("pond_rim", &[(rim_geometry, materials.stone)]);
    let water_geometry = b.add_geometry(&water);
    let water_mesh = b.add_mesh("pond_water", &[(water_geometry, materials.rough_water)]);
    let group =
        b.add_node(NodeSpec::group("stone_pond", None, NodeTransform::at(DVec3::new(-4.6, 0.0, -2.35))));
    b.add_node(NodeSpec::instance("pond_rim", Some(group), rim_mesh, NodeTransform::IDENTITY));
    let water_node = b.add_node(
        NodeSpec::instance("pond_water", Some(group), water_mesh, NodeTransform::IDENTITY)
            .with_extras(PprExtras { ppr: PprOverride { reflector: true, kind: Some("water") } }),
    );
    room.reflector(water_node, 0, ReflectorKind::Water);
}

/// `standing_box` moved to `centre` (x, y of its bottom, z).
fn standing_box_at(centre: [f64; 3], size: [f64; 3]) -> MeshData {
    let mut mesh = standing_box(DVec3::from_array(size));
    for position in &mut mesh.positions {
        *position += DVec3::from_array(centre);
    }
    mesh
}

/// L-shaped polished marble floor 1 mm above the floor, on a 1 m grid with shared
/// vertices: a 6 × 2 m arm (x in [-4.5, 1.5], z in [2.5, 4.5]) and a 2 × 3 m arm
/// (x in [-4.5, -2.5], z in [-0.5, 2.5]).
fn add_polished_floor(room: &mut DemoRoom, materials: &DemoMaterials) {
    let long_arm: Vec<(i32, i32)> = (0..6).flat_map(|i| (0..2).map(move |j| (i, j))).collect();
    let short_arm: Vec<(i32, i32)> = (0..2).flat_map(|i| (-3..0).map(move |j| (i, j))).collect();
    let cells: Vec<(i32, i32)> = long_arm.iter().chain(&short_arm).copied().collect();
    let grid = MeshData::cell_grid(&cells, 1.0, 1.0);

    // Cell k owns triangles 2k and 2k + 1.
    let triangles_of = |keep: &dyn Fn(usize, (i32, i32)) -> bool| -> Vec<usize> {
        cells
            .iter()
            .enumerate()
            .filter(|(k, cell)| keep(*k, **cell))
            .flat_map(|(k, _)| [2 * k, 2 * k + 1])
            .collect()
    };
    let in_long_arm = |k: usize, _: (i32, i32)| k < long_arm.len();
    let authored_split = vec![triangles_of(&in_long_arm), triangles_of(&|k, c| !in_long_arm(k, c))];
    let column_split = vec![triangles_of(&|_, (i, _)| i < 2), triangles_of(&|_, (i, _)| i >= 2)];

    let b = &mut room.builder;
    let geometry = b.add_geometry(&grid);
    let mesh = b.add_mesh("polished_floor", &[(geometry, materials.polished_marble)]);
    let node = b.add_node(NodeSpec::instance(
        "polished_floor",
        None,
        mesh,
        NodeTransform::at(DVec3::new(-4.5, 0.001, 2.5)),
    ));
    room.reflectors.push(ReflectorSpec {
        node,
        primitive: 0,
        kind: ReflectorKind::Opaque,
        splits: vec![authored_split, column_split],
    });
}

/// One irregular puddle outline: `count` radii `1 + Σ a·cos(k·θ + φ)` for the given
/// harmonics `(k, a, φ in degrees)`.
fn puddle_radii(count: u32, harmonics: &[(f64, f64, f64)]) -> Vec<f64> {
    (0..count)
        .map(|i| {
            let theta = 360.0 * f64::from(i) / f64::from(count);
            1.0 + harmonics.iter().map(|&(k, a, phi)| a * sin_cos_degrees(k * theta + phi).1).sum::<f64>()
        })
        .collect()
}

/// Three star-shaped puddles 2 mm above the floor; `puddle_c` sits under a node mirrored
/// in x (negative determinant), its reflecting side still +Y.
fn add_puddles(room: &mut DemoRoom, materials: &DemoMaterials) {
    let shapes = [
        ("puddle_a", 22, DVec2::new(1.1, 0.75), [(2.0, 0.10, 20.0), (3.0, 0.15, 65.0), (5.0, 0.07, 110.0)]),
        ("puddle_b", 18, DVec2::new(0.8, 0.55), [(2.0, 0.08, 200.0), (3.0, 0.18, 10.0), (4.0, 0.06, 300.0)]),
        ("puddle_c", 24, DVec2::new(0.9, 0.6), [(2.0, 0.12, 90.0), (3.0, 0.10, 240.0), (5.0, 0.09, 45.0)]),
    ];
    let meshes = shapes.map(|(name, count, scale, harmonics)| {
        let outline = MeshData::radial_polygon(&puddle_radii(count, &harmonics), scale, 1.0);
        let geometry = room.builder.add_geometry(&outline);
        room.builder.add_mesh(name, &[(geometry, materials.puddle)])
    });
    let b = &mut room.builder;
    let group = b.add_node(NodeSpec::group("puddles", None, NodeTransform::IDENTITY));
    let puddle_a = b.add_node(NodeSpec::instance(
        "puddle_a",
        Some(group),
        meshes[0],
        NodeTransform::at(DVec3::new(-0.6, 0.002, 0.6)).with_rotation(rotation_y_degrees(10.0)),
    ));
    let puddle_b = b.add_node(NodeSpec::instance(
        "puddle_b",
        Some(group),
        meshes[1],
        NodeTransform::at(DVec3::new(1.9, 0.002, -1.6)).with_rotation(rotation_y_degrees(-35.0)),
    ));
    let mirrored = b.add_node(NodeSpec::group(
        "puddle_c_mirrored",
        Some(group),
        NodeTransform::at(DVec3::new(-2.2, 0.002, -2.6)).with_scale(DVec3::new(-1.0, 1.0, 1.0)),
    ));
    let puddle_c = b.add_node(NodeSpec::instance(
        "puddle_c",
        Some(mirrored),
        meshes[2],
        NodeTransform::IDENTITY.with_rotation(rotation_y_degrees(25.0)),
    ));
    for node in [puddle_a, puddle_b, puddle_c] {
        room.reflector(node, 0, ReflectorKind::Opaque);
    }
}

/// Coloured pillars (one shared cylinder geometry, three materials) and boxes.
fn add_props(room: &mut DemoRoom, materials: &DemoMaterials) {
    let b = &mut room.builder;
    let group = b.add_node(NodeSpec::group("props", None, NodeTransform::IDENTITY));
    let cylinder = b.add_geometry(&MeshData::cylinder(0.3, ROOM_HEIGHT, 24, 1.0));
    let pillars = [
        ("pillar_red", materials.paint_red, [-4.0, -4.2]),
        ("pillar_blue", materials.paint_blue, [4.5, -4.6]),
        ("pillar_yellow", materials.paint_yellow, [-5.2, 5.0]),
    ];
    for (name, material, [x, z]) in pillars {
        let mesh = b.add_mesh(name, &[(cylinder, material)]);
        b.add_node(NodeSpec::instance(name, Some(group), mesh, NodeTransform::at(DVec3::new(x, 0.0, z))));
    }
    let boxes = [
        ("box_orange", materials.paint_orange, [0.8, 0.8, 0.8], [-1.6, -4.9], 0.0),
        ("box_cyan", materials.paint_cyan, [0.6, 1.4, 0.6], [2.0, 0.8], 20.0),
        ("box_purple", materials.paint_purple, [1.2, 0.6, 0.8], [-5.2, -3.0], 15.0),
        ("box_green", materials.paint_green, [0.7, 0.7, 0.7], [3.2, -4.8], -10.0),
    ];
    for (name, material, size, [x, z], turn) in boxes {
        let geometry = b.add_geometry(&standing_box(DVec3::from_array(size)));
        let mesh = b.add_mesh(name, &[(geometry, material)]);
        let transform = NodeTransform::at(DVec3::new(x, 0.0, z)).with_rotation(rotation_y_degrees(turn));
        b.add_node(NodeSpec::instance(name, Some(group), mesh, transform));
    }
}

/// A table at (6.3, 0, -0.2) whose glossy lacquered top (roughness 0.2) is marked
/// `{"ppr": {"reflector": false}}`.
fn add_table(room: &mut DemoRoom, materials: &DemoMaterials) {
    let b = &mut room.builder;
    let top = block([-0.6, 0.72, -0.4], [0.6, 0.77, 0.4]);
    let legs = MeshData::merged(&[
        standing_box_at([-0.52, 0.0, -0.32], [0.06, 0.72, 0.06]),
        standing_box_at([0.52, 0.0, -0.32], [0.06, 0.72, 0.06]),
        standing_box_at([-0.52, 0.0, 0.32], [0.06, 0.72, 0.06]),
        standing_box_at([0.52, 0.0, 0.32], [0.06, 0.72, 0.06]),
    ]);
    let top_geometry = b.add_geometry(&top);
    let top_mesh = b.add_mesh("table_top", &[(top_geometry, materials.lacquered_wood)]);
    let legs_geometry = b.add_geometry(&legs);
    let legs_mesh = b.add_mesh("table_legs", &[(legs_geometry, materials.wood_matte)]);
    let group = b.add_node(NodeSpec::group("table", None, NodeTransform::at(DVec3::new(6.3, 0.0, -0.2))));
    let top_node = b.add_node(
        NodeSpec::instance("table_top", Some(group), top_mesh, NodeTransform::IDENTITY)
            .with_extras(PprExtras { ppr: PprOverride { reflector: false, kind: None } }),
    );
    b.add_node(NodeSpec::instance("table_legs", Some(group), legs_mesh, NodeTransform::IDENTITY));
    room.non_reflectors.push(NonReflectorSpec {
        node: top_node,
        primitive: 0,
        reason: "glossy material (roughness 0.2) but the node's extras say {\"ppr\": {\"reflector\": false}}",
    });
}

/// A 1.6 × 0.9 m brushed-metal floor panel (metallic, roughness 0.3) centred at
/// (1.0, 0.003, 1.85), marked a reflector: a glossy reflection in front of the cameras.
fn add_brushed_metal_panel(room: &mut DemoRoom, materials: &DemoMaterials) {
    let b = &mut room.builder;
    let panel = MeshData::quad(DVec3::new(-0.8, 0.0, -0.45), DVec3::Z * 0.9, DVec3::X * 1.6, 1.0);
    let geometry = b.add_geometry(&panel);
    let mesh = b.add_mesh("brushed_metal_panel", &[(geometry, materials.brushed_metal)]);
    let node = b.add_node(
        NodeSpec::instance(
            "brushed_metal_panel",
            None,
            mesh,
            NodeTransform::at(DVec3::new(1.0, 0.003, 1.85)),
        )
        .with_extras(PprExtras { ppr: PprOverride { reflector: true, kind: None } }),
    );
    room.reflector(node, 0, ReflectorKind::Opaque);
}

/// Default viewpoints for the other tools (60° vertical field of view).
fn add_cameras(room: &mut DemoRoom) {
    let yfov = (std::f64::consts::PI / 3.0) as f32;
    let b = &mut room.builder;
    // Room centre-front, looking at the mirror wall through and past the glass.
    b.add_camera("cam_overview", DVec3::new(0.0, 2.0, 5.0), DVec3::new(0.5, 1.5, -6.0), yfov);
    // Low, over the L floor and the puddles, towards the mirror wall.
    b.add_camera("cam_mirror", DVec3::new(-1.2, 0.5, 5.6), DVec3::new(-0.5, 0.2, -3.0), yfov);
    // Above the front-left, looking down the mirror stairs.
    b.add_camera("cam_steps", DVec3::new(-2.5, 2.3, 5.2), DVec3::new(-7.0, 0.7, 1.0), yfov);
}
