//! The G-buffer: image orientation, reflector mask, negative-scale instances.

use glam::{DMat4, DVec3, Vec3};
use ppr_testbed::shape_meshes::cuboid;
use ppr_testbed::synthetic::BOX_COLORS;
use ppr_testbed::{FloorMirrorParams, Level, Material, SyntheticScene};

use crate::common::{render, timed};

const SIZE: [u32; 2] = [128, 96];

#[test]
fn gbuffer_marks_the_floor_and_puts_pixel_zero_top_left() {
    timed("gbuffer_marks_the_floor_and_puts_pixel_zero_top_left", || {
        let scene = SyntheticScene::floor_mirror(&FloorMirrorParams::default());
        let frame = render(&scene, &scene.camera, SIZE);
        let [w, h] = SIZE;
        let row_ids = |y: u32| (0..w).filter(|&x| frame.reflector_id.get(x, y) == 1).count();
        // The camera looks down at the floor: the floor fills the bottom row, the top row
        // sees over it (background and the pillar).
        assert_eq!(row_ids(h - 1), w as usize, "bottom row must be all floor");
        assert!(row_ids(0) < (w / 2) as usize, "top row is mostly above the floor");
        assert!(frame.reflector_id.data.iter().all(|&id| id <= 1), "one reflector only");
        // Box pixels (lit green, blue or yellow) are never reflector pixels.
        let mut box_pixels = 0;
        for (x, y, p) in frame.color.enumerate_pixels() {
            let rgb = [p.0[0], p.0[1], p.0[2]];
            let is_box = BOX_COLORS.iter().any(|c| {
                let max = c.iter().cloned().fold(0.0, f32::max);
                let ratio = |k: usize| rgb[k] / rgb.iter().cloned().fold(1e-6, f32::max);
                (0..3).all(|k| (ratio(k) - c[k] / max).abs() < 0.05)
            });
            if is_box && frame.reflector_id.get(x, y) == 0 {
                box_pixels += 1;
            }
            if is_box {
                assert_eq!(frame.reflector_id.get(x, y), 0, "box pixel ({x}, {y}) marked as reflector");
            }
        }
        assert!(box_pixels > 200, "boxes visible: {box_pixels}");
        // Normals: floor pixels face up.
        let n = frame.normal.get_pixel(w / 2, h - 1).0;
        assert!((n[1] - 1.0).abs() < 1e-3, "floor normal {n:?}");
    });
}

#[test]
fn matte_surfaces_on_a_reflector_plane_are_not_reflectors_by_default() {
    timed("matte_surfaces_on_a_reflector_plane_are_not_reflectors_by_default", || {
        let mut scene = SyntheticScene::floor_mirror(&FloorMirrorParams::default());
        scene.level.materials[0] = Material::matte("matte_floor", [0.3, 0.3, 0.3]);
        let frame = render(&scene, &scene.camera, SIZE);
        assert_eq!(frame.reflector_mask().count(), 0, "matte floor must not be a reflector");
    });
}

fn single_box(scale: DVec3) -> SyntheticScene {
    let mut scene =
        SyntheticScene::floor_mirror(&FloorMirrorParams { red_box_below: false, ..Default::default() });
    let mut level = Level::new();
    let m = level.add_material(Material::matte("box", [0.8, 0.4, 0.1]));
    let mesh = level.add_mesh(ppr_testbed::level::Mesh {
        name: "box".into(),
        primitives: vec![cuboid(Vec3::new(0.7, 0.5, 0.3), m)],
    });
    level.add_instance(
        "box",
        mesh,
        DMat4::from_translation(DVec3::new(0.0, 0.8, 0.0)) * DMat4::from_scale(scale),
    );
    scene.level = level;
    scene
}

/// A box mirrored by a negative scale renders exactly like the unmirrored box (it is the
/// same shape): winding flips are handled, so the front faces are the ones drawn.
#[test]
fn negative_scale_instances_render_like_their_twins() {
    timed("negative_scale_instances_render_like_their_twins", || {
        let plain = single_box(DVec3::ONE);
        let flipped = single_box(DVec3::new(-1.0, 1.0, 1.0));
        assert!(flipped.level.instances[0].flips_winding());
        let a = render(&plain, &plain.camera, SIZE);
        let b = render(&flipped, &flipped.camera, SIZE);
        let lit = a.color.pixels().filter(|p| p.0[0] > 0.3).count();
        assert!(lit > 300, "box visible: {lit} pixels");
        let differ = a
            .color
            .pixels()
            .zip(b.color.pixels())
            .filter(|(p, q)| (0..3).any(|c| (p.0[c] - q.0[c]).abs() > 0.01))
            .count();
        assert!(differ <= 10, "{differ} pixels differ between the box and its mirrored twin");
    });
}

/// A level without reflectors (or with only disabled ones) renders; nothing is marked and
/// the reference is empty.
#[test]
fn sets_without_enabled_reflectors_give_an_empty_reference() {
    timed("sets_without_enabled_reflectors_give_an_empty_reference", || {
        let mut scene = SyntheticScene::floor_mirror(&FloorMirrorParams::default());
        for set_up in [0, 1] {
            if set_up == 0 {
                scene.reflectors.reflectors.clear();
            } else {
                scene = SyntheticScene::floor_mirror(&FloorMirrorParams::default());
                scene.reflectors.reflectors[0].enabled = false;
            }
            let frame = render(&scene, &scene.camera, SIZE);
            assert_eq!(frame.reflector_mask().count(), 0);
            assert!(frame.reference.pixels().all(|p| p.0 == [0.0; 4]), "reference must be cleared");
            assert!(frame.reference_class.data.iter().all(|&c| c == 0));
        }
    });
}
