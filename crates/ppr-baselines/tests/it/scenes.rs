//! Test scenes: the testbed's floor mirror, and the same with a thin bar floating above it.

use glam::{DMat4, DVec3, Vec3};
use ppr_testbed::level::{Material, Mesh};
use ppr_testbed::shape_meshes::cuboid;
use ppr_testbed::{FloorMirrorParams, SyntheticScene};

/// Linear colour of the thin bar (unlit, so the reflection shows it exactly).
pub const BAR_COLOR: [f32; 3] = [1.0, 0.0, 1.0];

/// The testbed's floor mirror with its boxes and pillar.
pub fn floor_mirror() -> SyntheticScene {
    SyntheticScene::floor_mirror(&FloorMirrorParams::default())
}

/// The floor mirror with a thin horizontal bar (3 cm square section, 3 m long, running
/// along x at 0.6 m height, 1.5 m in front of the boxes): about one pixel tall in the test
/// image, crossed in one or two pixels by the reflection rays, which climb the screen.
pub fn floor_mirror_with_bar() -> SyntheticScene {
    let mut scene = floor_mirror();
    let level = &mut scene.level;
    let material = level.add_material(Material { unlit: true, ..Material::matte("bar", BAR_COLOR) });
    let mesh = level.add_mesh(Mesh {
        name: "bar".into(),
        primitives: vec![cuboid(Vec3::new(1.5, 0.015, 0.015), material)],
    });
    level.add_instance("bar", mesh, DMat4::from_translation(DVec3::new(0.0, 0.6, 1.5)));
    scene
}

/// A larger floor mirror (12 m square) with a wide wall standing behind the boxes (z = −3.8,
/// 12 m wide, 2.5 m tall): its reflection reaches the left and right screen edges, where
/// the reflected points lie beyond the screen.
pub fn floor_mirror_with_wall() -> SyntheticScene {
    let mut scene =
        SyntheticScene::floor_mirror(&FloorMirrorParams { floor_half_size: 6.0, ..Default::default() });
    let level = &mut scene.level;
    let material = level.add_material(Material::matte("wall", [0.8, 0.45, 0.2]));
    let mesh = level.add_mesh(Mesh {
        name: "wall".into(),
        primitives: vec![cuboid(Vec3::new(6.0, 1.25, 0.05), material)],
    });
    level.add_instance("wall", mesh, DMat4::from_translation(DVec3::new(0.0, 1.25, -3.8)));
    scene
}

/// Whether a linear colour is the bar's (within rounding of `Rgba16Float`).
pub fn is_bar_color(c: [f32; 4]) -> bool {
    (0..3).all(|i| (c[i] - BAR_COLOR[i]).abs() < 0.02)
}
