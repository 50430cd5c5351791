//! Image quality metrics over a pixel mask: PSNR, mean absolute error and FLIP.
//!
//! All three look at tonemapped values (see [`ToneMap`]), so the peak signal of PSNR is
//! 1.0. FLIP (NVIDIA's perceptual error, via `nv-flip`) compares the sRGB-encoded 8-bit
//! images and is averaged over the mask. An empty mask has no error: PSNR is infinite,
//! the others 0, and [`ImageComparison::pixels`] says 0.

use image::Rgba32FImage;

use crate::TestbedError;
use crate::image_io::{ToneMap, check_sizes, to_srgb8, tonemapped};
use crate::pixel_mask::PixelMask;

/// Pixels per degree of visual angle FLIP assumes (its default: a 0.7 m distance from a
/// 0.7 m wide 4K monitor, about 67).
pub const FLIP_PIXELS_PER_DEGREE: f32 = nv_flip::DEFAULT_PIXELS_PER_DEGREE;

/// The three metrics of one comparison.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageComparison {
    /// Number of pixels compared.
    pub pixels: usize,
    /// PSNR in dB with peak 1.0 on tonemapped values; `f64::INFINITY` when identical.
    pub psnr_db: f64,
    /// Mean absolute error per channel of the tonemapped values.
    pub mean_abs_error: f64,
    /// Mean FLIP error over the mask, in `[0, 1]`.
    pub flip_mean: f64,
}

impl std::fmt::Display for ImageComparison {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} px: PSNR {:.2} dB, MAE {:.4}, FLIP {:.4}",
            self.pixels, self.psnr_db, self.mean_abs_error, self.flip_mean
        )
    }
}

/// Compares `test` with `reference` over `mask` with all three metrics.
///
/// # Errors
/// [`TestbedError::SizeMismatch`] if the images or the mask differ in size.
pub fn compare(
    reference: &Rgba32FImage,
    test: &Rgba32FImage,
    mask: &PixelMask,
    tone_map: ToneMap,
) -> Result<ImageComparison, TestbedError> {
    Ok(ImageComparison {
        pixels: mask.count(),
        psnr_db: psnr(reference, test, mask, tone_map)?,
        mean_abs_error: mean_abs_error(reference, test, mask, tone_map)?,
        flip_mean: flip_mean(reference, test, mask, tone_map)?,
    })
}

/// Mean squared error per channel of the tonemapped RGB values over `mask` (0 when empty).
fn mean_squared_error(a: &Rgba32FImage, b: &Rgba32FImage, mask: &PixelMask, tone_map: ToneMap) -> f64 {
    let (sum, n) = masked_sum(a, b, mask, tone_map, |d| d * d);
    if n == 0 { 0.0 } else { sum / n as f64 }
}

fn masked_sum(
    a: &Rgba32FImage,
    b: &Rgba32FImage,
    mask: &PixelMask,
    tone_map: ToneMap,
    f: impl Fn(f64) -> f64,
) -> (f64, usize) {
    let mut sum = 0.0;
    let mut n = 0;
    for y in 0..a.height() {
        for x in 0..a.width() {
            if mask.get(x, y) {
                let (ta, tb) = (tonemapped(a, x, y, tone_map), tonemapped(b, x, y, tone_map));
                for c in 0..3 {
                    sum += f(f64::from(ta[c]) - f64::from(tb[c]));
                }
                n += 3;
            }
        }
    }
    (sum, n)
}

/// PSNR in dB over `mask`: `10 log10(1 / MSE)` with peak 1.0 on tonemapped values;
/// `f64::INFINITY` when the masked pixels are identical (or the mask is empty).
///
/// # Errors
/// [`TestbedError::SizeMismatch`] if the images or the mask differ in size.
pub fn psnr(
    a: &Rgba32FImage,
    b: &Rgba32FImage,
    mask: &PixelMask,
    tone_map: ToneMap,
) -> Result<f64, TestbedError> {
    check_sizes("PSNR", a, b, mask)?;
    let mse = mean_squared_error(a, b, mask, tone_map);
    Ok(if mse == 0.0 { f64::INFINITY } else { -10.0 * mse.log10() })
}

/// Mean absolute error per channel of the tonemapped values over `mask` (0 when empty).
///
/// # Errors
/// [`TestbedError::SizeMismatch`] if the images or the mask differ in size.
pub fn mean_abs_error(
    a: &Rgba32FImage,
    b: &Rgba32FImage,
    mask: &PixelMask,
    tone_map: ToneMap,
) -> Result<f64, TestbedError> {
    check_sizes("mean absolute error", a, b, mask)?;
    let (sum, n) = masked_sum(a, b, mask, tone_map, f64::abs);
    Ok(if n == 0 { 0.0 } else { sum / n as f64 })
}

/// The FLIP error map of `test` against `reference` (tonemapped, sRGB 8-bit), one value
/// in `[0, 1]` per pixel, rows top to bottom.
///
/// # Errors
/// [`TestbedError::SizeMismatch`] if the images differ in size.
pub fn flip_map(
    reference: &Rgba32FImage,
    test: &Rgba32FImage,
    tone_map: ToneMap,
) -> Result<Vec<f32>, TestbedError> {
    check_sizes("FLIP", reference, test, &PixelMask::all(reference.width(), reference.height()))?;
    let (w, h) = reference.dimensions();
    let r = nv_flip::FlipImageRgb8::with_data(w, h, to_srgb8(reference, tone_map).as_raw());
    let t = nv_flip::FlipImageRgb8::with_data(w, h, to_srgb8(test, tone_map).as_raw());
    Ok(nv_flip::flip(r, t, FLIP_PIXELS_PER_DEGREE).to_vec())
}

/// Mean FLIP error over `mask` (0 when the mask is empty).
///
/// FLIP's filters look at neighbours, so outside the mask the test image is replaced by the
/// reference first (differences outside the mask cannot bleed in); the error map is then
/// averaged over the mask.
///
/// # Errors
/// [`TestbedError::SizeMismatch`] if the images or the mask differ in size.
pub fn flip_mean(
    reference: &Rgba32FImage,
    test: &Rgba32FImage,
    mask: &PixelMask,
    tone_map: ToneMap,
) -> Result<f64, TestbedError> {
    check_sizes("FLIP", reference, test, mask)?;
    if mask.count() == 0 {
        return Ok(0.0);
    }
    let masked_test = Rgba32FImage::from_fn(test.width(), test.height(), |x, y| {
        if mask.get(x, y) { *test.get_pixel(x, y) } else { *reference.get_pixel(x, y) }
    });
    let map = flip_map(reference, &masked_test, tone_map)?;
    let (sum, n) = map
        .iter()
        .zip(&mask.bits)
        .filter(|(_, m)| **m)
        .fold((0.0f64, 0usize), |(s, n), (v, _)| (s + f64::from(*v), n + 1));
    Ok(sum / n as f64)
}
