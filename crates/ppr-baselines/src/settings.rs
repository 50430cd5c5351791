//! User-facing parameters of the baselines, with presets; each becomes a flat GPU uniform
//! (`gpu_types`) when a frame is prepared.

use crate::gpu_types::{GlossyBlurUniform, HiZUniform, SsprUniform, SsrUniform};

/// Longest reflection ray of the ray-marched techniques by default, metres (the march is
/// clipped to the screen long before on any level of room or street scale).
pub const DEFAULT_MAX_DISTANCE: f32 = 1000.0;

/// How [`crate::SsrTechnique`] marches its rays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SsrSettings {
    /// Pixels per step along the ray's major screen axis: 1 visits every pixel (brute
    /// force), 64 is the PPR talk's low-quality SSR. At least 1.
    pub stride: u32,
    /// Most steps per ray; 0 marches until the ray leaves the screen (at most the screen
    /// diagonal over `stride`).
    pub max_steps: u32,
    /// Bisection steps after a coarse hit: 0 with `stride` 1; `log2(stride)` reaches one
    /// pixel.
    pub refine_steps: u32,
    /// Thickness assumed behind every depth sample, metres of view depth: a ray hits a
    /// pixel when its depth over the pixel reaches behind the surface by at most this.
    /// Larger values close gaps at grazing angles and make rays stop behind thin objects.
    /// Room-scale scenes: 0.1 to 1.
    pub thickness: f32,
    /// Longest reflection ray, metres.
    pub max_distance: f32,
}

impl SsrSettings {
    /// Brute-force SSR at pixel granularity [McGuire14]: one-pixel steps up to the screen
    /// diagonal, no refinement needed.
    pub const fn brute_force() -> Self {
        Self { stride: 1, max_steps: 0, refine_steps: 0, thickness: 0.3, max_distance: DEFAULT_MAX_DISTANCE }
    }

    /// Low-quality SSR as in the PPR talk's comparison: 64-pixel steps, then 6 bisection
    /// steps (64 → 1 pixel).
    pub const fn low_quality() -> Self {
        Self { stride: 64, refine_steps: 6, ..Self::brute_force() }
    }

    /// Every preset with its name, for benches and tests.
    pub const fn presets() -> [(&'static str, Self); 2] {
        [("brute force", Self::brute_force()), ("low quality", Self::low_quality())]
    }

    /// The GPU uniform.
    pub fn uniform(&self) -> SsrUniform {
        SsrUniform {
            stride: self.stride.max(1) as f32,
            max_steps: self.max_steps,
            refine_steps: self.refine_steps,
            thickness: self.thickness,
            max_distance: self.max_distance,
            _pad: [0; 3],
        }
    }
}

impl Default for SsrSettings {
    fn default() -> Self {
        Self::brute_force()
    }
}

/// How [`crate::SsrGlossyTechnique`] marches and blurs (the glossy SSR of the kind Bevy
/// and Godot ship: a sharp march, then a blur sized by roughness and hit distance).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SsrGlossySettings {
    /// The march.
    pub march: SsrSettings,
    /// Blur radius at the hit in units of `alpha × hit distance` (alpha = roughness²; the
    /// Gaussian weights put its standard deviation at half the radius): 4 measured closest
    /// to the exact glossy reference on the testbed's rough floor; 0 turns the blur off.
    /// 2 to 8.
    pub spread: f32,
    /// Largest blur radius, pixels (the cost bound). 8 to 64.
    pub max_radius: f32,
    /// Gather taps per pixel besides the centre. 8 to 64.
    pub samples: u32,
}

impl SsrGlossySettings {
    /// Low-quality SSR's march (64-pixel steps, 6 bisections) with a 24-tap blur.
    pub const fn low_quality() -> Self {
        Self { march: SsrSettings::low_quality(), spread: 4.0, max_radius: 32.0, samples: 24 }
    }

    /// Brute-force SSR's march with the same blur.
    pub const fn brute_force() -> Self {
        Self { march: SsrSettings::brute_force(), ..Self::low_quality() }
    }

    /// Every preset with its name, for benches and tests.
    pub const fn presets() -> [(&'static str, Self); 2] {
        [("low quality", Self::low_quality()), ("brute force", Self::brute_force())]
    }

    /// The blur's GPU uniform.
    pub fn blur_uniform(&self) -> GlossyBlurUniform {
        GlossyBlurUniform {
            spread: self.spread.max(0.0),
            max_radius: self.max_radius.max(0.0),
            samples: self.samples,
            _pad: 0,
        }
    }
}

impl Default for SsrGlossySettings {
    fn default() -> Self {
        Self::low_quality()
    }
}

/// How [`crate::HiZSsrTechnique`] walks the min-depth pyramid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HiZSettings {
    /// Most cell visits per ray (a ray that has not converged by then finds nothing).
    /// 64 to 512.
    pub max_iterations: u32,
    /// Highest pyramid level the walk climbs to (clamped to the pyramid); level `l` cells
    /// are `2^l` pixels wide.
    pub top_level: u32,
    /// A hit further behind the surface than this (metres of view depth) is rejected;
    /// `None` accepts every hit, as the implementation the PPR talk measured (no tracing
    /// behind geometry).
    pub thickness: Option<f32>,
    /// Longest reflection ray, metres.
    pub max_distance: f32,
}

impl HiZSettings {
    /// Hi-Z SSR as in the PPR talk's comparison [Uludag14]: no tracing behind geometry.
    pub const fn seed() -> Self {
        Self { max_iterations: 256, top_level: 16, thickness: None, max_distance: DEFAULT_MAX_DISTANCE }
    }

    /// Every preset with its name.
    pub const fn presets() -> [(&'static str, Self); 1] {
        [("no tracing behind geometry", Self::seed())]
    }

    /// The GPU uniform for a pyramid of `levels` levels (≥ 1).
    pub fn uniform(&self, levels: u32) -> HiZUniform {
        HiZUniform {
            max_iterations: self.max_iterations,
            top_level: self.top_level.min(levels.saturating_sub(1)),
            thickness: self.thickness.unwrap_or(f32::MAX),
            max_distance: self.max_distance,
        }
    }
}

impl Default for HiZSettings {
    fn default() -> Self {
        Self::seed()
    }
}

/// The SSPR edge stretch (seed 002): the projected position's x is scaled away from the
/// screen centre by `1 + height · angle · screen · intensity`, with `height` the source
/// pixel's distance above the plane (metres), `angle` = `saturate(-forward · normal)` and
/// `screen` = `saturate(|ndc x| − threshold)`. (The seed scales the UV's x; scaling NDC x
/// stretches towards both edges.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeStretch {
    /// |NDC x| in `[0, 1)` where the stretch starts.
    pub threshold: f32,
    /// Stretch per metre of height, 0.1 to 2.
    pub intensity: f32,
}

impl Default for EdgeStretch {
    fn default() -> Self {
        Self { threshold: 0.2, intensity: 0.5 }
    }
}

/// How [`crate::SsprTechnique`] projects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SsprSettings {
    /// Stretch towards the left and right edges; `None` projects exactly.
    pub edge_stretch: Option<EdgeStretch>,
    /// Most planes with a hash layer per frame (the visible planes in set order; the seed
    /// keeps the N most present). Each layer is 4 bytes per pixel.
    pub max_layers: u32,
}

impl SsprSettings {
    /// The projection hash as published, without the edge stretch.
    pub const fn seed() -> Self {
        Self { edge_stretch: None, max_layers: 4 }
    }

    /// With the edge stretch at its default parameters.
    pub fn with_edge_stretch() -> Self {
        Self { edge_stretch: Some(EdgeStretch::default()), ..Self::seed() }
    }

    /// Every preset with its name.
    pub fn presets() -> [(&'static str, Self); 2] {
        [("hash", Self::seed()), ("hash + edge stretch", Self::with_edge_stretch())]
    }

    /// The GPU uniform.
    pub fn uniform(&self) -> SsprUniform {
        let s = self.edge_stretch;
        SsprUniform {
            stretch: u32::from(s.is_some()),
            stretch_threshold: s.map_or(0.0, |s| s.threshold),
            stretch_intensity: s.map_or(0.0, |s| s.intensity),
            _pad: 0,
        }
    }
}

impl Default for SsprSettings {
    fn default() -> Self {
        Self::seed()
    }
}
