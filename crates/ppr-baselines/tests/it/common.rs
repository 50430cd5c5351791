//! Shared test setup: one GPU context per test binary, running a technique on a scene next
//! to the exact reference, and the measures the tests assert on.

use std::sync::{Mutex, MutexGuard, OnceLock};
use std::time::Instant;

use image::Rgba32FImage;
use ppr_runtime::Camera;
use ppr_testbed::metrics::compare;
use ppr_testbed::readback::read_rgba_f32;
use ppr_testbed::render_job::hole_share;
use ppr_testbed::technique::REFLECTION_FORMAT;
use ppr_testbed::{
    FrameImages, GpuContext, ImageComparison, LevelRenderer, ReflectionInputs, ReflectionTechnique,
    RenderSettings, SyntheticScene, ToneMap, image_io,
};

/// Test image size: small enough for llvmpipe, large enough for 64-pixel steps to matter.
pub const SIZE: [u32; 2] = [256, 192];

/// The context every GPU test uses, with a lock: llvmpipe on two cores gains nothing from
/// parallel tests.
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
        eprintln!("[ppr-baselines tests] adapter: {} (created in {:.2?})", ctx.describe(), start.elapsed());
        Ok(Gpu { ctx, lock: Mutex::new(()) })
    });
    match gpu {
        Ok(g) => g,
        Err(e) => panic!("GPU tests need an adapter: {e}"),
    }
}

/// One frame of a technique next to the exact reference.
pub struct TechniqueRun {
    pub name: String,
    pub plan: String,
    pub frame: FrameImages,
    pub reflection: Rgba32FImage,
    pub timings: Option<Vec<(String, f64)>>,
}

impl TechniqueRun {
    /// The technique against the reference over reflector pixels whose reflected point is
    /// on screen (what a screen-space method can get).
    pub fn on_screen(&self) -> ImageComparison {
        compare(&self.frame.reference, &self.reflection, &self.frame.on_screen_mask(), ToneMap::Clamp)
            .expect("same sizes")
    }

    /// Share of on-screen reflector pixels without a reflection.
    pub fn on_screen_holes(&self) -> f64 {
        hole_share(&self.reflection, &self.frame.on_screen_mask())
    }

    /// One line for the test log.
    pub fn summary(&self) -> String {
        format!(
            "{} [{}]: on screen {}, holes {:.2}%",
            self.name,
            self.plan,
            self.on_screen(),
            100.0 * self.on_screen_holes()
        )
    }
}

/// Renders `scene` seen by `camera` (G-buffer and reference) and runs `technique` on it
/// in the same encoder, as `ppr-render` does; reads everything back.
pub fn run(
    scene: &SyntheticScene,
    camera: &Camera,
    size: [u32; 2],
    technique: &mut dyn ReflectionTechnique,
) -> TechniqueRun {
    run_with(scene, camera, size, technique, RenderSettings::default())
}

/// [`run`] with the level renderer's `settings` (the glossy reference, for one).
pub fn run_with(
    scene: &SyntheticScene,
    camera: &Camera,
    size: [u32; 2],
    technique: &mut dyn ReflectionTechnique,
    settings: RenderSettings,
) -> TechniqueRun {
    let g = gpu();
    let _guard = g.lock();
    let (device, queue) = (&g.ctx.device, &g.ctx.queue);
    let mut renderer = LevelRenderer::new(device, queue, &scene.level, &scene.reflectors);
    renderer.settings = settings;
    renderer.prepare(device, queue, camera, size);
    let output = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("technique output"),
        size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: REFLECTION_FORMAT,
        usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let output_view = output.create_view(&Default::default());
    let name = technique.name();
    let plan = technique.prepare(device, queue, camera, size);
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("test frame") });
    renderer.encode_gbuffer(&mut encoder);
    technique.encode(&mut encoder, &ReflectionInputs::from_gbuffer(renderer.gbuffer(), &output_view));
    renderer.encode_reference(&mut encoder);
    queue.submit([encoder.finish()]);
    let timings = technique.timings(device);
    let frame = FrameImages::read(device, queue, &renderer).expect("frame readback");
    let reflection = read_rgba_f32(device, queue, &output).expect("reflection readback");
    let run = TechniqueRun { name, plan, frame, reflection, timings };
    save_artifacts(&run);
    run
}

/// With `PPR_BASELINES_ARTIFACTS=dir`, writes the colour, reference and technique output of
/// every run there (named after the test thread and technique) to look at by eye.
fn save_artifacts(run: &TechniqueRun) {
    let Some(dir) = std::env::var_os("PPR_BASELINES_ARTIFACTS") else { return };
    let dir = std::path::PathBuf::from(dir);
    std::fs::create_dir_all(&dir).expect("artifact dir");
    let thread = std::thread::current().name().unwrap_or("test").replace("::", "-");
    let technique: String =
        run.name.chars().map(|c| if c.is_ascii_alphanumeric() { c } else { '_' }).collect();
    let stem = format!("{thread}-{technique}");
    let tm = ToneMap::Clamp;
    image_io::write_png(dir.join(format!("{stem}-color.png")), &run.frame.color, tm).expect("png");
    image_io::write_png(dir.join(format!("{stem}-reference.png")), &run.frame.reference, tm).expect("png");
    image_io::write_png(dir.join(format!("{stem}-technique.png")), &run.reflection, tm).expect("png");
}

/// Times a test body and prints the time with the test's name.
pub fn timed<T>(name: &str, f: impl FnOnce() -> T) -> T {
    let start = Instant::now();
    let out = f();
    eprintln!("[ppr-baselines tests] {name}: {:.2?}", start.elapsed());
    out
}

/// Reads `count` `u32` values from the start of `buffer` (a `COPY_SRC` buffer).
pub fn read_u32s(buffer: &wgpu::Buffer, count: usize) -> Vec<u32> {
    let g = gpu();
    let (device, queue) = (&g.ctx.device, &g.ctx.queue);
    let size = (count * 4) as u64;
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("test readback"),
        size,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
    queue.submit([encoder.finish()]);
    staging.map_async(wgpu::MapMode::Read, .., |r| r.expect("map"));
    device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
    let values = {
        let bytes = staging.get_mapped_range(..).expect("mapped");
        bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect()
    };
    staging.unmap();
    values
}
