//! What the user can switch per frame: the reflection pass's three steps.

/// Steps of the reflection pass (seed: `enableHolesFilling`, `enableFiltering`,
/// `enableFilterBleedingReduction`). All on by default.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ReflectionSettings {
    /// Fill holes from the neighbour with the smallest offset (the 6-pixel rule).
    pub holes: bool,
    /// Sample the colour with the encoded sub-pixel fractions (bilinear).
    pub filtering: bool,
    /// Pull the filtered colour towards the unfiltered one in YCoCg (needs `filtering`).
    pub anti_bleeding: bool,
}

impl Default for ReflectionSettings {
    fn default() -> Self {
        Self::ALL
    }
}

impl ReflectionSettings {
    /// Every step on: the seed's final image.
    pub const ALL: Self = Self { holes: true, filtering: true, anti_bleeding: true };
    /// Every step off: raw decoded pixel data.
    pub const RAW: Self = Self { holes: false, filtering: false, anti_bleeding: false };

    /// The settings as shader flags.
    pub fn flags(&self) -> u32 {
        use crate::gpu_types::*;
        (if self.holes { FLAG_HOLES } else { 0 })
            | (if self.filtering { FLAG_FILTERING } else { 0 })
            | (if self.anti_bleeding { FLAG_ANTI_BLEEDING } else { 0 })
    }
}
