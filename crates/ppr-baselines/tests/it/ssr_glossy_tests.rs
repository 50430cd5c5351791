//! Glossy SSR: plain SSR on mirrors, blurred on rough reflectors, and closer than plain
//! SSR to the exact glossy reference on a rough floor.

use ppr_baselines::{SsrGlossySettings, SsrGlossyTechnique, SsrTechnique};
use ppr_testbed::metrics::psnr;
use ppr_testbed::{GlossyParams, PixelMask, RenderSettings, SyntheticScene, ToneMap};

use crate::common::{TechniqueRun, gpu, run_with, timed};
use crate::scenes::floor_mirror;

/// Small enough for llvmpipe with 64 glossy-reference views.
const SIZE: [u32; 2] = [160, 120];

fn with_roughness(roughness: f64) -> SyntheticScene {
    let mut scene = floor_mirror();
    scene.reflectors.reflectors[0].roughness = roughness;
    scene
}

fn glossy_settings() -> RenderSettings {
    RenderSettings { glossy: GlossyParams::tests(), ..RenderSettings::default() }
}

fn run_pair(scene: &SyntheticScene, settings: SsrGlossySettings) -> (TechniqueRun, TechniqueRun) {
    let g = gpu();
    let (device, queue) = (&g.ctx.device, &g.ctx.queue);
    let mut plain = SsrTechnique::new(device, queue, &scene.reflectors, settings.march);
    let mut glossy = SsrGlossyTechnique::new(device, queue, &scene.reflectors, settings);
    let a = run_with(scene, &scene.camera, SIZE, &mut plain, glossy_settings());
    let b = run_with(scene, &scene.camera, SIZE, &mut glossy, glossy_settings());
    eprintln!("{}\n{}", a.summary(), b.summary());
    (a, b)
}

/// On-screen reflector pixels where plain SSR found a reflection.
fn found_on_screen(run: &TechniqueRun) -> PixelMask {
    let [w, h] = run.frame.size();
    let on = run.frame.on_screen_mask();
    PixelMask::from_fn(w, h, |x, y| on.get(x, y) && run.reflection.get_pixel(x, y).0[3] > 0.0)
}

#[test]
fn a_mirror_gets_plain_ssr_bit_for_bit() {
    timed("a_mirror_gets_plain_ssr_bit_for_bit", || {
        for (name, settings) in SsrGlossySettings::presets() {
            let (plain, glossy) = run_pair(&with_roughness(0.0), settings);
            // 64-pixel steps find little at 160 px (57 px measured), brute force 768.
            assert!(found_on_screen(&plain).count() > 40, "{name}: plain SSR found too little");
            assert_eq!(plain.reflection, glossy.reflection, "{name}: roughness 0 must be plain SSR");
        }
    });
}

#[test]
fn a_rough_floor_is_blurred_and_closer_to_the_glossy_reference_than_plain_ssr() {
    timed("a_rough_floor_is_blurred_and_closer_to_the_glossy_reference_than_plain_ssr", || {
        let scene = with_roughness(0.3);
        let (plain, glossy) = run_pair(&scene, SsrGlossySettings::brute_force());
        let mask = found_on_screen(&plain);
        assert!(mask.count() > 500, "plain SSR found {} on-screen pixels", mask.count());
        let reference = &plain.frame.reference;
        // Both runs render the same glossy reference; with other tests on the shared
        // software adapter at the same time the two differ in the last bits of some pixels
        // (seen: 4th significant digit), so both techniques are scored against one of them
        // and the two are only required to agree closely.
        let full = PixelMask::from_fn(SIZE[0], SIZE[1], |_, _| true);
        let agree = psnr(reference, &glossy.frame.reference, &full, ToneMap::Clamp).expect("sizes");
        assert!(agree >= 50.0, "the two runs' glossy references differ: {agree:.1} dB");
        let plain_db = psnr(reference, &plain.reflection, &mask, ToneMap::Clamp).expect("sizes");
        let glossy_db = psnr(reference, &glossy.reflection, &mask, ToneMap::Clamp).expect("sizes");
        let changed = PixelMask::from_fn(SIZE[0], SIZE[1], |x, y| {
            mask.get(x, y) && plain.reflection.get_pixel(x, y) != glossy.reflection.get_pixel(x, y)
        });
        eprintln!(
            "roughness 0.3 vs the glossy reference over {} px: plain SSR {plain_db:.1} dB, glossy SSR \
             {glossy_db:.1} dB; {} px changed by the blur",
            mask.count(),
            changed.count()
        );
        assert!(changed.count() * 2 > mask.count(), "the blur changed only {} px", changed.count());
        // Measured on llvmpipe: plain 19.5 dB, glossy 21.2 dB (spread 4; 2: 20.4, 8: 21.8).
        // The rest is what a screen-space blur cannot see: the sky a rough reflection
        // blends in where the march found nothing, and the lobe's stretch at grazing views.
        assert!(glossy_db >= plain_db + 1.0, "glossy SSR {glossy_db:.1} dB vs plain SSR {plain_db:.1} dB");
    });
}
