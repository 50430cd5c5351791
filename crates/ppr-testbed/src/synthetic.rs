//! Synthetic scenes built in code: a floor mirror with coloured boxes and its reflector set.
//!
//! Tests here and in `ppr-runtime` use them to render known geometry without files.

use glam::{DMat4, DVec2, DVec3, Vec3};
use ppr_format::{Reflector, ReflectorKind, ReflectorSet};
use ppr_runtime::{Camera, Projection};

use crate::level::{Level, LevelCamera, Material, Mesh};
use crate::shape_meshes::{cuboid, floor_quad};

/// A level, the reflector set that goes with it and a camera that sees the reflectors.
#[derive(Clone, Debug)]
pub struct SyntheticScene {
    /// The geometry.
    pub level: Level,
    /// The reflectors of the level.
    pub reflectors: ReflectorSet,
    /// A viewpoint that sees the reflectors (also stored as the level's first camera).
    pub camera: Camera,
}

/// What the floor-mirror scene contains.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FloorMirrorParams {
    /// Half size of the square mirror floor at y = 0, metres.
    pub floor_half_size: f64,
    /// Put a bright red box entirely below the floor (the reference must never show it).
    pub red_box_below: bool,
    /// Add a double-sided polished pane standing at z = −2.2 (x ∈ [−2.5, 2.5], y ∈ [0, 2.5],
    /// facing +Z, reflector 1) between the boxes and the pillar, like a glass panel.
    pub wall_pane: bool,
    /// Everything (geometry, reflectors, camera) is moved by this offset.
    pub offset: DVec3,
}

impl Default for FloorMirrorParams {
    fn default() -> Self {
        Self { floor_half_size: 4.0, red_box_below: true, wall_pane: false, offset: DVec3::ZERO }
    }
}

/// Linear colours of the boxes standing on the floor mirror, in the order they are placed.
pub const BOX_COLORS: [[f32; 3]; 3] = [[0.1, 0.8, 0.1], [0.1, 0.2, 0.9], [0.9, 0.8, 0.1]];

/// Linear colour of the box below the floor.
pub const BELOW_FLOOR_COLOR: [f32; 3] = [1.0, 0.0, 0.0];

impl SyntheticScene {
    /// A polished floor mirror at y = 0 (reflector 0, normal +Y) with three coloured boxes
    /// standing above it, a tall white pillar behind them, and optionally a red box below the
    /// floor; the camera looks down at the floor from 2 m up, 5 m back.
    pub fn floor_mirror(params: &FloorMirrorParams) -> Self {
        let mut level = Level::new();
        let mirror = level.add_material(Material::polished("floor_mirror", [0.3, 0.3, 0.32]));
        let half = params.floor_half_size as f32;
        let floor = level
            .add_mesh(Mesh { name: "floor".into(), primitives: vec![floor_quad(half, half, 1.0, mirror)] });
        level.add_instance("floor", floor, DMat4::IDENTITY);

        let boxes = [
            (DVec3::new(-1.2, 0.5, -0.5), Vec3::new(0.4, 0.5, 0.4)),
            (DVec3::new(0.3, 0.35, 0.4), Vec3::new(0.35, 0.35, 0.35)),
            (DVec3::new(1.4, 0.8, -1.2), Vec3::new(0.3, 0.8, 0.3)),
        ];
        for (k, ((center, half), color)) in boxes.into_iter().zip(BOX_COLORS).enumerate() {
            let material = level.add_material(Material::matte(format!("box_{k}"), color));
            let mesh =
                level.add_mesh(Mesh { name: format!("box_{k}"), primitives: vec![cuboid(half, material)] });
            level.add_instance(format!("box_{k}"), mesh, DMat4::from_translation(center));
        }
        let white = level.add_material(Material::matte("pillar", [0.85, 0.85, 0.85]));
        let pillar = level.add_mesh(Mesh {
            name: "pillar".into(),
            primitives: vec![cuboid(Vec3::new(0.3, 1.5, 0.3), white)],
        });
        level.add_instance("pillar", pillar, DMat4::from_translation(DVec3::new(-0.2, 1.5, -3.0)));
        if params.red_box_below {
            let red = level
                .add_material(Material { unlit: true, ..Material::matte("below_floor", BELOW_FLOOR_COLOR) });
            let below = level.add_mesh(Mesh {
                name: "below_floor".into(),
                primitives: vec![cuboid(Vec3::new(1.0, 0.4, 1.0), red)],
            });
            level.add_instance("below_floor", below, DMat4::from_translation(DVec3::new(0.0, -0.6, -0.5)));
        }

        if params.wall_pane {
            let pane = level.add_material(Material {
                double_sided: true,
                ..Material::polished("pane", [0.6, 0.62, 0.65])
            });
            let mut quad = floor_quad(2.5, 1.25, 1.0, pane);
            for v in &mut quad.vertices {
                // Stand the floor quad up: (x, 0, z) -> (x, -z, 0), normal +Y -> +Z.
                v.position = [v.position[0], -v.position[2], 0.0];
                v.normal = [0.0, 0.0, 1.0];
            }
            let mesh = level.add_mesh(Mesh { name: "pane".into(), primitives: vec![quad] });
            level.add_instance("pane", mesh, DMat4::from_translation(DVec3::new(0.0, 1.25, -2.2)));
        }

        let eye = DVec3::new(0.3, 2.0, 5.0);
        let target = DVec3::new(0.0, 0.0, -0.5);
        let camera =
            Camera::look_at(eye, target, Vec3::Y, Projection { far: Some(100.0), ..Projection::default() });
        level.cameras.push(LevelCamera {
            name: "synthetic_view".into(),
            world: DMat4::from_rotation_translation(camera.rotation.as_dquat(), eye),
            yfov: camera.projection.fov_y,
            znear: camera.projection.near,
            zfar: camera.projection.far,
        });

        let mut reflectors = ReflectorSet::new("synthetic:floor_mirror");
        reflectors.reflectors.push(Reflector::new(
            0,
            "floor_mirror",
            ReflectorKind::Opaque,
            DVec3::ZERO,
            DVec3::Y,
            DVec3::X,
            DVec2::splat(params.floor_half_size),
        ));
        if params.wall_pane {
            reflectors.reflectors.push(Reflector::new(
                1,
                "pane",
                ReflectorKind::Transparent,
                DVec3::new(0.0, 1.25, -2.2),
                DVec3::Z,
                DVec3::X,
                DVec2::new(2.5, 1.25),
            ));
        }
        // The wall pane faces another way than the floor: a parallel group of its own.
        reflectors.assign_parallel_groups();
        Self { level, reflectors, camera }.translated(params.offset)
    }

    /// The same scene with geometry, reflectors and camera moved by `offset`.
    pub fn translated(mut self, offset: DVec3) -> Self {
        if offset == DVec3::ZERO {
            return self;
        }
        self.level = self.level.translated(offset);
        for r in &mut self.reflectors.reflectors {
            r.center += offset;
        }
        self.camera.position += offset;
        self
    }
}
