//! End to end: `ppr-runtime`'s reflections measured against the exact reference.

use ppr_runtime::ReflectionSettings;
use ppr_testbed::camera_spec::ProjectionChoice;
use ppr_testbed::render_job::{OutputFiles, RenderJob, run_level};
use ppr_testbed::{
    CompositeParams, FloorMirrorParams, PprTechnique, RenderSettings, SyntheticScene, ToneMap,
};

use crate::common::{gpu, timed};

/// PPR on the floor mirror scene through the whole `ppr-render` job: the runtime runs, every
/// output file is written, and where the reflected point is on screen PPR is close to the
/// exact reference. Loose bars (measured 25.7 dB, FLIP 0.058, no holes on llvmpipe and the
/// same scene on an H100): the runtime's own tests hold the tight ones.
#[test]
fn ppr_render_job_runs_the_runtime_and_writes_every_file() {
    timed("ppr_render_job_runs_the_runtime_and_writes_every_file", || {
        let scene = SyntheticScene::floor_mirror(&FloorMirrorParams::default());
        let dir = tempfile::tempdir().expect("tempdir");
        let job = RenderJob {
            level: "synthetic".into(),
            reflectors: "synthetic".into(),
            camera: None,
            size: [192, 144],
            projection: ProjectionChoice::default(),
            // PPR_TESTBED_ARTIFACTS=dir keeps the images to look at.
            output: std::env::var_os("PPR_TESTBED_ARTIFACTS")
                .map_or_else(|| dir.path().to_owned(), std::path::PathBuf::from)
                .join("ppr_floor_mirror.png"),
            composite: CompositeParams::default(),
            tone_map: ToneMap::Clamp,
            render: RenderSettings::default(),
            accept_level_mismatch: false,
        };
        let g = gpu();
        let _guard = g.lock();
        let mut ppr =
            PprTechnique::new(&g.ctx.device, &g.ctx.queue, &scene.reflectors, ReflectionSettings::ALL)
                .expect("a valid set");
        let report = run_level(&job, &scene.level, &scene.reflectors, &scene.camera, &g.ctx, Some(&mut ppr))
            .expect("render job");
        eprintln!("{report}");
        let files = OutputFiles::for_output(&job.output);
        for f in [&files.frame, &files.reflection_png, &files.reflection_exr, &files.reference, &files.diff] {
            assert!(f.is_file(), "{} not written", f.display());
        }
        let on = report.on_screen.expect("PPR ran");
        let off = report.off_screen.expect("PPR ran");
        assert!(on.pixels > 1000 && off.pixels > 1000, "{on} / {off}");
        assert_eq!(on.pixels, report.reflector_pixels.1);
        for c in [on, off] {
            assert!(c.psnr_db.is_finite() && c.psnr_db > 0.0, "{c}");
            assert!((0.0..=1.0).contains(&c.flip_mean) && c.mean_abs_error.is_finite(), "{c}");
        }
        assert!(on.psnr_db >= 20.0, "on-screen PSNR too low: {on}");
        assert!(on.flip_mean <= 0.15, "on-screen FLIP too high: {on}");
        let holes = report.on_screen_holes.expect("PPR ran");
        assert!(holes < 0.05, "{:.1}% of the on-screen pixels have no reflection", holes * 100.0);
    });
}

/// A set whose `source.hash` is not the level file's is refused with both names, unless
/// the job accepts the mismatch (then it is a warning of the report).
#[test]
fn a_set_from_other_level_bytes_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let level = dir.path().join("demo_room.glb");
    let assets = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets");
    let mut bytes = std::fs::read(assets.join("demo_room.glb")).expect("demo level");
    let set_path = dir.path().join("demo_room.ppr.json");
    let mut set = ppr_format::ReflectorSet::new("demo_room.glb");
    set.reflectors.push(ppr_format::Reflector::new(
        0,
        "floor",
        ppr_format::ReflectorKind::Opaque,
        glam::DVec3::ZERO,
        glam::DVec3::Y,
        glam::DVec3::X,
        glam::DVec2::new(2.0, 2.0),
    ));
    // A hash other than the level file's: the set predates a change of the level.
    set.source.hash = format!("blake3:{}", "0".repeat(64));
    set.save(&set_path).expect("save");
    bytes.push(0); // the level changed since
    std::fs::write(&level, &bytes).expect("write level");
    let mut job = RenderJob {
        level: level.clone(),
        reflectors: set_path.clone(),
        camera: None,
        size: [64, 48],
        projection: ProjectionChoice::default(),
        output: dir.path().join("frame.png"),
        composite: CompositeParams::default(),
        tone_map: ToneMap::Clamp,
        render: RenderSettings::default(),
        accept_level_mismatch: false,
    };
    let g = gpu();
    let _guard = g.lock();
    let err = ppr_testbed::render_job::run(&job, &g.ctx, None).expect_err("refused").to_string();
    for needle in ["demo_room.ppr.json", "demo_room.glb", "--accept-level-mismatch"] {
        assert!(err.contains(needle), "{needle} missing from: {err}");
    }
    assert!(!job.output.exists(), "nothing rendered");
    job.accept_level_mismatch = true;
    let report = ppr_testbed::render_job::run(&job, &g.ctx, None).expect("accepted");
    assert_eq!(report.warnings.len(), 1, "{:?}", report.warnings);
    assert!(report.to_string().contains("warning: "));
}
