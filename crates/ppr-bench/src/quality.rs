//! Accuracy of a technique's reflection against the exact one, over reflector pixels, split
//! into pixels whose reflected point is on screen and those where it is not.
//!
//! Every technique is scored as a renderer would show it: its colour blended over one
//! fallback by its alpha (`mix(fallback, rgb, alpha)`; PPR's alpha is a confidence, the
//! baselines' 0 or 1). The fallback is the same for every technique: the scene's own colour
//! at the pixel, what the surface shows without a screen-space reflection. So a technique
//! gains nothing by writing nothing, and its share of pixels without data stays beside its
//! score.

use image::Rgba32FImage;
use ppr_testbed::image_io::ToneMap;
use ppr_testbed::metrics::{flip_map, psnr};
use ppr_testbed::{FrameImages, PixelMask};

use crate::error::BenchError;

/// The reference frame of one camera and size, with its masks.
pub struct ReferenceFrame {
    /// Exact reflection (alpha 1 on reflector pixels).
    pub reference: Rgba32FImage,
    /// Scene colour (for image sheets).
    pub color: Rgba32FImage,
    /// Reflector pixels whose reflected point is on screen.
    pub on_screen: PixelMask,
    /// Reflector pixels whose reflected point is off screen, hidden or background.
    pub off_screen: PixelMask,
    /// Either of the two.
    pub measured: PixelMask,
}

impl ReferenceFrame {
    pub fn new(images: FrameImages) -> Self {
        let on_screen = images.on_screen_mask();
        let off_screen = images.off_screen_mask();
        let bits = on_screen.bits.iter().zip(&off_screen.bits).map(|(a, b)| *a || *b).collect();
        let measured = PixelMask { width: on_screen.width, height: on_screen.height, bits };
        Self { reference: images.reference, color: images.color, on_screen, off_screen, measured }
    }
}

/// Accuracy of one reflection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quality {
    /// PSNR over on-screen reflector pixels, dB (`inf` when identical or none).
    pub psnr_on: f64,
    /// PSNR over off-screen reflector pixels, dB.
    pub psnr_off: f64,
    /// Mean FLIP over on-screen reflector pixels.
    pub flip_on: f64,
    /// Mean FLIP over off-screen reflector pixels.
    pub flip_off: f64,
    /// Share of on-screen reflector pixels left without data (alpha 0; PPR's alpha is a
    /// confidence, > 0 wherever a reflection was found).
    pub holes_on: f64,
    /// Share of all measured reflector pixels left without data.
    pub holes_all: f64,
    /// On-screen and off-screen reflector pixels.
    pub pixels: (usize, usize),
}

impl Quality {
    /// The exact reference against itself.
    pub fn exact(reference: &ReferenceFrame) -> Self {
        Self {
            psnr_on: f64::INFINITY,
            psnr_off: f64::INFINITY,
            flip_on: 0.0,
            flip_off: 0.0,
            holes_on: 0.0,
            holes_all: 0.0,
            pixels: (reference.on_screen.count(), reference.off_screen.count()),
        }
    }

    /// Measures `test` against `reference`.
    ///
    /// FLIP is computed once per image (it dominates the cost): outside the measured
    /// reflector pixels the test image is replaced by the reference, so errors elsewhere
    /// cannot bleed in through FLIP's filters; the map is then averaged over each class.
    /// (The testbed's `flip_mean` replaces outside each class separately; the two differ
    /// only at class borders.)
    ///
    /// # Errors
    /// Sizes differ.
    pub fn measure(
        reference: &ReferenceFrame,
        test: &Rgba32FImage,
        tone_map: ToneMap,
    ) -> Result<Self, BenchError> {
        let r = &reference.reference;
        let shown = over_fallback(test, &reference.color)?;
        let test = &shown;
        let psnr_on = psnr(r, test, &reference.on_screen, tone_map)?;
        let psnr_off = psnr(r, test, &reference.off_screen, tone_map)?;
        let (flip_on, flip_off) = if reference.measured.count() == 0 {
            (0.0, 0.0)
        } else {
            let masked = Rgba32FImage::from_fn(test.width(), test.height(), |x, y| {
                if reference.measured.get(x, y) { *test.get_pixel(x, y) } else { *r.get_pixel(x, y) }
            });
            let map = flip_map(r, &masked, tone_map)?;
            (masked_mean(&map, &reference.on_screen), masked_mean(&map, &reference.off_screen))
        };
        Ok(Self {
            psnr_on,
            psnr_off,
            flip_on,
            flip_off,
            holes_on: hole_share(&shown, &reference.on_screen),
            holes_all: hole_share(&shown, &reference.measured),
            pixels: (reference.on_screen.count(), reference.off_screen.count()),
        })
    }
}

/// What a renderer shows: `test`'s colour over `fallback` by `test`'s alpha (clamped to
/// [0, 1]; a non-finite alpha counts as 0). Keeps `test`'s alpha, for the hole shares.
///
/// # Errors
/// Sizes differ.
pub fn over_fallback(test: &Rgba32FImage, fallback: &Rgba32FImage) -> Result<Rgba32FImage, BenchError> {
    if test.dimensions() != fallback.dimensions() {
        return Err(ppr_testbed::TestbedError::SizeMismatch {
            what: "reflection against its fallback".into(),
            a: [test.width(), test.height()],
            b: [fallback.width(), fallback.height()],
        }
        .into());
    }
    Ok(Rgba32FImage::from_fn(test.width(), test.height(), |x, y| {
        let t = test.get_pixel(x, y).0;
        let f = fallback.get_pixel(x, y).0;
        let a = if t[3].is_finite() { t[3].clamp(0.0, 1.0) } else { 0.0 };
        let mix = |c: usize| match a {
            1.0 => t[c],
            0.0 => f[c],
            _ => f[c] + (t[c] - f[c]) * a,
        };
        image::Rgba([mix(0), mix(1), mix(2), t[3]])
    }))
}

/// Mean of `values` over the mask (0 for an empty mask).
fn masked_mean(values: &[f32], mask: &PixelMask) -> f64 {
    let (sum, n) = values
        .iter()
        .zip(&mask.bits)
        .filter(|(_, m)| **m)
        .fold((0.0f64, 0usize), |(s, n), (v, _)| (s + f64::from(*v), n + 1));
    if n == 0 { 0.0 } else { sum / n as f64 }
}

/// Share of the masked pixels whose alpha is 0: no reflection (0 for an empty mask).
pub fn hole_share(image: &Rgba32FImage, mask: &PixelMask) -> f64 {
    let total = mask.count();
    if total == 0 {
        return 0.0;
    }
    let holes = image.enumerate_pixels().filter(|(x, y, p)| mask.get(*x, *y) && p.0[3] <= 0.0).count();
    holes as f64 / total as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn holes_and_masked_mean() {
        let img =
            Rgba32FImage::from_fn(4, 1, |x, _| image::Rgba([0.5, 0.5, 0.5, if x < 1 { 0.0 } else { 1.0 }]));
        let mask = PixelMask::from_fn(4, 1, |x, _| x < 2);
        assert_eq!(hole_share(&img, &mask), 0.5);
        assert_eq!(masked_mean(&[1.0, 3.0, 100.0, 100.0], &mask), 2.0);
        assert_eq!(masked_mean(&[1.0; 4], &PixelMask::from_fn(4, 1, |_, _| false)), 0.0);
    }

    /// Writing nothing scores as the fallback does, whatever colour the "holes" hold; a
    /// technique that gets half the pixels right scores better than one that writes none.
    #[test]
    fn writing_nothing_scores_as_the_fallback() {
        let (w, h) = (8, 4);
        let exact = Rgba32FImage::from_fn(w, h, |x, _| image::Rgba([0.1 * x as f32, 0.5, 0.2, 1.0]));
        let scene = Rgba32FImage::from_fn(w, h, |_, _| image::Rgba([0.3, 0.3, 0.3, 1.0]));
        let all = PixelMask::from_fn(w, h, |_, _| true);
        let reference = ReferenceFrame {
            reference: exact.clone(),
            color: scene.clone(),
            on_screen: all.clone(),
            off_screen: PixelMask::from_fn(w, h, |_, _| false),
            measured: all,
        };
        // The exact colours, but flagged as no data: no credit for them.
        let hidden = Rgba32FImage::from_fn(w, h, |x, y| {
            let p = exact.get_pixel(x, y).0;
            image::Rgba([p[0], p[1], p[2], 0.0])
        });
        let nothing = Quality::measure(&reference, &hidden, ToneMap::Clamp).expect("sizes");
        let fallback_only = Quality::measure(&reference, &scene.clone(), ToneMap::Clamp);
        assert!(nothing.psnr_on.is_finite(), "{nothing:?}");
        assert_eq!(nothing.holes_on, 1.0);
        // The scene's alpha is 1: scored as its colour, the same as the fallback.
        assert_eq!(fallback_only.expect("sizes").psnr_on, nothing.psnr_on);
        let half = Rgba32FImage::from_fn(w, h, |x, y| {
            let p = exact.get_pixel(x, y).0;
            image::Rgba([p[0], p[1], p[2], if x < w / 2 { 1.0 } else { 0.0 }])
        });
        let half = Quality::measure(&reference, &half, ToneMap::Clamp).expect("sizes");
        assert!(half.psnr_on > nothing.psnr_on + 1.0, "{half:?} vs {nothing:?}");
        assert_eq!(half.holes_on, 0.5);
        let full = Quality::measure(&reference, &exact, ToneMap::Clamp).expect("sizes");
        assert!(full.psnr_on.is_infinite(), "{full:?}");
    }
}
