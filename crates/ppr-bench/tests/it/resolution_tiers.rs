//! The reduced-resolution tiers on the software adapter (issue 13): against the exact
//! reference over the on-screen reflector pixels of the box room, at 320×180, the half and
//! quarter tiers stay within a stated distance of full-resolution PPR and well above
//! writing nothing.

use image::Rgba32FImage;
use ppr_bench::TechniqueSpec;
use ppr_bench::mirror_room::one_frame::render_scene_frame;
use ppr_bench::mirror_room::{MirrorRoom, bench_scene};
use ppr_bench::quality::Quality;
use ppr_bench::scene::SceneOptions;
use ppr_runtime::PlanParams;
use ppr_testbed::GpuContext;
use ppr_testbed::image_io::ToneMap;

const SIZE: [u32; 2] = [320, 180];

/// Bounds (fade off so that only the tier differs), with margin over what llvmpipe gave at
/// 320×180 when written (on-screen PSNR full 37.1 / 36.9 / 42.4 dB on the three cameras,
/// half 32.9 / 31.4 / 33.8, quarter 29.6 / 28.0 / 29.2, writing nothing 16.4–18.1; no data
/// full 0.0 %, half 0.0–0.3 %, quarter 0.04–0.35 %): the half tier within 10 dB of full
/// resolution and 12 dB above writing nothing, with at most 3 points more on-screen pixels
/// without data; the quarter tier (80×45 pixels here) at least 8 dB above writing nothing.
/// Each tier must write: a tier that wrote nothing scores the fallback.
#[test]
fn reduced_tiers_stay_close_to_full_resolution() {
    let gpu = GpuContext::new_headless().expect("a wgpu adapter (llvmpipe without a GPU)");
    let scene = bench_scene(MirrorRoom::BoxesInBox { boxes: 2 }, &SceneOptions::default());
    let labels = ["ppr fade=0", "ppr fade=0 tier=half", "ppr fade=0 tier=quarter"];
    let specs: Vec<TechniqueSpec> = ["ppr:fade=0", "ppr:fade=0,tier=half", "ppr:fade=0,tier=quarter"]
        .map(|t| t.parse().expect("spec"))
        .to_vec();
    for cam in &scene.cameras {
        let f = render_scene_frame(&gpu, &scene, &cam.camera, SIZE, &specs, &PlanParams::default())
            .expect("frame");
        let q = |label: &str| &f.techniques.iter().find(|t| t.label == label).expect("ran").quality;
        let (full, half, quarter) = (q(labels[0]), q(labels[1]), q(labels[2]));
        let none = Rgba32FImage::from_pixel(SIZE[0], SIZE[1], image::Rgba([0.0; 4]));
        let nothing = Quality::measure(&f.reference, &none, ToneMap::Clamp).expect("sizes");
        let what = &cam.name;
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
            quarter.psnr_on >= nothing.psnr_on + 8.0,
            "{what}: quarter {:.2} dB, writing nothing {:.2} dB",
            quarter.psnr_on,
            nothing.psnr_on
        );
    }
}
