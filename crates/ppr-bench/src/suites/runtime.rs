//! Runtime numbers (issue 4): each PPR pass timed on real scenes, against the bandwidth
//! floor (the bytes the pass must move over the copy bandwidth measured in the same run).

use ppr_runtime::passes::{Ablation, BoxReduction};
use ppr_runtime::{
    CLEAR_VALUE, Choice, DebugOptions, LayerPlacement, PlanParams, ReflectionAblation, ReflectionSettings,
};
use ppr_testbed::gbuffer_targets::Target;
use ppr_testbed::technique::REFLECTION_FORMAT;
use ppr_testbed::{GpuContext, LevelRenderer, ReflectionInputs};

use crate::bandwidth::{CopyBandwidth, FrameFacts, PassBytes, measure_copy_bandwidth, pass_bytes};
use crate::buffer_readback::read_buffer_u32;
use crate::config::{BenchConfig, Resolution};
use crate::error::BenchError;
use crate::frame_loop::{FrameLoop, faster_of_two_rounds};
use crate::ppr_runner::PprRunner;
use crate::scene::{BenchScene, SceneOptions, SceneSpec};
use crate::stereo_probe::{StereoRow, run_stereo_probe};
use crate::technique::BenchFrame;
use crate::timing::{TimingSeries, TimingSource};
use crate::upload_probe::{UploadProbeRow, run_upload_probe};
use crate::write_probe::{WriteProbeRow, run_write_probe};

/// What the runtime suite runs.
#[derive(Clone, Debug, PartialEq)]
pub struct RuntimeConfig {
    pub scenes: Vec<String>,
    pub resolutions: Vec<Resolution>,
    pub max_cameras: usize,
    /// Size of each of the copy kernel's two buffers.
    pub copy_bytes: u64,
    /// Also run every scene with glass/water layers and normal maps off.
    pub features_off: bool,
    /// Also run every scene with each projection tuning and ablation.
    pub projection_profile: bool,
    /// With `projection_profile`: only these rows (every row when empty).
    pub profile_rows: Vec<String>,
    /// With `projection_profile`: leave out these rows.
    pub skip_profile_rows: Vec<String>,
    /// Also time full-screen image writes (`write_probe.rs`) at each resolution.
    pub write_probe: bool,
    /// Also time the upload's copies before a first pass (`upload_probe.rs`).
    pub upload_probe: bool,
    /// Also run every scene with every reflector at roughness [`GLOSSY_PROBE_ROUGHNESS`],
    /// glossy on and off: what the glossy blur costs.
    pub glossy: bool,
    /// Also time a stereo frame against two mono frames (`stereo_probe.rs`) on each scene's
    /// first camera at these per-eye sizes.
    pub stereo_sizes: Vec<[u32; 2]>,
}

/// The most taps per pixel of the extra `--glossy` rows (the default is 12; 0: the reflector
/// lookup only, 1: the footprint without taps; both leave the image sharp).
pub const GLOSSY_PROBE_TAPS: [u32; 4] = [0, 1, 4, 8];

/// The roughness every reflector gets in the `--glossy` rows.
pub const GLOSSY_PROBE_ROUGHNESS: f64 = 0.2;

/// The projection variants of `--projection-profile`: (name, source boxes, ablation); the
/// `reflection: …` rows ablate the reflection pass instead, the `reflection: mirrors …`
/// rows without the glossy blur (one pixel per invocation, or two by two with `quads`); the
/// `layers: …` rows change the layer pass (the water edge stretch off, walking all its
/// steps as before the eighteenth session, or writing every tile of the layers' common
/// rectangle as before the thirty-first; `every tile` rows that last).
fn projection_profile() -> Vec<(&'static str, Choice, Ablation)> {
    vec![
        ("empty", Choice::Off, Ablation::Empty),
        ("position only", Choice::Off, Ablation::PositionOnly),
        ("tests only", Choice::Off, Ablation::TestsOnly),
        ("no encode", Choice::Off, Ablation::NoEncode),
        ("no write", Choice::Off, Ablation::NoWrite),
        // The same, each pass timed on its own: what the projection and the reflection
        // cost doing nothing (the launch, and on GPUs the block lists the projection
        // builds), and how each grows as the projection does more.
        ("empty, reflection own pass", Choice::Off, Ablation::Empty),
        ("tests only, reflection own pass", Choice::Off, Ablation::TestsOnly),
        ("no write, reflection own pass", Choice::Off, Ablation::NoWrite),
        ("no atomic", Choice::Off, Ablation::NoAtomic),
        ("no atomic, reflection own pass", Choice::Off, Ablation::NoAtomic),
        ("source boxes", Choice::On, Ablation::None),
        ("no source boxes", Choice::Off, Ablation::None),
        ("culling on", Choice::Auto, Ablation::None),
        ("culling on, tests only", Choice::Auto, Ablation::TestsOnly),
        ("culling on, empty", Choice::Auto, Ablation::Empty),
        ("culling on, empty, lists box only", Choice::Auto, Ablation::Empty),
        ("culling on, separate lists", Choice::Auto, Ablation::None),
        ("culling on, empty, separate lists", Choice::Auto, Ablation::Empty),
        ("separate lists", Choice::Auto, Ablation::None),
        ("culling on, no inside entries", Choice::Auto, Ablation::None),
        ("no inside entries", Choice::Auto, Ablation::None),
        ("culling on, subgroup box", Choice::Auto, Ablation::None),
        ("subgroup box", Choice::Auto, Ablation::None),
        ("culling on, empty, subgroup box", Choice::Auto, Ablation::Empty),
        ("culling on, subgroup box atomics", Choice::Auto, Ablation::None),
        ("culling on, empty, subgroup box atomics", Choice::Auto, Ablation::Empty),
        ("culling on, prefetch", Choice::Auto, Ablation::None),
        ("culling on, empty, prefetch", Choice::Auto, Ablation::Empty),
        ("indirect off", Choice::Auto, Ablation::None),
        ("indirect on", Choice::Auto, Ablation::None),
        ("culling off", Choice::Auto, Ablation::None),
        ("culling off, tests only", Choice::Auto, Ablation::TestsOnly),
        ("occlusion off", Choice::Auto, Ablation::None),
        ("path blockers off", Choice::Auto, Ablation::None),
        ("no offset index", Choice::Auto, Ablation::None),
        ("tests only, offset index", Choice::Auto, Ablation::TestsOnly),
        ("tests only, no offset index", Choice::Auto, Ablation::TestsOnly),
        ("occluder lists", Choice::Auto, Ablation::None),
        ("storage tests", Choice::Auto, Ablation::None),
        ("no subgroup culling", Choice::Auto, Ablation::None),
        ("spread quads", Choice::Auto, Ablation::None),
        ("subgroup culling on", Choice::Auto, Ablation::None),
        ("subgroup culling only", Choice::Auto, Ablation::None),
        ("subgroup culling only, no inside entries", Choice::Auto, Ablation::None),
        ("subgroup culling only, tests only", Choice::Auto, Ablation::TestsOnly),
        ("occupancy pad 16 KiB", Choice::Auto, Ablation::None),
        ("occupancy pad 32 KiB", Choice::Auto, Ablation::None),
        ("occupancy pad 38 KiB", Choice::Auto, Ablation::None),
        ("clear pass every frame", Choice::Auto, Ablation::None),
        ("occlusion first", Choice::Auto, Ablation::None),
        ("occlusion last", Choice::Auto, Ablation::None),
        ("layers: no water stretch", Choice::Auto, Ablation::None),
        ("layers: full stretch walk", Choice::Auto, Ablation::None),
        ("layers: every tile", Choice::Auto, Ablation::None),
        ("layers: own pass, every tile", Choice::Auto, Ablation::None),
        ("layers: own pass", Choice::Auto, Ablation::None),
        ("layers: after reflection", Choice::Auto, Ablation::None),
        ("classify own pass", Choice::Auto, Ablation::None),
        ("frame span", Choice::Auto, Ablation::None),
        ("frame span, empty", Choice::Off, Ablation::Empty),
        ("frame span, layers own pass", Choice::Auto, Ablation::None),
        ("frame span, layers every tile", Choice::Auto, Ablation::None),
        ("frame span, layers after reflection", Choice::Auto, Ablation::None),
        ("frame span, classify own pass", Choice::Auto, Ablation::None),
        ("frame span, classify own pass, layers own pass", Choice::Auto, Ablation::None),
        ("frame span, reflection own pass", Choice::Auto, Ablation::None),
        ("frame span, separate upload copies", Choice::Auto, Ablation::None),
        ("frame span, copied upload", Choice::Auto, Ablation::None),
        ("frame span, path blockers off", Choice::Auto, Ablation::None),
        ("frame span, glossy, 8 taps", Choice::Auto, Ablation::None),
        ("frame span, layered reflection own pass", Choice::Auto, Ablation::None),
        ("layered reflection own pass", Choice::Auto, Ablation::None),
        ("reflection own pass", Choice::Auto, Ablation::None),
        ("reflection: empty", Choice::Auto, Ablation::None),
        ("reflection: empty, reflection own pass", Choice::Auto, Ablation::None),
        ("reflection: no glossy, reflection own pass", Choice::Auto, Ablation::None),
        ("reflection: mirrors, reflection own pass", Choice::Auto, Ablation::None),
        ("reflection: no colour", Choice::Auto, Ablation::None),
        ("reflection: no glossy", Choice::Auto, Ablation::None),
        ("reflection: mirrors", Choice::Auto, Ablation::None),
        ("reflection: mirrors, empty", Choice::Auto, Ablation::None),
        ("reflection: mirrors, quads", Choice::Auto, Ablation::None),
        ("reflection: mirrors, quads, empty", Choice::Auto, Ablation::None),
        ("reflection: mirrors, clear pass every frame", Choice::Auto, Ablation::None),
        ("reflection: mirrors, indirect off", Choice::Auto, Ablation::None),
        ("reflection: mirrors, indirect on", Choice::Auto, Ablation::None),
        ("reflection: indirect dispatch", Choice::Auto, Ablation::None),
        ("reflection: mirrors, indirect dispatch", Choice::Auto, Ablation::None),
        ("reflection: tile loop 1024", Choice::Auto, Ablation::None),
        ("reflection: mirrors, tile loop 1024", Choice::Auto, Ablation::None),
        ("reflection: tile loop 2048", Choice::Auto, Ablation::None),
        ("reflection: mirrors, tile loop 2048", Choice::Auto, Ablation::None),
        ("reflection: tile loop 8192", Choice::Auto, Ablation::None),
        ("reflection: mirrors, tile loop 8192", Choice::Auto, Ablation::None),
    ]
}

/// The rows of [`projection_profile`] that `wanted` names (all when it is empty), less
/// those `skipped` names.
///
/// # Errors
/// A name that is no row's, with the flag that gave it and the list of rows.
fn profile_rows(
    wanted: &[String],
    skipped: &[String],
) -> Result<Vec<(&'static str, Choice, Ablation)>, BenchError> {
    let all = projection_profile();
    let named =
        wanted.iter().map(|w| ("--profile-row", w)).chain(skipped.iter().map(|s| ("--skip-profile-row", s)));
    for (flag, name) in named {
        if !all.iter().any(|(n, ..)| n == name) {
            let names: Vec<_> = all.iter().map(|(n, ..)| format!("\"{n}\"")).collect();
            return Err(BenchError::Spec(format!(
                "{flag} \"{name}\" is no row of the projection profile; the rows: {}",
                names.join(", ")
            )));
        }
    }
    Ok(all
        .into_iter()
        .filter(|(n, ..)| wanted.is_empty() || wanted.iter().any(|w| w == n))
        .filter(|(n, ..)| !skipped.iter().any(|s| s == n))
        .collect())
}

/// One scene, camera and size.
#[derive(Clone, Debug)]
pub struct RuntimeRow {
    pub scene: String,
    pub camera: String,
    pub resolution: Resolution,
    /// The plan's passes and choices, as `FramePlan` prints them.
    pub plan: String,
    pub visible: usize,
    pub facts: FrameFacts,
    pub timings: TimingSeries,
    pub source: TimingSource,
    pub bytes: Vec<PassBytes>,
    /// Median CPU milliseconds of the renderer's `prepare` and `encode` a frame (planning,
    /// packing the upload, recording the passes).
    pub cpu_ms: f64,
}

/// Everything the runtime suite found.
pub struct RuntimeOutcome {
    pub adapter: String,
    pub bandwidth: Option<CopyBandwidth>,
    pub rows: Vec<RuntimeRow>,
    pub notes: Vec<String>,
    /// Full-screen write probes, per resolution (with `write_probe`).
    pub write_probe: Vec<(Resolution, Vec<WriteProbeRow>)>,
    /// Small copies before a dispatch (with `upload_probe`).
    pub upload_probe: Vec<UploadProbeRow>,
    /// Stereo against two mono frames (with `stereo_sizes`).
    pub stereo: Vec<StereoRow>,
}

/// Runs the suite.
///
/// # Errors
/// A readback fails.
pub fn run_runtime(
    gpu: &GpuContext,
    cfg: &BenchConfig,
    rc: &RuntimeConfig,
) -> Result<RuntimeOutcome, BenchError> {
    let (device, queue) = (&gpu.device, &gpu.queue);
    // The profile's rows, once; an unknown `--profile-row` fails before any GPU work.
    let profile = profile_rows(&rc.profile_rows, &rc.skip_profile_rows)?;
    let reps = cfg.frames.timed.max(3);
    let bandwidth = measure_copy_bandwidth(device, queue, rc.copy_bytes, reps);
    if let Some(b) = bandwidth {
        eprintln!(
            "copy bandwidth: {:.1} GB/s ({} MiB moved in {:.4} ms)",
            b.bytes_per_second() / 1e9,
            b.bytes >> 20,
            b.median_ms
        );
    }
    let mut write_probe = Vec::new();
    if rc.write_probe {
        for &res in &rc.resolutions {
            write_probe.push((res, run_write_probe(device, queue, res.size(), reps)));
        }
    }
    let upload_probe = if rc.upload_probe { run_upload_probe(device, queue, reps) } else { Vec::new() };
    let frames = FrameLoop::new(device, cfg);
    let mut rows = Vec::new();
    let mut notes = Vec::new();
    let mut stereo = Vec::new();
    let options = SceneOptions { max_cameras: rc.max_cameras, ..SceneOptions::default() };
    for text in &rc.scenes {
        let spec = SceneSpec::parse(text, &cfg.repo_root, &cfg.scenes_dir)?;
        let scene = match BenchScene::load_ranked(&spec, &options, gpu) {
            Ok(s) => s,
            Err(e) => {
                notes.push(format!("{}: skipped, cannot load: {e}", spec.name));
                continue;
            }
        };
        notes.extend(scene.notes.iter().map(|n| format!("{}: {n}", scene.name)));
        let mut level = LevelRenderer::new(device, queue, &scene.level, &scene.reflectors);
        if let Some(cam) = scene.cameras.first() {
            for &size in &rc.stereo_sizes {
                eprintln!("runtime: stereo {} {} {}x{} per eye", scene.name, cam.name, size[0], size[1]);
                let s = (scene.name.as_str(), &scene.level, &scene.reflectors);
                match run_stereo_probe(device, queue, s, (&cam.name, &cam.camera), size, reps, &frames.flush)
                {
                    Some(row) => stereo.push(row),
                    None => notes.push("stereo: no encoder timestamps on this adapter".to_owned()),
                }
            }
        }
        let tuning = DebugOptions::default();
        let all = ReflectionSettings::ALL;
        let mut variants =
            vec![(String::new(), PlanParams::default(), scene.reflectors.clone(), tuning, all)];
        if rc.glossy {
            let mut rough = scene.reflectors.clone();
            for r in &mut rough.reflectors {
                r.roughness = GLOSSY_PROBE_ROUGHNESS;
            }
            let sharp = ReflectionSettings { glossy: false, ..all };
            let name = format!(" (roughness {GLOSSY_PROBE_ROUGHNESS}");
            variants.push((format!("{name}, glossy)"), PlanParams::default(), rough.clone(), tuning, all));
            for taps in GLOSSY_PROBE_TAPS {
                let fewer = DebugOptions { glossy_taps: Some(taps), ..tuning };
                let label = format!("{name}, glossy, {taps} taps)");
                variants.push((label, PlanParams::default(), rough.clone(), fewer, all));
            }
            variants.push((format!("{name}, glossy off)"), PlanParams::default(), rough, tuning, sharp));
        }
        if rc.features_off {
            let off = PlanParams { layers: Choice::Off, normal_maps: Choice::Off, ..PlanParams::default() };
            variants.push((" (features off)".to_owned(), off, scene.reflectors.clone(), tuning, all));
            let mut normal_mapped = scene.reflectors.clone();
            for r in &mut normal_mapped.reflectors {
                r.normal_map = true;
            }
            variants.push((" (normal maps)".to_owned(), PlanParams::default(), normal_mapped, tuning, all));
        }
        if rc.projection_profile {
            for &(name, source_boxes, ablation) in &profile {
                let mut params = PlanParams { source_boxes, ..PlanParams::default() };
                if name.starts_with("culling on") {
                    params.tile_culling = Choice::On;
                } else if name.starts_with("culling off") {
                    params.tile_culling = Choice::Off;
                } else if name.ends_with("path blockers off") {
                    params.path_blockers = Choice::Off;
                } else if name.ends_with("no offset index") {
                    params.tree_index = Choice::Off;
                } else if name == "occlusion off" {
                    params.depth_occlusion = Choice::Off;
                } else if name == "occlusion first" {
                    params.occlusion_first = Choice::On;
                } else if name == "occlusion last" {
                    params.occlusion_first = Choice::Off;
                } else if name == "storage tests" {
                    params.uniform_tests = Choice::Off;
                } else if name.ends_with("indirect off") {
                    params.indirect = Choice::Off;
                } else if name.ends_with("indirect on") {
                    params.indirect = Choice::On;
                }
                // The box-only list pass is the separate pass's.
                if name.contains("separate lists") || name.ends_with("lists box only") {
                    params.fused_lists = Choice::Off;
                }
                if name.contains("no subgroup culling") {
                    params.subgroup_cull = Choice::Off;
                } else if name.starts_with("subgroup culling on") {
                    params.subgroup_cull = Choice::On;
                } else if name.starts_with("subgroup culling only") {
                    params.subgroup_cull = Choice::On;
                    params.tile_culling = Choice::Off;
                }

                let spread_quads = name.starts_with("spread quads");
                if name == "occluder lists" {
                    params.depth_occlusion = Choice::Off;
                    params.occluder_lists = Choice::On;
                }
                let reflection_ablation = match name
                    .strip_prefix("reflection: ")
                    .map(|r| r.trim_end_matches(", reflection own pass"))
                {
                    Some(r) if r.ends_with("empty") => ReflectionAblation::Empty,
                    Some(r) if r.ends_with("no colour") => ReflectionAblation::NoColour,
                    Some(r) if r.ends_with("no glossy") => ReflectionAblation::NoGlossy,
                    _ => ReflectionAblation::None,
                };
                let reflection_quads = name.starts_with("reflection: mirrors, quads");
                // The `mirrors` rows leave the glossy blur off, as a set without roughness:
                // the frames whose reflection pass may run two by two pixels per invocation.
                let settings = if name.starts_with("reflection: mirrors") {
                    ReflectionSettings { glossy: false, ..all }
                } else if name == "layers: no water stretch" {
                    ReflectionSettings { water_edge_stretch: false, ..all }
                } else {
                    all
                };
                let debug = DebugOptions {
                    projection_ablation: ablation,
                    spread_quads,
                    clear_pass_every_frame: name.ends_with("clear pass every frame"),
                    reflection_tile_loop: name.rsplit_once("tile loop ").and_then(|(_, n)| n.parse().ok()),
                    reflection_indirect_dispatch: name.ends_with("indirect dispatch"),
                    block_lists_box_only: name.ends_with("lists box only"),
                    no_inside_entries: name.ends_with("no inside entries"),
                    full_stretch_walk: name == "layers: full stretch walk",
                    layer_every_tile: name.ends_with("every tile"),
                    layer_placement: if name.ends_with("layers own pass")
                        || name.starts_with("layers: own pass")
                    {
                        LayerPlacement::OwnPass
                    } else if name.ends_with("after reflection") {
                        LayerPlacement::AfterReflection
                    } else {
                        tuning.layer_placement
                    },
                    frame_span: name.starts_with("frame span"),
                    classify_own_pass: name.contains("classify own pass"),
                    reflection_own_pass: name.ends_with(", reflection own pass")
                        || name == "reflection own pass",
                    // The most glossy taps 8, not 12 (the thirty-fifth session's row).
                    glossy_taps: if name.ends_with(", 8 taps") { Some(8) } else { tuning.glossy_taps },
                    layered_reflection_own_pass: name.ends_with("layered reflection own pass"),
                    separate_upload_copies: name.ends_with("separate upload copies"),
                    copied_upload: name.ends_with("copied upload")
                        || name.ends_with("separate upload copies"),
                    box_reduction: if name.ends_with("subgroup box") {
                        BoxReduction::SubgroupSlots
                    } else if name.ends_with("subgroup box atomics") {
                        BoxReduction::SubgroupAtomics
                    } else {
                        BoxReduction::Atomics
                    },
                    list_prefetch: name.ends_with("prefetch"),
                    occupancy_pad_kib: name
                        .strip_prefix("occupancy pad ")
                        .and_then(|k| k.strip_suffix(" KiB")?.parse().ok())
                        .unwrap_or(0),
                    reflection_ablation,
                    reflection_quads,
                    ..tuning
                };
                variants.push((format!(" [{name}]"), params, scene.reflectors.clone(), debug, settings));
            }
        }
        let mut runners = Vec::new();
        for (suffix, params, reflectors, tuning, settings) in &variants {
            let mut ppr = PprRunner::new(device, queue, reflectors, "ppr", *settings, *params)?;
            ppr.renderer().debug = *tuning;
            runners.push((suffix.clone(), ppr));
        }
        // Every (variant, camera, size) in two rounds (`faster_of_two_rounds`).
        let mut jobs = Vec::new();
        for v in 0..runners.len() {
            for c in 0..scene.cameras.len() {
                for &res in &rc.resolutions {
                    jobs.push((v, c, res));
                }
            }
        }
        // What the passes touched (and the visible count), read after each job's first run:
        // it does not depend on the timing.
        let mut facts: Vec<Option<(FrameFacts, usize)>> = jobs.iter().map(|_| None).collect();
        let runs = faster_of_two_rounds(jobs.len(), |j| {
            let (v, c, res) = jobs[j];
            let cam = &scene.cameras[c];
            let (suffix, ppr) = &mut runners[v];
            let size = res.size();
            level.prepare(device, queue, &cam.camera, size);
            let mut encoder = device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("runtime gbuffer") });
            level.encode_gbuffer(&mut encoder);
            queue.submit([encoder.finish()]);
            let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
            let output = Target::new(device, "runtime output", size, REFLECTION_FORMAT, usage);
            let frame = BenchFrame {
                level: &level,
                reflection: ReflectionInputs::from_gbuffer(level.gbuffer(), &output.view),
            };
            eprintln!("runtime: {}{suffix} {} {res}", scene.name, cam.name);
            let run = frames.run(device, queue, ppr, &frame, &cam.camera, size);
            if facts[j].is_none() {
                let visible = ppr.renderer().plan().map_or(0, |p| p.visible.len());
                facts[j] = Some((frame_facts(device, queue, ppr, size)?, visible));
            }
            Ok::<_, BenchError>(run)
        })?;
        for ((&(v, c, res), run), job_facts) in jobs.iter().zip(runs).zip(facts) {
            let (facts, visible) = job_facts.expect("read after the first round's run");
            let cpu_ms = run.cpu_median_ms();
            rows.push(RuntimeRow {
                scene: format!("{}{}", scene.name, runners[v].0),
                camera: scene.cameras[c].name.clone(),
                resolution: res,
                plan: run.plan,
                visible,
                facts,
                cpu_ms,
                timings: run.timings,
                source: run.source,
                bytes: pass_bytes(&facts),
            });
        }
    }
    Ok(RuntimeOutcome { adapter: gpu.describe(), bandwidth, rows, notes, write_probe, upload_probe, stereo })
}

/// Reads the last frame's active tiles and intermediate buffer back and counts what the
/// passes touched.
fn frame_facts(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    ppr: &mut PprRunner,
    [w, h]: [u32; 2],
) -> Result<FrameFacts, BenchError> {
    let renderer = ppr.renderer();
    let Some(plan) = renderer.plan().cloned() else {
        return Ok(FrameFacts::default());
    };
    let tiles_x = w.div_ceil(16);
    let tiles = u64::from(plan.tile_count());
    let mut facts = FrameFacts {
        pixels: u64::from(w) * u64::from(h),
        tiles,
        active_tiles: tiles,
        indirect: plan.indirect,
        // The clear pass (index 1) did not run on a direct frame: its buffer was cleared by
        // the frame before's reflection pass.
        cleared_ahead: !plan.indirect && !renderer.passes_recorded()[1],
        written_pixels: 0,
    };
    if plan.is_empty() {
        facts.active_tiles = 0;
        return Ok(facts);
    }
    let active: Vec<u32> = if plan.indirect {
        let words = match renderer.active_tiles_buffer() {
            Some(b) => read_buffer_u32(device, queue, b)?,
            None => Vec::new(),
        };
        let count = words.first().copied().unwrap_or(0) as usize;
        words.iter().skip(4).take(count).copied().collect()
    } else {
        (0..tiles as u32).collect()
    };
    facts.active_tiles = active.len() as u64;
    let intermediate = match renderer.intermediate_buffer() {
        Some(b) => read_buffer_u32(device, queue, b)?,
        None => Vec::new(),
    };
    let mut written = 0u64;
    for tile in active {
        let (tx, ty) = (tile % tiles_x, tile / tiles_x);
        for y in ty * 16..((ty + 1) * 16).min(h) {
            for x in tx * 16..((tx + 1) * 16).min(w) {
                let v = intermediate.get((x + y * w) as usize).copied().unwrap_or(CLEAR_VALUE);
                written += u64::from(v != CLEAR_VALUE);
            }
        }
    }
    facts.written_pixels = written;
    Ok(facts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profile_rows_keep_the_named_rows_in_profile_order() {
        let all = profile_rows(&[], &[]).expect("no filter");
        assert_eq!(all.len(), projection_profile().len());
        let wanted = ["reflection: mirrors".to_owned(), "empty".to_owned()];
        let names: Vec<_> =
            profile_rows(&wanted, &[]).expect("known rows").iter().map(|(n, ..)| *n).collect();
        assert_eq!(names, ["empty", "reflection: mirrors"]);
    }

    #[test]
    fn skipped_profile_rows_are_left_out_of_the_named_or_all_rows() {
        let skipped = ["empty".to_owned()];
        let rest = profile_rows(&[], &skipped).expect("known rows");
        assert_eq!(rest.len(), projection_profile().len() - 1);
        assert!(rest.iter().all(|(n, ..)| *n != "empty"));
        let wanted = ["reflection: mirrors".to_owned(), "empty".to_owned()];
        let names: Vec<_> =
            profile_rows(&wanted, &skipped).expect("known rows").iter().map(|(n, ..)| *n).collect();
        assert_eq!(names, ["reflection: mirrors"]);
        let err = profile_rows(&[], &["emtpy".to_owned()]).expect_err("no such row").to_string();
        assert!(err.contains("--skip-profile-row \"emtpy\""), "{err}");
    }

    #[test]
    fn an_unknown_profile_row_is_an_error_that_lists_the_rows() {
        let err = profile_rows(&["tests onyl".to_owned()], &[]).expect_err("no such row").to_string();
        assert!(err.contains("\"tests onyl\"") && err.contains("\"tests only\""), "{err}");
    }
}
