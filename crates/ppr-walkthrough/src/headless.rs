//! Headless mode: the same frame loop without a window, into an offscreen target, for
//! tests and CI (`--headless --frames N --screenshot out.png --camera ...`). The reflector
//! set comes through the same hot-reload watcher as in the window, and `--lose-device-at`
//! exercises the device-loss recovery. Unlike the window, it does not wait for a missing
//! set: a level or set it cannot use (missing, invalid, or extracted from another level
//! without `--accept-level-mismatch`) is a [`BadInput`] naming the file.

use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use image::{GrayImage, Rgba32FImage, RgbaImage};
use ppr_runtime::{Camera, FramePlan, PassTimings};

use crate::bad_input::BadInput;
use crate::camera_spec::pick_camera;
use crate::cli::Args;
use crate::gltf_level::LevelData;
use crate::gpu_context::{GpuContext, new_instance};
use crate::hot_reload::{ReflectorSetState, ReflectorSetWatcher, SetStatus, apply_first_event};
use crate::offscreen_target::{OFFSCREEN_FORMAT, OffscreenTarget};
use crate::overlay_text::{rasterise, scale_for_width};
use crate::screen_passes::ScreenPasses;
use crate::status_line::{StatusInputs, status_lines};
use crate::texture_readback::{read_r8, read_rgba16f};
use crate::walkthrough_renderer::WalkthroughRenderer;

/// How long start-up waits for the watcher's first reading of the set.
pub const FIRST_SET_TIMEOUT: Duration = Duration::from_secs(10);

/// The last frame of a headless run, with the buffers a test compares.
pub struct HeadlessFrame {
    /// The final image (composited, tone mapped, overlay), sRGB.
    pub image: RgbaImage,
    /// The forward pass's linear colour (what PPR reflects), before compositing.
    pub scene_color: Rgba32FImage,
    /// PPR's output: reflected colour, alpha its confidence (0 where none was found). All
    /// zero when the plan was empty.
    pub reflection: Rgba32FImage,
    /// The forward pass's reflection weight (reflectivity × Fresnel), 0–255.
    pub reflection_weight: GrayImage,
    pub plan: std::sync::Arc<FramePlan>,
    pub timings: Option<PassTimings>,
    pub camera: Camera,
    pub adapter: String,
    pub set_status: SetStatus,
    /// Times the device was lost and recreated during the run.
    pub device_recoveries: u32,
    /// GPU errors the error handler reported on the device that rendered the last frame.
    pub gpu_errors: u64,
}

/// Everything on one device; rebuilt whole after a device loss.
struct HeadlessSession {
    ctx: GpuContext,
    renderer: WalkthroughRenderer,
    screen: ScreenPasses,
    target: OffscreenTarget,
}

impl HeadlessSession {
    fn new(
        instance: &wgpu::Instance,
        level: &LevelData,
        sets: &ReflectorSetState,
        args: &Args,
    ) -> Result<Self> {
        let ctx = GpuContext::new(instance, None)?;
        let mut renderer =
            WalkthroughRenderer::new(&ctx.device, &ctx.queue, level, sets.set(), args.projection().depth)?;
        renderer.ppr.settings = args.settings();
        renderer.feed_previous_frame = args.feed_previous_frame;
        let screen = ScreenPasses::new(&ctx.device, &ctx.queue, OFFSCREEN_FORMAT);
        let target = OffscreenTarget::new(&ctx.device, args.size);
        Ok(Self { ctx, renderer, screen, target })
    }
}

/// Renders `args.frames` frames (at least 1) of `args.level` offscreen and returns the last;
/// writes it to `args.screenshot` when given.
///
/// # Errors
/// [`BadInput`] when the level does not load or the set is missing, invalid or refused
/// (another level's); otherwise the camera, no adapter, a readback or the PNG failing.
pub fn run_headless(args: &Args) -> Result<HeadlessFrame> {
    let level =
        LevelData::load(&args.level).map_err(|e| BadInput(format!("{:#}", anyhow::Error::from(e))))?;
    let camera = pick_camera(&level, args.camera.as_deref(), args.projection())?;
    let set_path = args.set_path();
    let watcher = ReflectorSetWatcher::start(&set_path);
    let mut sets =
        ReflectorSetState::new("not read yet").with_level_match(args.level_match(&level.source_hash));
    apply_first_event(&watcher, &mut sets, FIRST_SET_TIMEOUT);
    match sets.status() {
        SetStatus::Current { .. } => {}
        SetStatus::Waiting(why) | SetStatus::Refused { message: why, .. } => {
            return Err(BadInput(format!("no usable reflector set {}: {why}", set_path.display())).into());
        }
    }
    if let Some(warning) = sets.take_warning() {
        eprintln!("ppr-walkthrough: warning: {warning}");
    }

    let instance = new_instance(None);
    let mut session = HeadlessSession::new(&instance, &level, &sets, args)?;
    let mut recoveries = 0;
    let mut timings = None;
    let mut frame_ms = None;
    let mut plan = None;
    let frames = args.frames.unwrap_or(1).max(1);
    let set_file = set_path.display().to_string();
    // One more frame when the device is lost after the last one, so there is a frame to read.
    let mut frame = 0;
    while frame < frames || session.ctx.lost().is_some() {
        for event in watcher.poll() {
            if let Some(set) = sets.apply(event) {
                session.renderer.set_reflectors(set);
            }
            if let Some(warning) = sets.take_warning() {
                eprintln!("ppr-walkthrough: warning: {warning}");
            }
        }
        if let Some(reason) = session.ctx.lost() {
            eprintln!("ppr-walkthrough: device lost ({reason}); recreating the device and every resource");
            session = HeadlessSession::new(&instance, &level, &sets, args)?;
            recoveries += 1;
        }
        let started = Instant::now();
        let lines = status_lines(&StatusInputs {
            adapter: &session.ctx.describe(),
            size: args.size,
            frame_ms,
            plan: plan.as_deref(),
            timings: timings.as_ref(),
            timestamps: session.renderer.ppr.has_timestamps(),
            set_file: &set_file,
            set_status: sets.status(),
            settings: session.renderer.ppr.settings,
            view: args.view,
            speed: 0.0,
            device_recoveries: recoveries,
            surface_note: None,
            keys: false,
        });
        let text = rasterise(&lines, scale_for_width(args.size[0]), args.size[0].saturating_sub(16));
        session.screen.overlay.set_text(&session.ctx.device, &session.ctx.queue, text);
        let outputs = [(&session.screen, &session.target.view)];
        plan = Some(if args.stereo {
            let [left, _] = session.renderer.render_stereo(&camera, args.size, args.view, &outputs);
            left
        } else {
            session.renderer.render(&camera, args.size, args.view, &outputs)
        });
        timings = session.renderer.ppr.read_timings();
        frame_ms = Some(started.elapsed().as_secs_f64() * 1e3);
        if args.lose_device_at == Some(frame) {
            session.ctx.simulate_loss();
        }
        frame += 1;
    }

    let (device, queue) = (&session.ctx.device, &session.ctx.queue);
    let image = session.target.read(device, queue)?;
    let targets = session.renderer.targets().context("no frame was rendered")?;
    let scene_color = read_rgba16f(device, queue, &targets.color.texture)?;
    let reflection_weight = read_r8(device, queue, &targets.reflection_weight.texture)?;
    let plan = plan.context("no frame was rendered")?;
    let reflection = if plan.is_empty() {
        Rgba32FImage::new(targets.size[0], targets.size[1])
    } else {
        read_rgba16f(device, queue, &targets.reflection.texture)?
    };
    if let Some(path) = &args.screenshot {
        image.save(path).with_context(|| format!("{}: cannot write the screenshot", path.display()))?;
    }
    Ok(HeadlessFrame {
        image,
        scene_color,
        reflection,
        reflection_weight,
        plan,
        timings,
        camera,
        adapter: session.ctx.describe(),
        set_status: sets.status().clone(),
        device_recoveries: recoveries,
        gpu_errors: session.ctx.errors().0,
    })
}
