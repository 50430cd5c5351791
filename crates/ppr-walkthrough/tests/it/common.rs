//! Shared test setup: assets, the demo level's reflector set (extracted once), a lock that
//! runs GPU tests one at a time, and image comparison over masks.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, OnceLock};

use image::Rgba32FImage;
use ppr_walkthrough::Args;

pub fn asset(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets").join(name)
}

/// GPU tests take this lock (llvmpipe on two cores gains nothing from running them at
/// once), and so do the timed hot-reload tests, so that no frame competes with their clock.
pub fn gpu_lock() -> MutexGuard<'static, ()> {
    static LOCK: Mutex<()> = Mutex::new(());
    LOCK.lock().unwrap_or_else(|e| e.into_inner())
}

/// The demo level's reflector set as `ppr-extract` writes it (default parameters), saved
/// once per test run in a temporary folder.
pub fn demo_set_file() -> &'static Path {
    static FILE: OnceLock<(tempfile::TempDir, PathBuf)> = OnceLock::new();
    let (_, path) = FILE.get_or_init(|| {
        let level = ppr_extract::load_level(asset("demo_room.glb")).expect("demo level loads for extraction");
        let extraction = ppr_extract::extract(&level, &ppr_extract::ExtractParams::default(), &|_, _| {});
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("demo_room.ppr.json");
        extraction.set.save(&path).expect("set saved");
        (dir, path)
    });
    path
}

/// The walkthrough's headless command line for the demo level.
pub fn headless_args(extra: &[&str]) -> Args {
    let level = asset("demo_room.glb");
    let mut argv = vec![
        "ppr-walkthrough".to_owned(),
        level.display().to_string(),
        "--set".to_owned(),
        demo_set_file().display().to_string(),
        "--headless".to_owned(),
    ];
    argv.extend(extra.iter().map(|s| (*s).to_owned()));
    <Args as clap::Parser>::try_parse_from(argv).expect("arguments parse")
}

/// Mean absolute error (RGB, values clamped to [0, 1]) and PSNR in dB over `mask`.
pub struct Difference {
    pub pixels: usize,
    pub mean_abs_error: f64,
    pub psnr_db: f64,
}

pub fn difference(a: &Rgba32FImage, b: &Rgba32FImage, mask: impl Fn(u32, u32) -> bool) -> Difference {
    assert_eq!(a.dimensions(), b.dimensions());
    let (mut pixels, mut abs, mut sq) = (0usize, 0f64, 0f64);
    for (x, y, pa) in a.enumerate_pixels() {
        if !mask(x, y) {
            continue;
        }
        let pb = b.get_pixel(x, y);
        pixels += 1;
        for c in 0..3 {
            let d = f64::from(pa.0[c].clamp(0.0, 1.0)) - f64::from(pb.0[c].clamp(0.0, 1.0));
            abs += d.abs();
            sq += d * d;
        }
    }
    let n = (3 * pixels.max(1)) as f64;
    let mse = sq / n;
    let psnr_db = if mse == 0.0 { f64::INFINITY } else { 10.0 * (1.0 / mse).log10() };
    Difference { pixels, mean_abs_error: abs / n, psnr_db }
}
