//! The walkthrough's headless frame of the demo level against the testbed's frame of the
//! same camera and set.
//!
//! The two renderers composite differently (the walkthrough mixes by reflectivity ×
//! Fresnel and tone maps; the testbed mixes over its reflector mask), so what is compared is
//! what both compute the same way:
//!
//! - the **scene colour before compositing** (`Rgba16Float`): both light the level with the
//!   same sun and ambient, so it must agree except where the walkthrough blends the glass
//!   panel (the testbed draws it opaque); those pixels are left out (alpha < 1 in the
//!   walkthrough's colour);
//! - **PPR's raw output**: the runtime is the same and fed the same colour and depth, so the
//!   pixels where a reflection was found and its colour must agree. The camera keeps the
//!   glass panel out of view (its blending changes depth and colour behind it).

use image::Rgba32FImage;
use ppr_format::ReflectorSet;
use ppr_runtime::{Choice, ReflectionSettings};
use ppr_testbed::camera_spec::{ProjectionChoice, pick_camera};
use ppr_testbed::readback::read_rgba_f32;
use ppr_testbed::{GpuContext, Level, LevelRenderer, PprTechnique, ReflectionInputs, ReflectionTechnique};
use ppr_walkthrough::run_headless;

use crate::common::{asset, demo_set_file, difference, gpu_lock, headless_args};

/// The view compared: down the five mirror steps (parallel reflectors), the puddles and the
/// water basin; the glass panel is out of view.
const CAMERA: &str = "cam_steps";
const SIZE: [u32; 2] = [320, 180];

/// Tolerances, set on llvmpipe 22.3 through GL, where the run measured: scene colour
/// 103.9 dB (identical up to f32 rounding: the same shading maths on the same triangles);
/// reflections found at the same 6938 pixels (100%), 64.3 dB over them. The bounds leave
/// room for another adapter's rounding while anything structural (another light, a missing
/// mesh or texture, a wrong depth convention, a shifted reflection) falls far below them:
/// a one-pixel shift of the reflections alone measures 21.9 dB here (asserted below).
const SCENE_MIN_PSNR_DB: f64 = 50.0;
const FOUND_MIN_AGREEMENT: f64 = 0.99;
const REFLECTION_MIN_PSNR_DB: f64 = 40.0;

struct TestbedFrame {
    color: Rgba32FImage,
    reflection: Rgba32FImage,
    adapter: String,
}

fn testbed_frame(set: &ReflectorSet) -> TestbedFrame {
    let gpu = GpuContext::new_headless().expect("the testbed needs an adapter");
    let (device, queue) = (&gpu.device, &gpu.queue);
    let level = Level::load_gltf(asset("demo_room.glb")).expect("demo level");
    let camera = pick_camera(&level, Some(CAMERA), ProjectionChoice::default()).expect("camera");
    let mut renderer = LevelRenderer::new(device, queue, &level, set);
    renderer.prepare(device, queue, &camera, SIZE);
    let output = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("testbed ppr output"),
        size: wgpu::Extent3d { width: SIZE[0], height: SIZE[1], depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: ppr_runtime::OUTPUT_FORMAT,
        usage: wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = output.create_view(&Default::default());
    let mut ppr = PprTechnique::new(device, queue, set, ReflectionSettings::ALL).expect("a valid set");
    // As in the walkthrough: no glass or water layers, water in the main buffer.
    ppr.renderer().plan_params.layers = Choice::Off;
    ppr.prepare(device, queue, &camera, SIZE);
    let mut encoder = device.create_command_encoder(&Default::default());
    renderer.encode_gbuffer(&mut encoder);
    ppr.encode(&mut encoder, &ReflectionInputs::from_gbuffer(renderer.gbuffer(), &view));
    queue.submit([encoder.finish()]);
    TestbedFrame {
        color: read_rgba_f32(device, queue, &renderer.gbuffer().color.texture).expect("colour readback"),
        reflection: read_rgba_f32(device, queue, &output).expect("reflection readback"),
        adapter: gpu.describe(),
    }
}

#[test]
fn headless_frame_matches_the_testbed_frame_of_the_same_camera() {
    let _gpu = gpu_lock();
    let size = format!("{}x{}", SIZE[0], SIZE[1]);
    let args = headless_args(&["--camera", CAMERA, "--size", &size, "--frames", "3"]);
    let ours = run_headless(&args).expect("headless run");
    assert_eq!(ours.device_recoveries, 0);
    assert_eq!(ours.gpu_errors, 0, "wgpu reported errors");
    assert!(!ours.plan.visible.is_empty(), "the demo camera sees reflectors: {}", ours.plan);

    let set = ReflectorSet::load(demo_set_file()).expect("set");
    let theirs = testbed_frame(&set);
    eprintln!("[walkthrough] adapter: {} / testbed adapter: {}", ours.adapter, theirs.adapter);

    if let Some(dir) = std::env::var_os("PPR_WALKTHROUGH_ARTIFACTS") {
        let dir = std::path::PathBuf::from(dir);
        std::fs::create_dir_all(&dir).expect("artifact dir");
        ours.image.save(dir.join("walkthrough-final.png")).expect("png");
        let png = |img: &Rgba32FImage, name: &str| {
            let rgba = image::RgbaImage::from_fn(img.width(), img.height(), |x, y| {
                let p = img.get_pixel(x, y).0;
                let c = |v: f32| (v.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0) as u8;
                image::Rgba([c(p[0]), c(p[1]), c(p[2]), 255])
            });
            rgba.save(dir.join(name)).expect("png");
        };
        png(&ours.scene_color, "walkthrough-scene.png");
        png(&theirs.color, "testbed-scene.png");
        png(&ours.reflection, "walkthrough-reflection.png");
        png(&theirs.reflection, "testbed-reflection.png");
    }

    // Scene colour, leaving out what the glass covers in the walkthrough's frame.
    let opaque = |x, y| ours.scene_color.get_pixel(x, y).0[3] >= 0.999;
    let scene = difference(&ours.scene_color, &theirs.color, opaque);
    let total = (SIZE[0] * SIZE[1]) as usize;
    eprintln!(
        "[walkthrough] scene colour over {} of {total} pixels: PSNR {:.1} dB, mean error {:.5}",
        scene.pixels, scene.psnr_db, scene.mean_abs_error
    );
    assert!(scene.pixels > total * 3 / 4, "most of the frame is compared ({} pixels)", scene.pixels);
    assert!(scene.psnr_db >= SCENE_MIN_PSNR_DB, "scene colour PSNR {:.1} dB", scene.psnr_db);

    // PPR's output: where a reflection was found, and what it shows.
    let found = |img: &Rgba32FImage, x, y| img.get_pixel(x, y).0[3] > 0.0;
    let (mut either, mut both) = (0usize, 0usize);
    for (x, y, _) in ours.reflection.enumerate_pixels() {
        let (a, b) = (found(&ours.reflection, x, y), found(&theirs.reflection, x, y));
        either += usize::from(a || b);
        both += usize::from(a && b);
    }
    let agreement = both as f64 / either.max(1) as f64;
    let reflection = difference(&ours.reflection, &theirs.reflection, |x, y| {
        found(&ours.reflection, x, y) && found(&theirs.reflection, x, y)
    });
    eprintln!(
        "[walkthrough] reflections: found by either {either}, by both {both} ({:.2}%); over both: PSNR {:.1} dB, mean error {:.5}",
        agreement * 100.0,
        reflection.psnr_db,
        reflection.mean_abs_error
    );
    assert!(either > total / 50, "reflections cover a visible part of the frame ({either} pixels)");
    assert!(agreement >= FOUND_MIN_AGREEMENT, "found-pixel agreement {:.3}", agreement);
    assert!(reflection.psnr_db >= REFLECTION_MIN_PSNR_DB, "reflection PSNR {:.1} dB", reflection.psnr_db);

    // The bound has teeth: the same comparison with the reflections one pixel to the right
    // falls below it.
    let shifted =
        Rgba32FImage::from_fn(SIZE[0], SIZE[1], |x, y| *ours.reflection.get_pixel(x.saturating_sub(1), y));
    let shifted = difference(&shifted, &theirs.reflection, |x, y| {
        found(&ours.reflection, x, y) && found(&theirs.reflection, x, y)
    });
    eprintln!("[walkthrough] reflections shifted by one pixel: PSNR {:.1} dB", shifted.psnr_db);
    assert!(shifted.psnr_db < REFLECTION_MIN_PSNR_DB, "a one-pixel shift passes ({:.1} dB)", shifted.psnr_db);

    // And the composite shows them: the final image differs from no reflections somewhere.
    assert!(ours.image.pixels().any(|p| p.0 != [0, 0, 0, 255]), "the final image is not black");
}
