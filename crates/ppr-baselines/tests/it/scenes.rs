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

/// Whether a linear colour is the bar's (within rounding of `Rgba16Float`).
pub fn is_bar_color(c: [f32; 4]) -> bool {
    (0..3).all(|i| (c[i] - BAR_COLOR[i]).abs() < 0.02)
}
