//! What every technique and preset shares: output only on reflector pixels (alpha 1 where
//! found, 0 elsewhere, nothing NaN), a new viewport size, and a clear failure without the
//! reflector ids.

use ppr_baselines::{
    HiZSettings, HiZSsrTechnique, PlanarReflectionTechnique, SsprSettings, SsprTechnique, SsrGlossySettings,
    SsrGlossyTechnique, SsrSettings, SsrTechnique,
};
use ppr_runtime::ReflectionSettings;
use ppr_testbed::{PprTechnique, ReflectionInputs, ReflectionTechnique, RenderSettings, SyntheticScene};

use crate::common::{gpu, run, timed};
use crate::scenes::floor_mirror;

/// Every technique with every preset, for `scene`.
fn every_technique(scene: &SyntheticScene) -> Vec<Box<dyn ReflectionTechnique>> {
    let g = gpu();
    let (device, queue) = (&g.ctx.device, &g.ctx.queue);
    let mut all: Vec<Box<dyn ReflectionTechnique>> = Vec::new();
    for (_, s) in SsrSettings::presets() {
        all.push(Box::new(SsrTechnique::new(device, queue, &scene.reflectors, s)));
    }
    for (_, s) in HiZSettings::presets() {
        all.push(Box::new(HiZSsrTechnique::new(device, queue, &scene.reflectors, s)));
    }
    for (_, s) in SsprSettings::presets() {
        all.push(Box::new(SsprTechnique::new(device, queue, &scene.reflectors, s)));
    }
    all.push(Box::new(PlanarReflectionTechnique::new(
        device,
        queue,
        &scene.level,
        &scene.reflectors,
        RenderSettings::default(),
    )));
    all
}

/// Each technique writes a reflection only on reflector pixels, alpha exactly 0 or 1 and
/// finite colour; run twice at two sizes (reallocation on resize), with standard and
/// reversed Z; and names its passes in its timings when the device has timestamps.
#[test]
fn every_technique_writes_only_reflector_pixels_at_any_size() {
    timed("every_technique_writes_only_reflector_pixels_at_any_size", || {
        let scene = floor_mirror();
        let g = gpu();
        for mut technique in every_technique(&scene) {
            for (size, reversed) in [([160, 120], false), ([97, 131], true)] {
                let mut camera = scene.camera;
                if reversed {
                    camera.projection.depth = ppr_runtime::DepthMode::Reversed;
                }
                let r = run(&scene, &camera, size, technique.as_mut());
                let name = &r.name;
                let mut found = 0;
                for (x, y, p) in r.reflection.enumerate_pixels() {
                    let [cr, cg, cb, a] = p.0;
                    assert!(a == 0.0 || a == 1.0, "{name} {size:?}: alpha {a} at ({x}, {y})");
                    assert!(
                        [cr, cg, cb].iter().all(|c| c.is_finite()),
                        "{name} {size:?}: {p:?} at ({x}, {y})"
                    );
                    if a == 1.0 {
                        found += 1;
                        assert_ne!(
                            r.frame.reflector_id.get(x, y),
                            0,
                            "{name} {size:?}: reflection off the reflector at ({x}, {y})"
                        );
                    } else {
                        assert_eq!(
                            [cr, cg, cb],
                            [0.0; 3],
                            "{name} {size:?}: colour without a reflection at ({x}, {y})"
                        );
                    }
                }
                // Low-quality SSR finds least: 59 pixels at 160 x 120 on llvmpipe.
                assert!(found > 20, "{name} {size:?}: only {found} pixels reflect");
                match &r.timings {
                    None => assert!(!g.ctx.has_timestamps(), "{name}: the device has timestamps"),
                    Some(t) => {
                        assert!(
                            !t.is_empty() && t.iter().all(|(_, ms)| ms.is_finite() && *ms >= 0.0),
                            "{name}: {t:?}"
                        )
                    }
                }
            }
        }
    });
}

/// A technique told to stop its pass timing (`ppr-bench`'s `timing=frame` times its whole
/// frame itself) gives no timings from then on and draws the same reflection; before, it
/// gave them (llvmpipe's GL has timestamps).
#[test]
fn techniques_without_pass_timing_give_none_and_draw_the_same() {
    timed("techniques_without_pass_timing_give_none_and_draw_the_same", || {
        let scene = floor_mirror();
        let g = gpu();
        assert!(g.ctx.has_timestamps(), "this test needs timestamps (llvmpipe's GL has them)");
        let (device, queue) = (&g.ctx.device, &g.ctx.queue);
        let mut all = every_technique(&scene);
        all.push(Box::new(SsrGlossyTechnique::new(
            device,
            queue,
            &scene.reflectors,
            SsrGlossySettings::default(),
        )));
        all.push(Box::new(
            PprTechnique::new(device, queue, &scene.reflectors, ReflectionSettings::default())
                .expect("a valid set"),
        ));
        for mut technique in all {
            let size = [96, 72];
            let timed_run = run(&scene, &scene.camera, size, technique.as_mut());
            let name = &timed_run.name;
            assert!(timed_run.timings.as_ref().is_some_and(|t| !t.is_empty()), "{name}: no timings before");
            technique.stop_pass_timing();
            let quiet = run(&scene, &scene.camera, size, technique.as_mut());
            assert_eq!(quiet.timings, None, "{name}: timings after stop_pass_timing");
            assert!(
                timed_run.reflection.as_raw() == quiet.reflection.as_raw(),
                "{name}: another reflection without pass timing"
            );
        }
    });
}

/// The Hi-Z build is its own entry in the Hi-Z technique's timings, before the trace.
#[test]
fn hiz_timings_name_the_build_apart() {
    timed("hiz_timings_name_the_build_apart", || {
        let scene = floor_mirror();
        let g = gpu();
        assert!(g.ctx.has_timestamps(), "this test needs timestamps (llvmpipe's GL has them)");
        let mut technique =
            HiZSsrTechnique::new(&g.ctx.device, &g.ctx.queue, &scene.reflectors, HiZSettings::seed());
        let r = run(&scene, &scene.camera, [128, 96], &mut technique);
        let names: Vec<String> = r.timings.expect("timestamps").into_iter().map(|(n, _)| n).collect();
        assert_eq!(names, ["hi-z build", "hi-z trace"]);
    });
}

/// The screen-space techniques need the reflector ids and say so.
#[test]
#[should_panic(expected = "needs ReflectionInputs::reflector_id")]
fn ssr_without_reflector_ids_panics_with_a_clear_message() {
    let scene = floor_mirror();
    let g = gpu();
    let (device, queue) = (&g.ctx.device, &g.ctx.queue);
    let mut technique = SsrTechnique::new(device, queue, &scene.reflectors, SsrSettings::brute_force());
    technique.prepare(device, queue, &scene.camera, [64, 48]);
    let texture = |format, usage| {
        device
            .create_texture(&wgpu::TextureDescriptor {
                label: None,
                size: wgpu::Extent3d { width: 64, height: 48, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
            .create_view(&Default::default())
    };
    let color = texture(wgpu::TextureFormat::Rgba16Float, wgpu::TextureUsages::TEXTURE_BINDING);
    let depth = texture(wgpu::TextureFormat::R32Float, wgpu::TextureUsages::TEXTURE_BINDING);
    let output = texture(wgpu::TextureFormat::Rgba16Float, wgpu::TextureUsages::STORAGE_BINDING);
    let mut encoder = device.create_command_encoder(&Default::default());
    technique.encode(&mut encoder, &ReflectionInputs::new(&color, &depth, &output));
}
