//! Bevy apps for tests: no window, driven frame by frame.

use std::path::Path;

use bevy::asset::AssetPlugin;
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::renderer::RenderAdapterInfo;
use bevy::render::settings::{Backends, WgpuSettings};
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;

fn asset_plugin(assets: &Path, watch: bool) -> AssetPlugin {
    AssetPlugin {
        file_path: assets.display().to_string(),
        watch_for_changes_override: Some(watch),
        ..default()
    }
}

/// No rendering: the asset server reading `assets` (watching it when `watch`) and the PPR
/// plugin, which then registers only its asset and main-world systems.
pub fn asset_app(assets: &Path, watch: bool) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, asset_plugin(assets, watch), bevy_ppr::PprPlugin));
    app.finish();
    app.cleanup();
    app
}

/// Default plugins without a window or winit, assets read from `assets`, and the PPR plugin,
/// rendering through wgpu's Vulkan backend only: Mesa's lavapipe without a GPU (`.ci/run`
/// installs it). Bevy 0.19 on wgpu's GL backend (llvmpipe) never draws into an image target.
///
/// # Panics
///
/// Without a Vulkan adapter (Bevy's "Unable to find a GPU!"): the test fails, never skips.
pub fn render_app(assets: &Path) -> App {
    let mut app = App::new();
    let window = WindowPlugin { primary_window: None, exit_condition: ExitCondition::DontExit, ..default() };
    let render = RenderPlugin {
        render_creation: WgpuSettings { backends: Some(Backends::VULKAN), ..default() }.into(),
        ..default()
    };
    let plugins =
        DefaultPlugins.set(asset_plugin(assets, false)).set(window).set(render).disable::<WinitPlugin>();
    app.add_plugins((plugins, bevy_ppr::PprPlugin));
    app.finish();
    app.cleanup();
    let adapter: &wgpu::AdapterInfo =
        app.world().get_resource::<RenderAdapterInfo>().expect("Bevy created a renderer");
    assert_eq!(adapter.backend, wgpu::Backend::Vulkan, "{adapter:?}");
    eprintln!("bevy_ppr test app on {} ({:?}, {})", adapter.name, adapter.backend, adapter.driver_info);
    app
}

/// Runs frames until `done` says so or `max_frames` have run; returns whether it did.
pub fn run_until(app: &mut App, max_frames: u32, mut done: impl FnMut(&mut App) -> bool) -> bool {
    for _ in 0..max_frames {
        app.update();
        if done(app) {
            return true;
        }
    }
    false
}
