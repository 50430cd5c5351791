//! The reduced-resolution tiers on the software adapter (issue 13): against the exact
//! reference over the on-screen reflector pixels of the box room, at 320×180, the half and
//! quarter tiers stay within a stated distance of full-resolution PPR and well above
//! writing nothing; and the upsample's shared-memory variant gives its per-pixel image bit
//! for bit.

use image::Rgba32FImage;
use ppr_bench::TechniqueSpec;
use ppr_bench::mirror_room::one_frame::render_scene_frame;
use ppr_bench::mirror_room::{MirrorRoom, bench_scene};
use ppr_bench::quality::Quality;
use ppr_bench::scene::{BenchScene, SceneOptions};
use ppr_runtime::{Choice, PlanParams};
use ppr_testbed::GpuContext;
use ppr_testbed::image_io::ToneMap;
use ppr_testbed::synthetic::{FloorMirrorParams, SyntheticScene};

/// 320×180 (reduced 160×90 and 80×45) and 325×183, which neither tier divides (163×92 and
/// 82×46: the reduced viewport's aspect is not the output's).
const SIZES: [[u32; 2]; 2] = [[320, 180], [325, 183]];

/// Bounds (fade off so that only the tier differs), with margin over what llvmpipe gave at
/// 320×180 when written (on-screen PSNR full 37.1 / 36.9 / 42.4 dB on the three cameras,
/// half 32.9 / 31.4 / 33.8, quarter 29.6 / 28.0 / 29.2, writing nothing 16.4–18.1; no data
/// full 0.0 %, half 0.0–0.3 %, quarter 0.04–0.35 %): the half tier within 10 dB of full
/// resolution and 12 dB above writing nothing, with at most 3 points more on-screen pixels
/// without data; the quarter tier (80×45 pixels here) at least 8 dB above writing nothing,
/// with as few more pixels without data. The same bounds at 325×183.
/// Each tier must write: a tier that wrote nothing scores the fallback.
#[test]
fn reduced_tiers_stay_close_to_full_resolution() {
    let gpu = GpuContext::new_headless().expect("a wgpu adapter (llvmpipe without a GPU)");
    let scene = bench_scene(MirrorRoom::BoxesInBox { boxes: 2 }, &SceneOptions::default());
    let labels = ["ppr fade=0", "ppr fade=0 tier=half", "ppr fade=0 tier=quarter"];
    let specs: Vec<TechniqueSpec> = ["ppr:fade=0", "ppr:fade=0,tier=half", "ppr:fade=0,tier=quarter"]
        .map(|t| t.parse().expect("spec"))
        .to_vec();
    for (size, cam) in SIZES.iter().flat_map(|&size| scene.cameras.iter().map(move |cam| (size, cam))) {
        let f = render_scene_frame(&gpu, &scene, &cam.camera, size, &specs, &PlanParams::default())
            .expect("frame");
        let q = |label: &str| &f.techniques.iter().find(|t| t.label == label).expect("ran").quality;
        let (full, half, quarter) = (q(labels[0]), q(labels[1]), q(labels[2]));
        let none = Rgba32FImage::from_pixel(size[0], size[1], image::Rgba([0.0; 4]));
        let nothing = Quality::measure(&f.reference, &none, ToneMap::Clamp).expect("sizes");
        let what = format!("{} {size:?}", cam.name);
        eprintln!(
            "{what}: on-screen PSNR full {:.2}, half {:.2}, quarter {:.2}, nothing {:.2} dB; \
             no data full {:.2} %, half {:.2} %, quarter {:.2} %",
            full.psnr_on,
            half.psnr_on,
            quarter.psnr_on,
            nothing.psnr_on,
            100.0 * full.holes_on,
            100.0 * half.holes_on,
            100.0 * quarter.holes_on
        );
        assert!(full.pixels.0 > 5000, "{what}: {} on-screen pixels", full.pixels.0);
        assert!(
            half.psnr_on >= full.psnr_on - 10.0 && half.psnr_on >= nothing.psnr_on + 12.0,
            "{what}: half {:.2} dB, full {:.2} dB, nothing {:.2} dB",
            half.psnr_on,
            full.psnr_on,
            nothing.psnr_on
        );
        assert!(
            half.holes_on <= full.holes_on + 0.03,
            "{what}: half leaves {:.2} % without data, full {:.2} %",
            100.0 * half.holes_on,
            100.0 * full.holes_on
        );
        assert!(
            quarter.holes_on <= full.holes_on + 0.03,
            "{what}: quarter leaves {:.2} % without data, full {:.2} %",
            100.0 * quarter.holes_on,
            100.0 * full.holes_on
        );
        assert!(
            quarter.psnr_on >= nothing.psnr_on + 8.0,
            "{what}: quarter {:.2} dB, writing nothing {:.2} dB",
            quarter.psnr_on,
            nothing.psnr_on
        );
    }
}

/// The first pixel, row by row, where `a` and `b` differ in any channel's bits, with both
/// values and how many pixels differ.
fn first_difference(a: &Rgba32FImage, b: &Rgba32FImage) -> Option<String> {
    assert_eq!(a.dimensions(), b.dimensions());
    let same = |p: &image::Rgba<f32>, q: &image::Rgba<f32>| {
        p.0.iter().zip(q.0).all(|(u, v)| u.to_bits() == v.to_bits())
    };
    let differing = a.pixels().zip(b.pixels()).filter(|(p, q)| !same(p, q)).count();
    a.enumerate_pixels().zip(b.pixels()).find_map(|((x, y, p), q)| {
        (!same(p, q))
            .then(|| format!("pixel ({x}, {y}): {:?} against {:?} ({differing} pixels differ)", p.0, q.0))
    })
}

/// Pixels with a reflection (alpha above 0).
fn written(image: &Rgba32FImage) -> usize {
    image.pixels().filter(|p| p.0[3] > 0.0).count()
}

/// `upsample=shared` (`DebugOptions::shared_upsample`) gives the per-pixel upsample's image
/// bit for bit, every pixel and channel: the half and quarter tiers, with direct and
/// indirect dispatch (`INDIRECT`), without and with a border fade (partial alphas), on
/// the box room's cameras at 320×180 (reduced 160×90 and 80×45, exact divisions) and 325×183 (163×92 and 82×46: scales that are no 1/2 or 1/4,
/// and the last tiles of each row and column partial, their samples clamped at the right
/// and bottom edges). The box room has no glass or water (no layers); the floor mirror with
/// a glass pane has one, so its frames run the layer output's upsample (`LAYERS`) too.
#[test]
fn shared_upsample_gives_the_per_pixel_image() {
    let gpu = GpuContext::new_headless().expect("a wgpu adapter (llvmpipe without a GPU)");
    let room = bench_scene(MirrorRoom::BoxesInBox { boxes: 2 }, &SceneOptions::default());
    let pane = SyntheticScene::floor_mirror(&FloorMirrorParams { wall_pane: true, ..Default::default() });
    let pane = BenchScene::from_parts(
        "floor mirror with a glass pane",
        pane.level,
        pane.reflectors,
        &SceneOptions::default(),
        &mut Vec::new(),
    );
    // fade=0 (alpha 1 wherever there is data) and a border fade of 0.2 (alphas between
    // 0 and 1 near the screen's edges, which the shared span's depth reads must not skip).
    let per_pixel: Vec<String> = ["half", "quarter"]
        .iter()
        .flat_map(|tier| ["", ",indirect=on"].map(|dispatch| format!("ppr:fade=0,tier={tier}{dispatch}")))
        .chain(["ppr:fade=0.2,tier=half".to_string(), "ppr:fade=0.2,tier=quarter,indirect=on".to_string()])
        .collect();
    let specs: Vec<TechniqueSpec> = per_pixel
        .iter()
        .cloned()
        .chain(per_pixel.iter().map(|s| format!("{s},upsample=shared")))
        .map(|t| t.parse().expect("spec"))
        .collect();
    let n = per_pixel.len();
    let params = PlanParams::default();
    for size in [[320, 180], [325, 183]] {
        for (scene, min_written, layered) in [(&room, 20_000, false), (&pane, 3_000, true)] {
            for cam in &scene.cameras {
                let what = format!("{} {} {size:?}", scene.name, cam.name);
                let f = render_scene_frame(&gpu, scene, &cam.camera, size, &specs, &params).expect("frame");
                for (own, shared) in f.techniques[..n].iter().zip(&f.techniques[n..]) {
                    assert_eq!(shared.label, format!("{} upsample=shared", own.label));
                    let count = written(&own.image);
                    eprintln!("{what}, {}: {count} pixels with a reflection", own.label);
                    assert!(count >= min_written, "{what}, {}: {count} pixels with a reflection", own.label);
                    if let Some(d) = first_difference(&own.image, &shared.image) {
                        panic!("{what}, {} against {}: {d}", own.label, shared.label);
                    }
                }
                if layered {
                    // The pane's layer output is part of the image: without layers it differs.
                    let off = PlanParams { layers: Choice::Off, ..params };
                    let flat =
                        render_scene_frame(&gpu, scene, &cam.camera, size, &specs[..n], &off).expect("frame");
                    for (layered, flat) in f.techniques.iter().zip(&flat.techniques) {
                        let layer_pixels =
                            layered.image.pixels().zip(flat.image.pixels()).filter(|(a, b)| a != b);
                        let layer_pixels = layer_pixels.count();
                        assert!(
                            layer_pixels >= 500,
                            "{what}, {}: {layer_pixels} pixels from layers",
                            layered.label
                        );
                    }
                }
            }
        }
    }
}

/// The upsample's time probes (`upsample=store-only|depth-only|no-own-depth`,
/// `DebugOptions::upsample_probe`) record what they name: the first two no reflection at all
/// (the depth probe's value, depth × 1e-30, is below the output's half floats), the third
/// the upsample with each pixel's distance from its samples', whose image is the default's
/// but at silhouettes: reflections on about as many pixels, nearly all the same colour.
#[test]
fn upsample_probes_record_what_they_name() {
    let gpu = GpuContext::new_headless().expect("a wgpu adapter (llvmpipe without a GPU)");
    let room = bench_scene(MirrorRoom::BoxesInBox { boxes: 2 }, &SceneOptions::default());
    let specs: Vec<TechniqueSpec> =
        ["", ",upsample=store-only", ",upsample=depth-only", ",upsample=no-own-depth"]
            .iter()
            .map(|probe| format!("ppr:fade=0,tier=quarter{probe}").parse().expect("spec"))
            .collect();
    let cam = &room.cameras[0];
    let f = render_scene_frame(&gpu, &room, &cam.camera, [320, 180], &specs, &PlanParams::default())
        .expect("frame");
    let [own, store, depth, no_own] = &f.techniques[..] else { panic!("four techniques") };
    let count = written(&own.image);
    assert!(count >= 20_000, "{}: {count} pixels with a reflection", own.label);
    assert_eq!(written(&store.image), 0, "{}", store.label);
    assert_eq!(written(&depth.image), 0, "{}", depth.label);
    let approx = written(&no_own.image);
    assert!(approx.abs_diff(count) * 20 <= count, "{}: {approx} pixels against {count}", no_own.label);
    let close =
        |p: &image::Rgba<f32>, q: &image::Rgba<f32>| p.0.iter().zip(q.0).all(|(u, v)| (u - v).abs() <= 0.02);
    let unlike = own.image.pixels().zip(no_own.image.pixels()).filter(|(p, q)| !close(p, q)).count();
    assert!(unlike * 20 <= count, "{}: {unlike} pixels unlike the default's", no_own.label);
    assert!(unlike > 0 || approx != count, "{}: the very same image", no_own.label);
}
