//! One frame of the demo room from `cam_mirror` at 160 × 90 on the software adapter (Bevy
//! through Vulkan: Mesa's lavapipe without a GPU): the Bevy app's reflector pixels against
//! `ppr-render`'s frame for the same camera.
//!
//! The two renderers light the level differently (Bevy's PBR with a directional light and
//! ambient set to the testbed's Lambert light, roughly; the testbed's Lambert exactly), and
//! the testbed resolves glass and water as layers where the plugin turns layers off, so the
//! frames are compared by PSNR over the pixels where `ppr-render`'s PPR found a reflection,
//! with a floor between what PPR off and PPR on give (the same Bevy frame without the plugin's
//! composite is also measured, so the floor is shown to tell the two apart).

use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use bevy::camera::RenderTarget;
use bevy::prelude::*;
use bevy::render::render_resource::{TextureFormat, TextureUsages};
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy_ppr::{PprCamera, PprReflectorSet};
use image::{Rgba32FImage, RgbaImage};

use crate::app::render_app;
use crate::scene::{ASSETS, DemoRoom, adopt_gltf_camera, spawn_room, tolerate_failed_pipelines};

const SIZE: [u32; 2] = [160, 90];
const CAMERA: &str = "cam_mirror";
/// Measured 15.7 dB with PPR, 11.8 dB without (Bevy on Mesa 22.3 lavapipe through Vulkan,
/// `ppr-render` on llvmpipe through GL or on lavapipe: the same numbers): the floor lies
/// between the two, so the frame without the plugin's composite fails it.
const MIN_PSNR_DB: f64 = 14.0;
/// How much nearer `ppr-render` PPR must bring the reflector pixels (measured: 3.9 dB).
const MIN_GAIN_DB: f64 = 2.0;

/// The demo set as the main command writes it (`ppr-extract`, default parameters).
fn extract_demo_set() -> ppr_format::ReflectorSet {
    let glb = Path::new(ASSETS).join("demo_room.glb");
    let level = ppr_extract::load_level(glb).expect("demo level loads");
    ppr_extract::extract(&level, &ppr_extract::ExtractParams::default(), &|_, _| {}).set
}

/// `ppr-render --camera cam_mirror --size 160x90`: its frame (sRGB) and its PPR reflection.
fn ppr_render(set: &ppr_format::ReflectorSet) -> (RgbaImage, Rgba32FImage) {
    let dir = tempfile::tempdir().expect("temp dir");
    let set_file = dir.path().join("demo_room.ppr.json");
    set.save(&set_file).expect("set saved");
    let gpu = ppr_testbed::GpuContext::new_headless().expect("an adapter (llvmpipe without a GPU)");
    let mut ppr = ppr_testbed::PprTechnique::new(
        &gpu.device,
        &gpu.queue,
        set,
        ppr_runtime_wgpu30::ReflectionSettings::ALL,
    )
    .expect("valid set");
    let job = ppr_testbed::RenderJob {
        level: Path::new(ASSETS).join("demo_room.glb"),
        reflectors: set_file,
        camera: Some(CAMERA.to_owned()),
        size: SIZE,
        projection: Default::default(),
        output: dir.path().join("frame.png"),
        composite: Default::default(),
        tone_map: ppr_testbed::ToneMap::Clamp,
        render: Default::default(),
        accept_level_mismatch: false,
    };
    ppr_testbed::render_job::run(&job, &gpu, Some(&mut ppr)).expect("ppr-render runs");
    let frame = image::open(dir.path().join("frame.png")).expect("frame.png").to_rgba8();
    let reflection =
        image::open(dir.path().join("frame.reflection.exr")).expect("reflection exr").to_rgba32f();
    (frame, reflection)
}

/// The camera renders into the test's image.
#[derive(Component)]
struct ImageCamera;

/// The Bevy app's frame of the PPR camera, with the plugin's composite or without it.
fn bevy_frame(set: &Arc<ppr_format::ReflectorSet>, with_ppr: bool) -> RgbaImage {
    let mut app = render_app(Path::new(ASSETS));
    let mut target = Image::new_target_texture(SIZE[0], SIZE[1], TextureFormat::Rgba8UnormSrgb, None);
    target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    let target = app.world_mut().resource_mut::<Assets<Image>>().add(target);
    let set = app
        .world_mut()
        .resource_mut::<Assets<PprReflectorSet>>()
        .add(PprReflectorSet { set: Arc::clone(set) });
    app.insert_resource(DemoRoom { camera: CAMERA.to_owned(), set })
        .insert_resource(tolerate_failed_pipelines());
    let image_target = target.clone();
    app.add_systems(Startup, spawn_room).add_systems(Update, adopt_gltf_camera).add_systems(
        PostUpdate,
        move |mut commands: Commands, added: Query<Entity, Added<PprCamera>>| {
            for entity in &added {
                // Bevy 0.19's `camera_system` sizes a camera's target when the camera is
                // added or its projection, viewport, window or image changes, not when its
                // `RenderTarget` is replaced: without the touch the glTF camera keeps no
                // target size and never renders into the image.
                commands
                    .entity(entity)
                    .insert((RenderTarget::Image(image_target.clone().into()), ImageCamera))
                    .entry::<Projection>()
                    .and_modify(|mut projection| projection.set_changed());
                if !with_ppr {
                    commands.entity(entity).remove::<PprCamera>();
                }
            }
        },
    );
    // Once the camera is up, capture every 30 frames until two captures agree: the scene
    // is loaded and every pipeline compiled (they compile in the background).
    let captured: Arc<Mutex<Vec<RgbaImage>>> = Arc::default();
    let deadline = Instant::now() + Duration::from_secs(120);
    let mut frames_with_camera = 0u32;
    while Instant::now() < deadline {
        app.update();
        if let Some(exit) = app.should_exit() {
            panic!("the app quit: {exit:?} (a render error; see the log)");
        }
        let world = app.world_mut();
        if world.query::<&ImageCamera>().iter(world).next().is_none() {
            std::thread::sleep(Duration::from_millis(5));
            continue;
        }
        frames_with_camera += 1;
        if frames_with_camera.is_multiple_of(30) {
            let sink = Arc::clone(&captured);
            world.spawn(Screenshot::image(target.clone())).observe(move |shot: On<ScreenshotCaptured>| {
                let image = shot.image.clone().try_into_dynamic().expect("8-bit capture").to_rgba8();
                sink.lock().expect("capture sink").push(image);
            });
        }
        let shots = captured.lock().expect("capture sink");
        if let [.., a, b] = shots.as_slice()
            && a == b
            && a.pixels().any(|p| p.0[..3] != [0, 0, 0])
        {
            return b.clone();
        }
    }
    let shots = captured.lock().expect("capture sink");
    let lit = shots.iter().filter(|s| s.pixels().any(|p| p.0[..3] != [0, 0, 0])).count();
    if let Some(last) = shots.last() {
        let _ = last.save(Path::new(env!("CARGO_TARGET_TMPDIR")).join("bevy_ppr-unsettled.png"));
    }
    panic!(
        "the Bevy frame did not settle within 120 s: {frames_with_camera} frames with the camera, {} captures, {lit} not black",
        shots.len()
    );
}

/// PSNR (dB, 8-bit sRGB) between two frames over the pixels where `mask` holds.
fn psnr(a: &RgbaImage, b: &RgbaImage, mask: impl Fn(u32, u32) -> bool) -> (f64, usize) {
    let (mut n, mut se) = (0usize, 0f64);
    for (x, y, pa) in a.enumerate_pixels() {
        if mask(x, y) {
            let pb = b.get_pixel(x, y);
            n += 1;
            se += (0..3).map(|c| (f64::from(pa.0[c]) - f64::from(pb.0[c])).powi(2) / 3.0).sum::<f64>();
        }
    }
    let mse = se / n.max(1) as f64;
    (10.0 * (255.0f64.powi(2) / mse.max(1e-12)).log10(), n)
}

#[test]
fn reflector_pixels_match_ppr_render() {
    let set = Arc::new(extract_demo_set());
    let (reference, reflection) = ppr_render(&set);
    let with = bevy_frame(&set, true);
    let without = bevy_frame(&set, false);
    let out_dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
    with.save(out_dir.join("bevy_ppr-cam_mirror.png")).expect("save");
    reference.save(out_dir.join("ppr-render-cam_mirror.png")).expect("save");
    let mask = |x: u32, y: u32| reflection.get_pixel(x, y).0[3] > 0.0;
    let (db, pixels) = psnr(&with, &reference, mask);
    let (db_off, _) = psnr(&without, &reference, mask);
    eprintln!(
        "cam_mirror {}x{}: {pixels} reflector pixels, PSNR {db:.1} dB with PPR, {db_off:.1} dB without",
        SIZE[0], SIZE[1]
    );
    assert!(pixels > 1000, "ppr-render must find reflections on cam_mirror: {pixels}");
    assert!(
        db >= MIN_PSNR_DB,
        "reflector pixels: {db:.1} dB < {MIN_PSNR_DB} dB (without PPR: {db_off:.1} dB)"
    );
    assert!(
        db >= db_off + MIN_GAIN_DB,
        "PPR must bring the frame {MIN_GAIN_DB} dB nearer ppr-render: {db:.1} dB vs {db_off:.1} dB without"
    );
}
