//! Image sheets: the same crop of every technique's reflection side by side, one row per
//! scene, so that artefacts can be compared by eye.

use std::path::Path;

use image::{Rgb, RgbImage, Rgba32FImage, imageops};
use ppr_testbed::PixelMask;
use ppr_testbed::image_io::{ToneMap, linear_to_srgb};

use crate::config::Resolution;
use crate::error::BenchError;
use crate::quality::ReferenceFrame;
use crate::report::plot::draw_labels;

/// A crop window in pixels: x, y, width, height.
pub type Window = [u32; 4];

/// One row of a sheet: a scene's crop per column.
pub struct SheetRow {
    pub scene: String,
    pub camera: String,
    pub resolution: Resolution,
    pub window: Window,
    /// Column label and its crop (all the window's size).
    pub columns: Vec<(String, RgbImage)>,
}

/// Colour of reflector pixels a technique left without data.
pub const HOLE_COLOR: Rgb<u8> = Rgb([255, 0, 255]);
/// Size of a tile on the sheet.
const TILE: (u32, u32) = (320, 180);
const LABEL_H: u32 = 22;
const ROW_LABEL_W: u32 = 200;

/// The window, a quarter of the frame in each direction, that holds the most pixels of
/// `mask` (searched on a grid of an eighth of the window).
pub fn crop_window(mask: &PixelMask) -> Window {
    let (w, h) = (mask.width, mask.height);
    let (cw, ch) = ((w / 4).max(1), (h / 4).max(1));
    // Summed-area table.
    let stride = (w + 1) as usize;
    let mut sat = vec![0u32; stride * (h + 1) as usize];
    for y in 0..h {
        let mut row = 0;
        for x in 0..w {
            row += u32::from(mask.get(x, y));
            sat[(y + 1) as usize * stride + (x + 1) as usize] =
                sat[y as usize * stride + (x + 1) as usize] + row;
        }
    }
    let count = |x: u32, y: u32| {
        let at = |x: u32, y: u32| sat[y as usize * stride + x as usize];
        at(x + cw, y + ch) + at(x, y) - at(x + cw, y) - at(x, y + ch)
    };
    let (sx, sy) = ((cw / 8).max(1), (ch / 8).max(1));
    let mut best = (0, 0, 0);
    let mut y = 0;
    while y + ch <= h {
        let mut x = 0;
        while x + cw <= w {
            let c = count(x, y);
            if c > best.0 {
                best = (c, x, y);
            }
            x += sx;
        }
        y += sy;
    }
    [best.1, best.2, cw, ch]
}

fn srgb8(p: &image::Rgba<f32>, tone_map: ToneMap, scale: f32) -> Rgb<u8> {
    Rgb([0, 1, 2].map(|c| (linear_to_srgb(tone_map.apply(p.0[c]) * scale) * 255.0).round() as u8))
}

fn crop(window: Window, f: impl Fn(u32, u32) -> Rgb<u8>) -> RgbImage {
    let [x0, y0, w, h] = window;
    RgbImage::from_fn(w, h, |x, y| f(x0 + x, y0 + y))
}

/// The scene colour in the window.
pub fn visualize_scene(r: &ReferenceFrame, window: Window, tone_map: ToneMap) -> RgbImage {
    crop(window, |x, y| srgb8(r.color.get_pixel(x, y), tone_map, 1.0))
}

/// The exact reflection on reflector pixels, the scene darkened elsewhere.
pub fn visualize_reference(r: &ReferenceFrame, window: Window, tone_map: ToneMap) -> RgbImage {
    visualize_technique(r, &r.reference, window, tone_map)
}

/// A technique's reflection on measured reflector pixels (holes in magenta), the scene
/// darkened elsewhere.
pub fn visualize_technique(
    r: &ReferenceFrame,
    image: &Rgba32FImage,
    window: Window,
    tone_map: ToneMap,
) -> RgbImage {
    crop(window, |x, y| {
        if !r.measured.get(x, y) {
            return srgb8(r.color.get_pixel(x, y), tone_map, 0.3);
        }
        let p = image.get_pixel(x, y);
        if p.0[3] <= 0.0 { HOLE_COLOR } else { srgb8(p, tone_map, 1.0) }
    })
}

/// Writes the sheet: one row per [`SheetRow`], one tile per column, labelled.
///
/// # Errors
/// The PNG cannot be written.
pub fn write_sheet(path: &Path, rows: &[SheetRow]) -> Result<(), BenchError> {
    let cols = rows.iter().map(|r| r.columns.len()).max().unwrap_or(0) as u32;
    let width = ROW_LABEL_W + cols * (TILE.0 + 4);
    let height = (rows.len() as u32 * (TILE.1 + LABEL_H + 6)).max(1);
    let mut sheet = RgbImage::from_pixel(width.max(1), height, Rgb([255, 255, 255]));
    let mut labels = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        let top = i as u32 * (TILE.1 + LABEL_H + 6);
        labels.push((4, (top + LABEL_H + 8) as i32, row.scene.clone()));
        labels.push((4, (top + LABEL_H + 30) as i32, row.camera.clone()));
        labels.push((4, (top + LABEL_H + 52) as i32, row.resolution.to_string()));
        let [x, y, w, h] = row.window;
        labels.push((4, (top + LABEL_H + 74) as i32, format!("crop {w}x{h}+{x}+{y}")));
        for (k, (label, image)) in row.columns.iter().enumerate() {
            let left = ROW_LABEL_W + k as u32 * (TILE.0 + 4);
            let tile = imageops::resize(image, TILE.0, TILE.1, imageops::FilterType::Nearest);
            imageops::replace(&mut sheet, &tile, i64::from(left), i64::from(top + LABEL_H));
            labels.push((left as i32, (top + 3) as i32, label.clone()));
        }
    }
    draw_labels(&mut sheet, &labels, 15)
        .map_err(|reason| BenchError::Plot { path: path.to_owned(), reason })?;
    sheet.save(path).map_err(|e| BenchError::Plot { path: path.to_owned(), reason: e.to_string() })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crop_finds_the_dense_corner() {
        let mask = PixelMask::from_fn(64, 36, |x, y| x >= 40 && y >= 20);
        let [x, y, w, h] = crop_window(&mask);
        assert_eq!((w, h), (16, 9));
        assert!(x >= 40 && y >= 20, "{x} {y}");
    }
}
