//! The demo room as the example and the headless test set it up: the glTF scene, the
//! testbed's light, and one of the level's glTF cameras made the PPR camera.

use bevy::camera::Camera3d;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::gltf::GltfAssetLabel;
use bevy::light::{DirectionalLight, GlobalAmbientLight};
use bevy::prelude::*;
use bevy::render::error_handler::{RenderErrorHandler, RenderErrorPolicy};
use bevy::world_serialization::WorldAssetRoot;
use bevy_ppr::{PprCamera, PprReflectorSet};

/// Where the workspace keeps `demo_room.glb` (and the main command writes its set).
pub const ASSETS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets");

/// `ppr-testbed`'s light (`Lighting::default`): towards the light, before normalising.
const LIGHT_TOWARDS: Vec3 = Vec3::new(0.35, 1.0, 0.55);

/// Bevy's default exposure (EV100 9.7) divides by about 998.5: these give the testbed's
/// Lambert intensity 0.85 and ambient 0.25 on a diffuse surface, roughly (Bevy's PBR adds
/// specular and its own diffuse term).
const LUX_PER_UNIT: f32 = 998.5 * std::f32::consts::PI;

/// Which glTF camera renders, and with which set.
#[derive(Resource, Clone)]
pub struct DemoRoom {
    /// A camera node of `demo_room.glb` (`cam_overview`, `cam_mirror`, `cam_steps`).
    pub camera: String,
    pub set: Handle<PprReflectorSet>,
}

/// Spawns the level and the light.
pub fn spawn_room(mut commands: Commands, assets: Res<AssetServer>) {
    commands.spawn(WorldAssetRoot(assets.load(GltfAssetLabel::Scene(0).from_asset("demo_room.glb"))));
    commands.spawn((
        DirectionalLight { illuminance: 0.85 * LUX_PER_UNIT, shadow_maps_enabled: false, ..default() },
        Transform::from_translation(LIGHT_TOWARDS).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.insert_resource(GlobalAmbientLight { brightness: 0.25 * 998.5, ..default() });
}

/// As the level's cameras appear: the chosen one becomes the PPR camera, the others are
/// switched off. No tone mapping (as `ppr-render` writes its frames; Bevy's default needs
/// the `tonemapping_luts` feature).
pub fn adopt_gltf_camera(
    mut commands: Commands,
    room: Res<DemoRoom>,
    mut cameras: Query<(Entity, &Name, &mut Camera), Added<Camera3d>>,
) {
    for (entity, name, mut camera) in &mut cameras {
        let chosen = name.as_str() == room.camera;
        camera.is_active = chosen;
        commands.entity(entity).insert(Tonemapping::None);
        if chosen {
            commands.entity(entity).insert(PprCamera::new(room.set.clone()));
        }
    }
}

/// Keeps rendering when a pipeline fails to build (an error whose description names a
/// pipeline, logged by Bevy; that pipeline is then unusable); quits on any other. Bevy 0.19 compiles its SSAO depth-preprocess shader at
/// start-up whether or not a camera uses SSAO, and on wgpu's GL backend (Mesa's llvmpipe,
/// no GPU) naga's GLSL for it does not compile (`textureGatherOffset` on a shadow
/// sampler): Bevy's default handler would quit. Nothing here uses SSAO.
pub fn tolerate_failed_pipelines() -> RenderErrorHandler {
    RenderErrorHandler(|error, main_world, _| {
        if error.description.to_lowercase().contains("pipeline") {
            return RenderErrorPolicy::Ignore;
        }
        main_world.write_message(AppExit::error());
        RenderErrorPolicy::StopRendering
    })
}
