//! A per-pixel selection (which pixels a metric or a difference image looks at).

/// A boolean per pixel, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PixelMask {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` flags.
    pub bits: Vec<bool>,
}

impl PixelMask {
    /// Every pixel selected.
    pub fn all(width: u32, height: u32) -> Self {
        Self { width, height, bits: vec![true; (width * height) as usize] }
    }

    /// Pixels where `f(x, y)` is true.
    pub fn from_fn(width: u32, height: u32, mut f: impl FnMut(u32, u32) -> bool) -> Self {
        let bits = (0..height).flat_map(|y| (0..width).map(move |x| (x, y))).map(|(x, y)| f(x, y)).collect();
        Self { width, height, bits }
    }

    /// Whether pixel `(x, y)` is selected (false outside the image).
    pub fn get(&self, x: u32, y: u32) -> bool {
        x < self.width && y < self.height && self.bits[(y * self.width + x) as usize]
    }

    /// Number of selected pixels.
    pub fn count(&self) -> usize {
        self.bits.iter().filter(|&&b| b).count()
    }

    /// Pixels selected in both masks.
    ///
    /// # Panics
    /// If the sizes differ.
    pub fn and(&self, other: &Self) -> Self {
        assert_eq!((self.width, self.height), (other.width, other.height), "mask sizes differ");
        let bits = self.bits.iter().zip(&other.bits).map(|(a, b)| *a && *b).collect();
        Self { width: self.width, height: self.height, bits }
    }
}
