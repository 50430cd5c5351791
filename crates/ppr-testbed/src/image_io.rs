//! Images on disk: tonemapping and sRGB encoding to PNG, raw float EXR, and difference images.

use std::path::Path;

use image::{Rgb, RgbImage, Rgba32FImage};

use crate::TestbedError;
use crate::pixel_mask::PixelMask;

/// How linear HDR values are brought to `[0, 1]` before sRGB encoding.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ToneMap {
    /// Clamp each channel to `[0, 1]`.
    #[default]
    Clamp,
    /// Reinhard per channel: `v / (1 + v)`.
    Reinhard,
}

impl ToneMap {
    /// Maps one linear channel value to `[0, 1]`.
    pub fn apply(self, v: f32) -> f32 {
        let v = if v.is_finite() { v.max(0.0) } else { 0.0 };
        match self {
            Self::Clamp => v.min(1.0),
            Self::Reinhard => v / (1.0 + v),
        }
    }
}

/// The sRGB transfer function (linear `[0, 1]` to encoded `[0, 1]`).
pub fn linear_to_srgb(v: f32) -> f32 {
    let v = v.clamp(0.0, 1.0);
    if v <= 0.003_130_8 { v * 12.92 } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 }
}

/// Tonemaps and sRGB-encodes a linear image to 8-bit RGB (alpha dropped).
pub fn to_srgb8(image: &Rgba32FImage, tone_map: ToneMap) -> RgbImage {
    RgbImage::from_fn(image.width(), image.height(), |x, y| {
        let p = image.get_pixel(x, y).0;
        Rgb([0, 1, 2].map(|c| encode_u8(linear_to_srgb(tone_map.apply(p[c])))))
    })
}

/// Tonemapped (not sRGB-encoded) RGB values of a pixel, each in `[0, 1]`.
pub fn tonemapped(image: &Rgba32FImage, x: u32, y: u32, tone_map: ToneMap) -> [f32; 3] {
    let p = image.get_pixel(x, y).0;
    [tone_map.apply(p[0]), tone_map.apply(p[1]), tone_map.apply(p[2])]
}

fn encode_u8(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// Writes a linear image as an 8-bit sRGB PNG.
///
/// # Errors
/// [`TestbedError::ImageWrite`] naming the path.
pub fn write_png(
    path: impl AsRef<Path>,
    image: &Rgba32FImage,
    tone_map: ToneMap,
) -> Result<(), TestbedError> {
    write_rgb8(path, &to_srgb8(image, tone_map))
}

/// Writes an 8-bit RGB image as PNG.
///
/// # Errors
/// [`TestbedError::ImageWrite`] naming the path.
pub fn write_rgb8(path: impl AsRef<Path>, image: &RgbImage) -> Result<(), TestbedError> {
    let path = path.as_ref();
    image
        .save_with_format(path, image::ImageFormat::Png)
        .map_err(|source| TestbedError::ImageWrite { path: path.to_owned(), source })
}

/// Writes the raw linear float values (RGBA) as OpenEXR.
///
/// # Errors
/// [`TestbedError::ImageWrite`] naming the path.
pub fn write_exr(path: impl AsRef<Path>, image: &Rgba32FImage) -> Result<(), TestbedError> {
    let path = path.as_ref();
    image
        .save_with_format(path, image::ImageFormat::OpenExr)
        .map_err(|source| TestbedError::ImageWrite { path: path.to_owned(), source })
}

/// Reads an image file (PNG decoded to linear, EXR as is) as linear RGBA `f32`.
///
/// # Errors
/// [`TestbedError::ImageRead`] naming the path.
pub fn read_linear(path: impl AsRef<Path>) -> Result<Rgba32FImage, TestbedError> {
    let path = path.as_ref();
    let decoded =
        image::open(path).map_err(|source| TestbedError::ImageRead { path: path.to_owned(), source })?;
    let is_float =
        matches!(decoded, image::DynamicImage::ImageRgba32F(_) | image::DynamicImage::ImageRgb32F(_));
    let mut out = decoded.to_rgba32f();
    if !is_float {
        for p in out.pixels_mut() {
            for c in 0..3 {
                p.0[c] = crate::readback::srgb_to_linear(p.0[c]);
            }
        }
    }
    Ok(out)
}

/// A colour ramp for errors in `[0, 1]`: black, blue, cyan, green, yellow, red.
pub fn error_ramp(t: f32) -> [u8; 3] {
    const STOPS: [[f32; 3]; 6] = [
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 1.0, 1.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
    ];
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 1.0 } * (STOPS.len() - 1) as f32;
    let i = (t.floor() as usize).min(STOPS.len() - 2);
    let f = t - i as f32;
    [0, 1, 2].map(|c| encode_u8(STOPS[i][c] + (STOPS[i + 1][c] - STOPS[i][c]) * f))
}

/// A difference image: inside `mask`, the largest per-channel absolute difference of the
/// tonemapped values times `scale`, through [`error_ramp`]; outside, `b` darkened to a
/// quarter in grey so the context stays readable.
///
/// # Errors
/// [`TestbedError::SizeMismatch`] if the images or the mask differ in size.
pub fn difference_image(
    a: &Rgba32FImage,
    b: &Rgba32FImage,
    mask: &PixelMask,
    scale: f32,
    tone_map: ToneMap,
) -> Result<RgbImage, TestbedError> {
    check_sizes("difference image", a, b, mask)?;
    Ok(RgbImage::from_fn(a.width(), a.height(), |x, y| {
        let (ta, tb) = (tonemapped(a, x, y, tone_map), tonemapped(b, x, y, tone_map));
        if mask.get(x, y) {
            let d = (0..3).map(|c| (ta[c] - tb[c]).abs()).fold(0.0, f32::max);
            Rgb(error_ramp(d * scale))
        } else {
            let luma = 0.2126 * tb[0] + 0.7152 * tb[1] + 0.0722 * tb[2];
            let g = encode_u8(linear_to_srgb(luma) * 0.25);
            Rgb([g, g, g])
        }
    }))
}

/// Checks that two images and a mask have one size.
///
/// # Errors
/// [`TestbedError::SizeMismatch`] naming `what`.
pub fn check_sizes(
    what: &str,
    a: &Rgba32FImage,
    b: &Rgba32FImage,
    mask: &PixelMask,
) -> Result<(), TestbedError> {
    let sa = [a.width(), a.height()];
    for other in [[b.width(), b.height()], [mask.width, mask.height]] {
        if sa != other {
            return Err(TestbedError::SizeMismatch { what: what.to_owned(), a: sa, b: other });
        }
    }
    Ok(())
}
