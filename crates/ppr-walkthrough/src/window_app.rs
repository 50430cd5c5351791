//! The windowed walkthrough: a winit `ApplicationHandler` that owns the window, the wgpu
//! surface and the [`WalkthroughRenderer`], flies the camera, reloads the reflector set,
//! and survives resizes, minimising, surface loss and a lost device.

use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use ppr_runtime::{FramePlan, PassTimings};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{DeviceEvent, DeviceId, ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::PhysicalKey;
use winit::window::{Window, WindowId};

use crate::bad_input::BadInput;
use crate::camera_spec::{level_camera, pick_camera};
use crate::cli::Args;
use crate::controls::{Action, action, update_move_keys};
use crate::fly_camera::{FlyCamera, MoveKeys};
use crate::frame_clock::FrameClock;
use crate::gltf_level::LevelData;
use crate::gpu_context::{GpuContext, new_instance};
use crate::hot_reload::{ReflectorSetState, ReflectorSetWatcher};
use crate::offscreen_target::{OFFSCREEN_FORMAT, OffscreenTarget};
use crate::overlay_text::{rasterise, scale_for_width};
use crate::screen_passes::ScreenPasses;
use crate::status_line::{StatusInputs, status_lines};
use crate::surface_state::{AcquireOutcome, AfterAcquire, BeforeFrame, SurfaceState};
use crate::view_mode::ViewMode;
use crate::walkthrough_renderer::WalkthroughRenderer;

/// PPR's GPU times are read (a wait for the GPU) this often, not every frame.
pub const TIMINGS_EVERY: Duration = Duration::from_millis(500);
/// After a failed device re-creation, wait this long before the next try.
pub const RETRY_AFTER: Duration = Duration::from_secs(1);
/// Fly speed at start, metres per second.
pub const START_SPEED: f64 = 2.0;

/// Opens the window and runs until it is closed (or `--frames` frames were shown).
///
/// # Errors
/// Loading the level or the camera, no event loop, or a fatal GPU error at start-up.
pub fn run_window(args: Args) -> Result<()> {
    let level =
        LevelData::load(&args.level).map_err(|e| BadInput(format!("{:#}", anyhow::Error::from(e))))?;
    let camera = pick_camera(&level, args.camera.as_deref(), args.projection())?;
    let sets = ReflectorSetState::new("not read yet").with_level_match(args.level_match(&level.source_hash));
    let event_loop = EventLoop::new().context("cannot open a window (no display?); try --headless")?;
    let instance = new_instance(Some(Box::new(event_loop.owned_display_handle())));
    let watcher = ReflectorSetWatcher::start(args.set_path());
    let mut app = WalkthroughApp {
        fly: FlyCamera::from_camera(&camera, START_SPEED),
        set_file: args.set_path().display().to_string(),
        view: args.view,
        settings: args.settings(),
        args,
        level,
        instance,
        watcher,
        sets,
        keys: MoveKeys::default(),
        looking: false,
        occluded: false,
        camera_index: 0,
        window: None,
        session: None,
        surface: SurfaceState::default(),
        clock: FrameClock::new(Instant::now()),
        timings: None,
        timings_read: Instant::now(),
        plan: None,
        recoveries: 0,
        surface_note: None,
        frames: 0,
        retry_at: None,
        fatal: None,
    };
    event_loop.run_app(&mut app).context("event loop")?;
    app.fatal.map_or(Ok(()), Err)
}

/// Everything on one device; dropped and rebuilt whole after a device loss.
struct WindowSession {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    ctx: GpuContext,
    renderer: WalkthroughRenderer,
    screen: ScreenPasses,
}

impl WindowSession {
    fn new(
        instance: &wgpu::Instance,
        window: &Arc<Window>,
        level: &LevelData,
        sets: &ReflectorSetState,
        args: &Args,
        settings: ppr_runtime::ReflectionSettings,
    ) -> Result<Self> {
        let surface = instance.create_surface(Arc::clone(window)).context("cannot create the surface")?;
        let ctx = GpuContext::new(instance, Some(&surface))?;
        let size = window.inner_size();
        let mut config = surface
            .get_default_config(&ctx.adapter, size.width.max(1), size.height.max(1))
            .context("the adapter cannot present to this window")?;
        // An sRGB format when there is one (the composite encodes otherwise).
        let caps = surface.get_capabilities(&ctx.adapter);
        config.format = caps.formats.iter().copied().find(|f| f.is_srgb()).unwrap_or(config.format);
        config.present_mode = wgpu::PresentMode::AutoVsync;
        // Stereo copies each eye into its half of the swapchain image.
        if args.stereo {
            anyhow::ensure!(
                caps.usages.contains(wgpu::TextureUsages::COPY_DST),
                "--stereo: this window's surface cannot be copied into (no COPY_DST usage); use the headless mode"
            );
            config.usage |= wgpu::TextureUsages::COPY_DST;
        }
        let mut renderer =
            WalkthroughRenderer::new(&ctx.device, &ctx.queue, level, sets.set(), args.projection().depth)?;
        renderer.ppr.settings = settings;
        renderer.feed_previous_frame = args.feed_previous_frame;
        let screen = ScreenPasses::new(&ctx.device, &ctx.queue, config.format);
        Ok(Self { surface, config, ctx, renderer, screen })
    }

    fn configure(&mut self, [width, height]: [u32; 2]) {
        self.config.width = width;
        self.config.height = height;
        self.surface.configure(&self.ctx.device, &self.config);
    }
}

struct WalkthroughApp {
    args: Args,
    level: LevelData,
    instance: wgpu::Instance,
    watcher: ReflectorSetWatcher,
    sets: ReflectorSetState,
    set_file: String,
    fly: FlyCamera,
    keys: MoveKeys,
    /// The right mouse button is held: mouse motion turns the camera.
    looking: bool,
    /// The last `WindowEvent::Occluded`.
    occluded: bool,
    camera_index: usize,
    settings: ppr_runtime::ReflectionSettings,
    view: ViewMode,
    window: Option<Arc<Window>>,
    session: Option<WindowSession>,
    surface: SurfaceState,
    clock: FrameClock,
    timings: Option<PassTimings>,
    timings_read: Instant,
    plan: Option<std::sync::Arc<FramePlan>>,
    recoveries: u32,
    surface_note: Option<&'static str>,
    frames: u32,
    retry_at: Option<Instant>,
    fatal: Option<anyhow::Error>,
}

impl WalkthroughApp {
    fn poll_reflector_set(&mut self) {
        for event in self.watcher.poll() {
            if let Some(set) = self.sets.apply(event)
                && let Some(session) = &mut self.session
            {
                session.renderer.set_reflectors(set);
            }
            if let Some(warning) = self.sets.take_warning() {
                eprintln!("ppr-walkthrough: warning: {warning}");
            }
        }
    }

    /// Makes sure there is a working session: rebuilds it after a device loss.
    fn ensure_session(&mut self) {
        if let Some(reason) = self.session.as_ref().and_then(|s| s.ctx.lost()) {
            eprintln!("ppr-walkthrough: device lost ({reason}); recreating the device and every resource");
            self.session = None;
            self.recoveries += 1;
        }
        if self.session.is_some() || self.retry_at.is_some_and(|t| Instant::now() < t) {
            return;
        }
        let Some(window) = &self.window else { return };
        match WindowSession::new(&self.instance, window, &self.level, &self.sets, &self.args, self.settings) {
            Ok(session) => {
                self.session = Some(session);
                self.surface = SurfaceState::new(self.surface.window_size());
                self.retry_at = None;
                self.clock.resume(Instant::now());
            }
            Err(e) if self.recoveries == 0 => self.fatal = Some(e),
            Err(e) => {
                eprintln!("ppr-walkthrough: cannot recreate the device yet: {e:#}");
                self.retry_at = Some(Instant::now() + RETRY_AFTER);
            }
        }
    }

    fn act(&mut self, action: Action, event_loop: &ActiveEventLoop) {
        match action {
            Action::ToggleHoles => self.settings.holes = !self.settings.holes,
            Action::ToggleFiltering => self.settings.filtering = !self.settings.filtering,
            Action::ToggleAntiBleeding => self.settings.anti_bleeding = !self.settings.anti_bleeding,
            Action::ToggleGlossy => self.settings.glossy = !self.settings.glossy,
            // Kept in `args`, so that a session rebuilt after a device loss keeps it.
            Action::TogglePreviousFrame => self.args.feed_previous_frame = !self.args.feed_previous_frame,
            Action::NextView => self.view = self.view.next(),
            Action::NextCamera => {
                if !self.level.cameras.is_empty() {
                    self.camera_index = (self.camera_index + 1) % self.level.cameras.len();
                    let camera = level_camera(&self.level.cameras[self.camera_index], self.args.projection());
                    self.fly = FlyCamera::from_camera(&camera, self.fly.speed);
                }
            }
            Action::LoseDevice => {
                if let Some(session) = &self.session {
                    session.ctx.simulate_loss();
                }
            }
            Action::Quit => event_loop.exit(),
        }
        if let Some(session) = &mut self.session {
            session.renderer.ppr.settings = self.settings;
            session.renderer.feed_previous_frame = self.args.feed_previous_frame;
        }
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let dt = self.clock.tick(Instant::now());
        self.fly.advance(&self.keys, dt);
        self.poll_reflector_set();
        self.ensure_session();
        let Some(session) = &mut self.session else { return };

        match self.surface.before_frame() {
            BeforeFrame::SkipMinimised => return,
            BeforeFrame::Configure(size) => {
                session.configure(size);
                self.surface.configured(size);
            }
            BeforeFrame::Render => {}
        }
        let current = session.surface.get_current_texture();
        let outcome = AcquireOutcome::of(&current);
        match self.surface.after_acquire(outcome) {
            AfterAcquire::Render => self.surface_note = None,
            AfterAcquire::RenderThenReconfigure => self.surface_note = Some("suboptimal, reconfigured"),
            AfterAcquire::Skip => {
                self.surface_note = Some("timeout or occluded, frame skipped");
                return;
            }
            AfterAcquire::SkipAndReconfigure => {
                self.surface_note = Some("outdated, reconfigured");
                return;
            }
            AfterAcquire::RecreateSurface => {
                self.surface_note = Some("lost, surface recreated");
                // Rebuilding the session recreates the surface (and keeps the device's
                // resources simple: one path for every kind of loss).
                self.session = None;
                return;
            }
        }
        let (wgpu::CurrentSurfaceTexture::Success(frame) | wgpu::CurrentSurfaceTexture::Suboptimal(frame)) =
            current
        else {
            return;
        };
        let size = [session.config.width, session.config.height];
        let lines = status_lines(&StatusInputs {
            adapter: &session.ctx.describe(),
            size,
            frame_ms: self.clock.mean_ms(),
            plan: self.plan.as_deref(),
            timings: self.timings.as_ref(),
            timestamps: session.renderer.ppr.has_timestamps(),
            set_file: &self.set_file,
            set_status: self.sets.status(),
            settings: self.settings,
            view: self.view,
            speed: self.fly.speed,
            device_recoveries: self.recoveries,
            surface_note: self.surface_note,
            keys: true,
        });
        let (device, queue) = (&session.ctx.device, &session.ctx.queue);
        let text = rasterise(&lines, scale_for_width(size[0]), size[0].saturating_sub(16));
        session.screen.overlay.set_text(device, queue, text.clone());

        let view = frame.texture.create_view(&wgpu::TextureViewDescriptor::default());
        let last_frame = self.args.frames.is_some_and(|n| self.frames + 1 >= n);
        let capture = (last_frame && self.args.screenshot.is_some()).then(|| {
            let mut passes = ScreenPasses::new(device, queue, OFFSCREEN_FORMAT);
            passes.overlay.set_text(device, queue, text);
            (passes, OffscreenTarget::new(device, size))
        });
        let mut outputs = vec![(&session.screen, &view)];
        if let Some((passes, target)) = &capture {
            outputs.push((passes, &target.view));
        }
        let camera = self.fly.camera();
        self.plan = Some(if self.args.stereo {
            let [left, _] = session.renderer.render_stereo(&camera, size, self.view, &outputs);
            left
        } else {
            session.renderer.render(&camera, size, self.view, &outputs)
        });
        if self.timings_read.elapsed() >= TIMINGS_EVERY {
            self.timings = session.renderer.ppr.read_timings();
            self.timings_read = Instant::now();
        }
        session.ctx.queue.present(frame);
        self.frames += 1;

        if let (Some((_, target)), Some(path)) = (&capture, &self.args.screenshot) {
            let saved = target.read(&session.ctx.device, &session.ctx.queue).and_then(|image| {
                image.save(path).with_context(|| format!("{}: cannot write", path.display()))
            });
            match saved {
                Ok(()) => println!("ppr-walkthrough: wrote {}", path.display()),
                Err(e) => self.fatal = Some(e),
            }
        }
        if last_frame {
            event_loop.exit();
        }
    }
}

impl ApplicationHandler for WalkthroughApp {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_none() {
            let [w, h] = self.args.size;
            let attributes = Window::default_attributes()
                .with_title(format!("PPR walkthrough: {}", self.args.level.display()))
                .with_inner_size(PhysicalSize::new(w, h));
            match event_loop.create_window(attributes) {
                Ok(window) => {
                    let size = window.inner_size();
                    self.surface = SurfaceState::new([size.width, size.height]);
                    self.window = Some(Arc::new(window));
                }
                Err(e) => {
                    self.fatal = Some(anyhow::Error::new(e).context("cannot create the window"));
                    event_loop.exit();
                    return;
                }
            }
        }
        // Let the first frame start with the set already read (or the reason it is not).
        if let Some(event) = self.watcher.wait(Duration::from_secs(2)) {
            self.sets.apply(event);
            if let Some(warning) = self.sets.take_warning() {
                eprintln!("ppr-walkthrough: warning: {warning}");
            }
        }
        self.ensure_session();
        if self.fatal.is_some() {
            event_loop.exit();
        }
    }

    fn suspended(&mut self, _event_loop: &ActiveEventLoop) {
        // Mobile platforms take the surface away; recreate everything on resume.
        self.session = None;
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                self.surface.resized([size.width, size.height]);
                if let Some(window) = &self.window {
                    window.request_redraw();
                }
            }
            WindowEvent::KeyboardInput { event, .. } => {
                let PhysicalKey::Code(key) = event.physical_key else { return };
                let pressed = event.state == ElementState::Pressed;
                if update_move_keys(&mut self.keys, key, pressed) || !pressed || event.repeat {
                    return;
                }
                if let Some(action) = action(key) {
                    self.act(action, event_loop);
                }
            }
            WindowEvent::MouseInput { button: MouseButton::Right, state, .. } => {
                self.looking = state == ElementState::Pressed;
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let notches = match delta {
                    MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                self.fly.scroll(notches);
            }
            WindowEvent::Occluded(occluded) => self.occluded = occluded,
            WindowEvent::Focused(false) => {
                self.keys = MoveKeys::default();
                self.looking = false;
            }
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            _ => {}
        }
    }

    fn device_event(&mut self, _event_loop: &ActiveEventLoop, _id: DeviceId, event: DeviceEvent) {
        if let DeviceEvent::MouseMotion { delta: (dx, dy) } = event
            && self.looking
        {
            self.fly.look(dx, dy);
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if self.fatal.is_some() {
            event_loop.exit();
            return;
        }
        let iconified = self.window.as_ref().and_then(|w| w.is_minimized()).unwrap_or(false);
        self.surface.set_hidden(self.occluded || iconified);
        if self.surface.minimised() {
            // Nothing to draw: sleep until the window comes back (the watcher keeps the
            // set current meanwhile).
            event_loop.set_control_flow(ControlFlow::Wait);
            self.clock.resume(Instant::now());
        } else {
            event_loop.set_control_flow(ControlFlow::Poll);
            if let Some(window) = &self.window {
                window.request_redraw();
            }
        }
    }
}
