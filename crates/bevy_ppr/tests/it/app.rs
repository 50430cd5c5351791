//! Bevy apps for tests: no window, driven frame by frame, and a lock that runs them one at
//! a time (llvmpipe on two cores gains nothing from two at once).

use std::path::Path;
use std::sync::{Mutex, MutexGuard};

use bevy::asset::AssetPlugin;
use bevy::prelude::*;
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;

pub fn lock() -> MutexGuard<'static, ()> {
    static LOCK: Mutex<()> = Mutex::new(());
    LOCK.lock().unwrap_or_else(|e| e.into_inner())
}

/// Default plugins without a window or winit, assets read from `assets`, and the PPR plugin.
pub fn headless_app(assets: &Path, watch: bool) -> App {
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(AssetPlugin {
                file_path: assets.display().to_string(),
                watch_for_changes_override: Some(watch),
                ..default()
            })
            .set(WindowPlugin { primary_window: None, exit_condition: ExitCondition::DontExit, ..default() })
            .disable::<WinitPlugin>(),
    )
    .add_plugins(bevy_ppr::PprPlugin);
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
