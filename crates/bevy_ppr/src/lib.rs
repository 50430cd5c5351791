//! Pixel-projected reflections in Bevy 0.19: a `*.ppr.json` asset, a camera component, the
//! render-world pass that runs `ppr-runtime` after the opaque pass, and its GPU times as
//! diagnostics.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_ppr::{PprCamera, PprPlugin};
//!
//! fn setup(mut commands: Commands, assets: Res<AssetServer>) {
//!     commands.spawn((Camera3d::default(), PprCamera::new(assets.load("demo_room.ppr.json"))));
//! }
//! # fn main() { App::new().add_plugins(PprPlugin).add_systems(Startup, setup); }
//! ```
//!
//! Bevy renders with wgpu 29: the runtime comes from `ppr-runtime-wgpu29`, the same sources
//! as `ppr-runtime` built against it.

mod asset;
mod camera;
mod composite;
mod diagnostics;
mod render;
mod runtime;

use bevy::app::{App, Plugin, PostUpdate, Update};
use bevy::asset::{AssetApp, Assets};
use bevy::core_pipeline::core_3d::main_opaque_pass_3d;
use bevy::core_pipeline::schedule::{Core3d, Core3dSystems};
use bevy::ecs::schedule::IntoScheduleConfigs;
use bevy::pbr::main_transmissive_pass_3d;
use bevy::render::{ExtractSchedule, Render, RenderApp, RenderStartup, RenderSystems};
use bevy::shader::Shader;

use composite::CompositeShader;

pub use asset::{PprReflectorSet, ReflectorSetLoadError, ReflectorSetLoader, parse_reflector_set};
pub use camera::PprCamera;
pub use diagnostics::PASS_DIAGNOSTICS;
pub use ppr_runtime::{ReflectionSettings, ResolutionTier};

/// Adds the `*.ppr.json` loader, [`PprCamera`] and the render-world pass. Add it after
/// `DefaultPlugins` (it needs the asset server and the render app).
pub struct PprPlugin;

impl Plugin for PprPlugin {
    fn build(&self, app: &mut App) {
        let timings = diagnostics::PendingTimings::default();
        app.init_asset::<PprReflectorSet>()
            .init_asset_loader::<ReflectorSetLoader>()
            .insert_resource(timings.clone())
            .add_systems(PostUpdate, camera::configure_ppr_cameras)
            .add_systems(Update, diagnostics::record_timings);
        diagnostics::register(app);
        let shader =
            app.world_mut().get_resource_mut::<Assets<Shader>>().map(|mut s| CompositeShader::add(&mut s));
        let (Some(shader), Some(render_app)) = (shader, app.get_sub_app_mut(RenderApp)) else {
            return;
        };
        render_app
            .insert_resource(timings)
            .insert_resource(shader)
            .init_resource::<render::PprViews>()
            .add_systems(RenderStartup, composite::init_composite_pipeline)
            .add_systems(ExtractSchedule, render::extract_ppr_cameras)
            .add_systems(Render, render::prune_views.in_set(RenderSystems::Cleanup))
            .add_systems(
                Core3d,
                // Opaque colour and depth are final (deferred lighting ran before the opaque
                // pass); glass, water and other transmissive or transparent surfaces draw over.
                render::ppr_pass
                    .after(main_opaque_pass_3d)
                    .before(main_transmissive_pass_3d)
                    .in_set(Core3dSystems::MainPass),
            );
    }
}
