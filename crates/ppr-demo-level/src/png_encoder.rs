//! The textures' PNG files, written by the `image` crate's encoder with fixed settings
//! (best compression, adaptive filtering), so that the same pixels give the same bytes on
//! every run. A future `image`/`png` version may compress differently: then the committed
//! `.glb` changes once, which `committed_assets_equal_a_fresh_run` reports.

use image::ImageEncoder;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};

pub use image::RgbImage;

/// `image` as a PNG file.
pub fn png_bytes(image: &RgbImage) -> Vec<u8> {
    let mut png = Vec::new();
    PngEncoder::new_with_quality(&mut png, CompressionType::Best, FilterType::Adaptive)
        .write_image(image.as_raw(), image.width(), image.height(), image::ExtendedColorType::Rgb8)
        .expect("encoding an RGB8 image into memory cannot fail");
    png
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_png_decodes_to_the_same_pixels() {
        let image = RgbImage::from_fn(4, 3, |x, y| image::Rgb([x as u8, y as u8, 7]));
        let png = png_bytes(&image);
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        let decoded = image::load_from_memory_with_format(&png, image::ImageFormat::Png).expect("decodes");
        assert_eq!(decoded.to_rgb8(), image);
        assert_eq!(png_bytes(&image), png, "the same bytes every time");
    }
}
