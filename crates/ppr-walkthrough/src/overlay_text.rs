//! The on-screen text as an image: coloured lines in the 5 × 7 font on a translucent box,
//! rasterised on the CPU (only when the text changes) and drawn by `OverlayPass`.

use crate::bitmap_font::{GLYPH_HEIGHT, GLYPH_WIDTH, pixel};

/// Font pixels from one character cell to the next (glyph plus one column of space).
const CELL_WIDTH: u32 = GLYPH_WIDTH + 1;
/// Font pixels from one line to the next.
const LINE_HEIGHT: u32 = GLYPH_HEIGHT + 3;
/// Font pixels of margin inside the box.
const PADDING: u32 = 2;

/// Colours of the text (sRGB, straight alpha).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextColour {
    Normal,
    Dim,
    Good,
    Warning,
    Error,
}

impl TextColour {
    fn rgba(self) -> [u8; 4] {
        match self {
            Self::Normal => [235, 235, 235, 255],
            Self::Dim => [160, 170, 180, 255],
            Self::Good => [140, 230, 140, 255],
            Self::Warning => [250, 210, 90, 255],
            Self::Error => [255, 110, 100, 255],
        }
    }
}

/// One line of text and its colour.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TextLine {
    pub text: String,
    pub colour: TextColour,
}

impl TextLine {
    pub fn new(text: impl Into<String>, colour: TextColour) -> Self {
        Self { text: text.into(), colour }
    }
}

/// The text rasterised: sRGB RGBA8 with straight alpha, row-major, no padding.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TextImage {
    pub width: u32,
    pub height: u32,
    pub rgba8: Vec<u8>,
}

/// Pixels per font pixel for a window of this width (2 from 800 px on).
pub fn scale_for_width(window_width: u32) -> u32 {
    if window_width >= 800 { 2 } else { 1 }
}

/// Splits lines longer than `columns` characters (at spaces where possible).
pub fn wrap(lines: &[TextLine], columns: usize) -> Vec<TextLine> {
    let columns = columns.max(8);
    let mut out = Vec::new();
    for line in lines {
        let mut rest: &str = &line.text;
        while rest.chars().count() > columns {
            let cut = rest.char_indices().nth(columns).map_or(rest.len(), |(i, _)| i);
            let split = rest[..cut].rfind(' ').filter(|&i| i > cut / 2).unwrap_or(cut);
            out.push(TextLine::new(rest[..split].trim_end(), line.colour));
            rest = rest[split..].trim_start();
        }
        out.push(TextLine::new(rest, line.colour));
    }
    out
}

/// Rasterises `lines` at `scale` screen pixels per font pixel, wrapped to fit `max_width`.
pub fn rasterise(lines: &[TextLine], scale: u32, max_width: u32) -> TextImage {
    let scale = scale.max(1);
    let columns = (max_width / scale).saturating_sub(2 * PADDING) / CELL_WIDTH;
    let lines = wrap(lines, columns as usize);
    let longest = lines.iter().map(|l| l.text.chars().count() as u32).max().unwrap_or(0);
    let width = (longest * CELL_WIDTH + 2 * PADDING) * scale;
    let height = (lines.len() as u32 * LINE_HEIGHT + 2 * PADDING) * scale;
    let mut rgba8 = [0u8, 0, 0, 150].repeat((width * height) as usize);
    for (row, line) in lines.iter().enumerate() {
        let colour = line.colour.rgba();
        for (col, c) in line.text.chars().enumerate() {
            let x0 = PADDING + col as u32 * CELL_WIDTH;
            let y0 = PADDING + row as u32 * LINE_HEIGHT + 1;
            for (gx, gy) in (0..GLYPH_HEIGHT).flat_map(|y| (0..GLYPH_WIDTH).map(move |x| (x, y))) {
                if !pixel(c, gx, gy) {
                    continue;
                }
                for (sx, sy) in (0..scale).flat_map(|y| (0..scale).map(move |x| (x, y))) {
                    let (x, y) = ((x0 + gx) * scale + sx, (y0 + gy) * scale + sy);
                    let i = ((y * width + x) * 4) as usize;
                    rgba8[i..i + 4].copy_from_slice(&colour);
                }
            }
        }
    }
    TextImage { width, height, rgba8 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wraps_at_spaces_and_keeps_colour() {
        let lines = [TextLine::new("alpha beta gamma delta", TextColour::Error)];
        let wrapped = wrap(&lines, 12);
        let texts: Vec<&str> = wrapped.iter().map(|l| l.text.as_str()).collect();
        assert_eq!(texts, ["alpha beta", "gamma delta"]);
        assert!(wrapped.iter().all(|l| l.colour == TextColour::Error));
        let long = [TextLine::new("x".repeat(25), TextColour::Normal)];
        assert_eq!(wrap(&long, 10).len(), 3, "a word longer than a line is cut");
    }

    #[test]
    fn rasterises_glyphs_in_the_line_colour_on_a_translucent_box() {
        let image = rasterise(&[TextLine::new("I", TextColour::Good)], 2, 1000);
        assert_eq!(
            (image.width, image.height),
            ((CELL_WIDTH + 2 * PADDING) * 2, (LINE_HEIGHT + 2 * PADDING) * 2)
        );
        let at = |x: u32, y: u32| &image.rgba8[((y * image.width + x) * 4) as usize..][..4];
        assert_eq!(at(0, 0), [0, 0, 0, 150]);
        // 'I' has its top bar from x = 1 to 3 on row 0 of the glyph.
        let (x, y) = ((PADDING + 2) * 2, (PADDING + 1) * 2);
        assert_eq!(at(x, y), TextColour::Good.rgba());
        assert_eq!(at(x + 1, y + 1), TextColour::Good.rgba(), "each font pixel is scale × scale");
    }
}
