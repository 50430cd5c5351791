//! Shared test setup: one GPU context per test binary, rendering helpers.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard, OnceLock};
use std::time::Instant;

use ppr_runtime::Camera;
use ppr_testbed::{FrameImages, GpuContext, LevelRenderer, ReflectedPointClass, SyntheticScene, image_io};

/// The context every GPU test uses, with a lock: llvmpipe on two cores gains nothing from
/// parallel tests, and serial runs make the per-test timings meaningful.
pub struct Gpu {
    pub ctx: GpuContext,
    lock: Mutex<()>,
}

impl Gpu {
    pub fn lock(&self) -> MutexGuard<'_, ()> {
        self.lock.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The shared GPU; panics (test failure, never a skip) when no adapter exists.
pub fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Result<Gpu, String>> = OnceLock::new();
    let gpu = GPU.get_or_init(|| {
        let start = Instant::now();
        let ctx = GpuContext::new_headless().map_err(|e| e.to_string())?;
        eprintln!("[ppr-testbed tests] adapter: {} (created in {:.2?})", ctx.describe(), start.elapsed());
        Ok(Gpu { ctx, lock: Mutex::new(()) })
    });
    match gpu {
        Ok(g) => g,
        Err(e) => panic!("GPU tests need an adapter: {e}"),
    }
}

/// Renders the G-buffer and the reference of `scene` seen by `camera` and reads them back.
pub fn render(scene: &SyntheticScene, camera: &Camera, size: [u32; 2]) -> FrameImages {
    let g = gpu();
    let _guard = g.lock();
    let (device, queue) = (&g.ctx.device, &g.ctx.queue);
    let mut renderer = LevelRenderer::new(device, queue, &scene.level, &scene.reflectors);
    renderer.render(device, queue, camera, size);
    let frame = FrameImages::read(device, queue, &renderer).expect("readback");
    save_artifacts(&frame);
    frame
}

/// With `PPR_TESTBED_ARTIFACTS=dir`, writes the colour and reference of every rendered
/// frame there (named after the test thread and a counter) to look at by eye.
pub fn save_artifacts(frame: &FrameImages) {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let Some(dir) = std::env::var_os("PPR_TESTBED_ARTIFACTS") else { return };
    let dir = std::path::PathBuf::from(dir);
    std::fs::create_dir_all(&dir).expect("artifact dir");
    let name = std::thread::current().name().unwrap_or("test").replace("::", "-");
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let tm = ppr_testbed::ToneMap::Clamp;
    image_io::write_png(dir.join(format!("{name}-{n}-color.png")), &frame.color, tm).expect("png");
    image_io::write_png(dir.join(format!("{name}-{n}-reference.png")), &frame.reference, tm).expect("png");
    let classes = image::RgbImage::from_fn(frame.size()[0], frame.size()[1], |x, y| {
        image::Rgb(match frame.class(x, y) {
            ReflectedPointClass::NotReflector => [0, 0, 0],
            ReflectedPointClass::OnScreen => [0, 200, 0],
            ReflectedPointClass::OffScreen => [200, 0, 0],
            ReflectedPointClass::Background => [0, 0, 200],
        })
    });
    image_io::write_rgb8(dir.join(format!("{name}-{n}-class.png")), &classes).expect("png");
}

/// Times a test body and prints the time with the test's name.
pub fn timed<T>(name: &str, f: impl FnOnce() -> T) -> T {
    let start = Instant::now();
    let out = f();
    eprintln!("[ppr-testbed tests] {name}: {:.2?}", start.elapsed());
    out
}
