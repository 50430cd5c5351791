//! Bevy apps for tests: no window, driven frame by frame.

use std::path::Path;

use bevy::asset::AssetPlugin;
use bevy::prelude::*;
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

/// Default plugins without a window or winit, assets read from `assets`, and the PPR plugin.
pub fn render_app(assets: &Path) -> App {
    let mut app = App::new();
    let window = WindowPlugin { primary_window: None, exit_condition: ExitCondition::DontExit, ..default() };
    let plugins = DefaultPlugins.set(asset_plugin(assets, false)).set(window).disable::<WinitPlugin>();
    app.add_plugins((plugins, bevy_ppr::PprPlugin));
    app.finish();
    app.cleanup();
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
