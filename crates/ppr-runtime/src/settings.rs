//! What the user can switch per frame: the reflection pass's steps and the confidence fade.

/// Default [`ReflectionSettings::border_fade`]: off. A fade trades per-frame accuracy for
/// stability in motion (a reflection about to leave the screen fades instead of popping),
/// and how much it costs depends on the fallback it fades to. Measured on the lent H200 at
/// 3840×2160 with the scene's own colour as fallback (`docs/perf/comparison.md`): a fade of
/// 0.1 lowered the on-screen PSNR of the demo's `cam_mirror` from 36.0 to 18.3 dB and of
/// the kitchen's black metal from 39.8 to 27.1 dB. Engines that fade to a good probe may
/// want 0.05–0.1.
pub const DEFAULT_BORDER_FADE: f32 = 0.0;

/// Steps of the reflection pass (seed: `enableHolesFilling`, `enableFiltering`,
/// `enableFilterBleedingReduction`), and how the output's alpha (a confidence) fades. All on
/// by default.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReflectionSettings {
    /// Fill pixels without a reflection from the neighbour with the smallest offset (seed:
    /// `enableHolesFilling`).
    pub holes: bool,
    /// The seed's 6-pixel rule, part of its hole filling (needs `holes`): a pixel that has a
    /// reflection takes a neighbour's instead when the neighbour's offset is more than 6 px
    /// shorter. Off by default: on the lent H200 and the software adapter it lowered the
    /// on-screen PSNR on every camera of the demo and the kitchen but one (kitchen
    /// `view-silver-metal`, 480×270: 26.1 dB raw, 20.2 with the rule, 25.6 without;
    /// `docs/perf/comparison.md`), because a shorter neighbouring offset is as often a
    /// different surface's reflection as the nearer one this pixel missed.
    pub replace_far_reflections: bool,
    /// Sample the colour with the encoded sub-pixel fractions (bilinear).
    pub filtering: bool,
    /// Pull the filtered colour towards the unfiltered one in YCoCg (needs `filtering`).
    /// The luma threshold is relative to the brighter sample (the seed's where that luma
    /// is 1), so linear HDR input gets the same decisions at any exposure: no pre-exposure
    /// is needed.
    pub anti_bleeding: bool,
    /// Water layers: fill reflections missing at the borders by stretching the nearest
    /// valid one along the plane's projected normal (the hash method's edge stretch,
    /// seed 002).
    pub water_edge_stretch: bool,
    /// Width of the confidence fade at the screen borders, as a fraction of the viewport's
    /// shorter side, in `[0, 0.5]` (values outside are clamped; NaN is 0). The output's
    /// alpha is a confidence in `[0, 1]`: 0 where no reflection was found, else falling
    /// linearly from 1 to 0 as the reflected point nears an edge of the screen over this
    /// width (a reflected point about to leave the screen fades instead of popping), never
    /// 0 where a reflection was found. 0 turns the fade off (alpha 1 wherever found, the
    /// seed's output). PPR has no distance limit (every on-screen offset is encoded), so
    /// nothing fades with distance.
    pub border_fade: f32,
    /// At what resolution projection and reflection run ([`ResolutionTier`]); the output
    /// is always full size.
    pub resolution: ResolutionTier,
    /// Blur the reflections of reflectors with roughness by their GGX lobe, over the
    /// footprint their exact reflection distance gives (sharp near contact, spreading far
    /// away). Off: every reflector is a mirror.
    pub glossy: bool,
}

/// The resolution the PPR passes run at. Reduced tiers downsample the depth (a pass of
/// their own), run clear, projection and reflection at half or a quarter of the size in
/// each direction (the reflection samples the full-size colour), and upsample the reflection to the output, edge-aware (a
/// sample only blends into output pixels whose surface lies within 2 % of its own camera
/// distance). Normal maps are not applied in reduced tiers. The frame plan is built for
/// the reduced viewport (`FramePlan::viewport` is the reduced size).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ResolutionTier {
    /// Every pixel (the seed).
    #[default]
    Full,
    /// Half the width and height: a quarter of the pixels.
    Half,
    /// A quarter of the width and height: a sixteenth of the pixels.
    Quarter,
}

impl ResolutionTier {
    /// How many output pixels a reduced pixel spans in each direction.
    pub fn divisor(self) -> u32 {
        match self {
            Self::Full => 1,
            Self::Half => 2,
            Self::Quarter => 4,
        }
    }

    /// The size the passes run at for a full-size viewport (each side rounded up, never 0).
    pub fn reduced(self, [w, h]: [u32; 2]) -> [u32; 2] {
        let d = self.divisor();
        [w.div_ceil(d).max(1), h.div_ceil(d).max(1)]
    }
}

impl Default for ReflectionSettings {
    fn default() -> Self {
        Self::ALL
    }
}

impl ReflectionSettings {
    /// Every step on: the seed's final image (the border fade at its default, off).
    pub const ALL: Self = Self {
        holes: true,
        replace_far_reflections: false,
        filtering: true,
        anti_bleeding: true,
        water_edge_stretch: true,
        border_fade: DEFAULT_BORDER_FADE,
        resolution: ResolutionTier::Full,
        glossy: true,
    };
    /// Every step off: raw decoded pixel data (alpha 1 wherever found: no fade).
    pub const RAW: Self = Self {
        holes: false,
        replace_far_reflections: false,
        filtering: false,
        anti_bleeding: false,
        water_edge_stretch: false,
        border_fade: 0.0,
        resolution: ResolutionTier::Full,
        glossy: false,
    };

    /// The settings as shader flags.
    pub fn flags(&self) -> u32 {
        use crate::gpu_types::*;
        (if self.holes { FLAG_HOLES } else { 0 })
            | (if self.filtering { FLAG_FILTERING } else { 0 })
            | (if self.anti_bleeding { FLAG_ANTI_BLEEDING } else { 0 })
            | (if self.water_edge_stretch { FLAG_WATER_STRETCH } else { 0 })
            | (if self.holes && self.replace_far_reflections { FLAG_REPLACE_FAR } else { 0 })
    }

    /// The border fade's width in pixels for a viewport (0 when off).
    pub fn border_fade_px(&self, [width, height]: [u32; 2]) -> f32 {
        let fade = if self.border_fade.is_nan() { 0.0 } else { self.border_fade.clamp(0.0, 0.5) };
        fade * width.min(height) as f32
    }
}

/// How the projection pass writes the intermediate buffer. Only [`WriteMode::AtomicMin`]
/// is correct; the others exist to show the artefact the seed's flowerpot slide shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum WriteMode {
    /// `atomicMin`: the smallest offset, i.e. the closest reflected surface, wins.
    #[default]
    AtomicMin,
    /// Plain stores: whichever write the GPU schedules last wins.
    LastWriter,
    /// `atomicMax`: the worst case of an unordered write, the farthest surface wins.
    AtomicMax,
}

impl WriteMode {
    /// The mode as shader flag bits.
    pub fn flags(self) -> u32 {
        use crate::gpu_types::{FLAG_WRITE_LAST, FLAG_WRITE_MAX};
        match self {
            Self::AtomicMin => 0,
            Self::LastWriter => FLAG_WRITE_LAST,
            Self::AtomicMax => FLAG_WRITE_MAX,
        }
    }
}
