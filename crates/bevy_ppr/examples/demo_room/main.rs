//! `cargo run -p bevy_ppr --example demo_room [-- cam_steps] [--screenshot out.png]`: the
//! demo room in Bevy with PPR, flown with the mouse (left button) and WASD. Run the main
//! command first: `cargo run --release -p ppr-extract -- assets/demo_room.glb`.

mod scene;

use std::path::{Path, PathBuf};

use bevy::asset::AssetPlugin;
use bevy::camera_controller::free_camera::{FreeCamera, FreeCameraPlugin};
use bevy::diagnostic::{DiagnosticsStore, LogDiagnosticsPlugin};
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, save_to_disk};
use bevy_ppr::{PASS_DIAGNOSTICS, PprCamera, PprPlugin};

use scene::{ASSETS, DemoRoom, adopt_gltf_camera, spawn_room, tolerate_failed_pipelines};

/// `--screenshot PATH`: save the frame after this many frames, then quit.
const SCREENSHOT_FRAME: u32 = 90;

#[derive(Resource)]
struct ScreenshotAt(Option<PathBuf>);

fn main() -> AppExit {
    let mut args = std::env::args().skip(1);
    let (mut camera, mut screenshot) = ("cam_mirror".to_owned(), None);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--screenshot" => screenshot = args.next().map(PathBuf::from),
            _ => camera = arg,
        }
    }
    if !Path::new(ASSETS).join("demo_room.ppr.json").exists() {
        eprintln!(
            "no assets/demo_room.ppr.json: run `cargo run --release -p ppr-extract -- assets/demo_room.glb`"
        );
        return AppExit::error();
    }
    App::new()
        .add_plugins(DefaultPlugins.set(AssetPlugin {
            file_path: ASSETS.into(),
            // Save the set in the inspector and the running example takes it.
            watch_for_changes_override: Some(true),
            ..default()
        }))
        .add_plugins((
            PprPlugin,
            FreeCameraPlugin,
            LogDiagnosticsPlugin::filtered(PASS_DIAGNOSTICS.into_iter().collect()),
        ))
        .insert_resource(tolerate_failed_pipelines())
        .insert_resource(ScreenshotAt(screenshot))
        .insert_resource(CameraName(camera))
        .add_systems(Startup, (load_set, spawn_room))
        .add_systems(Update, (adopt_gltf_camera, fly, take_screenshot, title))
        .run()
}

#[derive(Resource)]
struct CameraName(String);

fn load_set(mut commands: Commands, assets: Res<AssetServer>, name: Res<CameraName>) {
    commands.insert_resource(DemoRoom { camera: name.0.clone(), set: assets.load("demo_room.ppr.json") });
}

/// The PPR camera flies.
fn fly(mut commands: Commands, cameras: Query<Entity, Added<PprCamera>>) {
    for entity in &cameras {
        commands.entity(entity).insert(FreeCamera::default());
    }
}

/// The window title shows the runtime's GPU time per frame.
fn title(store: Res<DiagnosticsStore>, mut windows: Query<&mut Window>) {
    let total = store.get(&PASS_DIAGNOSTICS[7]).and_then(|d| d.smoothed());
    for mut window in &mut windows {
        window.title = match total {
            Some(ms) => format!("bevy_ppr demo room: PPR {ms:.3} ms GPU"),
            None => "bevy_ppr demo room".to_owned(),
        };
    }
}

fn take_screenshot(
    mut commands: Commands,
    at: Res<ScreenshotAt>,
    mut frame: Local<u32>,
    mut exit: MessageWriter<AppExit>,
) {
    let Some(path) = &at.0 else { return };
    *frame += 1;
    if *frame == SCREENSHOT_FRAME {
        commands.spawn(Screenshot::primary_window()).observe(save_to_disk(path.clone()));
    }
    if *frame == SCREENSHOT_FRAME + 10 {
        exit.write(AppExit::Success);
    }
}
