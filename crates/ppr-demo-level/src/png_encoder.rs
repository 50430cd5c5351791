//! A minimal PNG writer (8-bit RGB, uncompressed deflate blocks) whose bytes never change.
//!
//! A general encoder may pick other compression settings in a later version, which would
//! change the committed `.glb`; stored blocks are trivially stable and still small enough
//! for two 128 × 128 textures.

/// An 8-bit RGB image, rows top to bottom, `3 * width * height` bytes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RgbImage {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<u8>,
}

impl RgbImage {
    /// An image of `width × height` pixels whose colour is `colour_at(x, y)`.
    pub fn from_fn(width: u32, height: u32, mut colour_at: impl FnMut(u32, u32) -> [u8; 3]) -> Self {
        let mut pixels = Vec::with_capacity(3 * width as usize * height as usize);
        for y in 0..height {
            for x in 0..width {
                pixels.extend_from_slice(&colour_at(x, y));
            }
        }
        Self { width, height, pixels }
    }

    /// The image as a PNG file.
    pub fn to_png(&self) -> Vec<u8> {
        let row_bytes = 3 * self.width as usize;
        // Every scanline starts with its filter type (0: none).
        let mut raw = Vec::with_capacity((row_bytes + 1) * self.height as usize);
        for row in self.pixels.chunks_exact(row_bytes) {
            raw.push(0);
            raw.extend_from_slice(row);
        }

        let mut header = Vec::with_capacity(13);
        header.extend_from_slice(&self.width.to_be_bytes());
        header.extend_from_slice(&self.height.to_be_bytes());
        // Bit depth 8, colour type 2 (RGB), deflate, adaptive filtering, no interlace.
        header.extend_from_slice(&[8, 2, 0, 0, 0]);

        let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
        write_chunk(&mut png, b"IHDR", &header);
        write_chunk(&mut png, b"IDAT", &zlib_stored(&raw));
        write_chunk(&mut png, b"IEND", &[]);
        png
    }
}

fn write_chunk(png: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
    let length = u32::try_from(data.len()).expect("PNG chunks of the demo textures are small");
    png.extend_from_slice(&length.to_be_bytes());
    let crc_start = png.len();
    png.extend_from_slice(kind);
    png.extend_from_slice(data);
    let crc = crc32(&png[crc_start..]);
    png.extend_from_slice(&crc.to_be_bytes());
}

/// A zlib stream of stored (uncompressed) deflate blocks.
fn zlib_stored(data: &[u8]) -> Vec<u8> {
    const MAX_BLOCK: usize = 65_535;
    // CMF: deflate, 32 KiB window; FLG: no dictionary, check bits so that CMF·256+FLG ≡ 0 (mod 31).
    let mut out = vec![0x78, 0x01];
    let mut blocks = data.chunks(MAX_BLOCK).peekable();
    if blocks.peek().is_none() {
        out.extend_from_slice(&[1, 0, 0, 0xff, 0xff]);
    }
    while let Some(block) = blocks.next() {
        let is_last = blocks.peek().is_none();
        out.push(u8::from(is_last));
        let length = u16::try_from(block.len()).expect("blocks are at most 65535 bytes");
        out.extend_from_slice(&length.to_le_bytes());
        out.extend_from_slice(&(!length).to_le_bytes());
        out.extend_from_slice(block);
    }
    out.extend_from_slice(&adler32(data).to_be_bytes());
    out
}

fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = 0xffff_ffffu32;
    for &byte in bytes {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            let mask = (crc & 1).wrapping_neg();
            crc = (crc >> 1) ^ (0xedb8_8320 & mask);
        }
    }
    !crc
}

fn adler32(bytes: &[u8]) -> u32 {
    let (mut a, mut b) = (1u32, 0u32);
    for &byte in bytes {
        a = (a + u32::from(byte)) % 65_521;
        b = (b + a) % 65_521;
    }
    (b << 16) | a
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checksums_match_known_values() {
        assert_eq!(crc32(b"123456789"), 0xcbf4_3926);
        assert_eq!(adler32(b"Wikipedia"), 0x11e6_0398);
    }

    #[test]
    fn png_has_signature_and_expected_size() {
        let image = RgbImage::from_fn(4, 3, |x, y| [x as u8, y as u8, 7]);
        let png = image.to_png();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        // signature + IHDR (25) + IDAT (12 + 2 + 5 + 3·13 + 4) + IEND (12)
        assert_eq!(png.len(), 8 + 25 + 12 + 2 + 5 + 39 + 4 + 12);
    }
}
