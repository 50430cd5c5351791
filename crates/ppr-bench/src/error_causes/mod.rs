//! Where full PPR's error comes from (issue 14): every reflector pixel the exact reference
//! classes gets exactly one cause, and its squared error (as `compare` scores it: the
//! reflection over the scene-colour fallback by its alpha, tonemapped) goes to that cause.
//!
//! Pixels whose reflected point no screen-space method can see (the reference's off-screen
//! and background classes, scored by `psnr_off`) are split by where that point is:
//!
//! - [`Cause::Hidden`]: it projects inside the viewport, in front of the camera, but the
//!   main view shows another surface there (occluded in the main depth buffer);
//! - [`Cause::OffView`]: it projects outside the viewport or behind the camera;
//! - [`Cause::Background`]: the reflection shows the background (no geometry).
//!
//! Pixels whose reflected point is on screen (scored by `psnr_on`) take the first cause
//! that applies, in this order, from four untimed renders of the same frame (raw PPR,
//! PPR with hole filling, full PPR without the border fade, full PPR) and raw PPR's
//! intermediate buffer (which source pixel each pixel's reflection came from):
//!
//! 1. [`Cause::OutsideRect`]: the pixel's surface point lies outside its fitted rectangle
//!    (the G-buffer's reflector mask grows each rectangle by a depth tolerance; PPR's
//!    pyramid test does not), so PPR cannot reflect there.
//! 2. [`Cause::Fade`]: the border fade (`ReflectionSettings::border_fade`) costs more than
//!    half of the pixel's error (full PPR against full PPR without the fade).
//! 3. [`Cause::ParallelRule`]: raw PPR with the plan's parallel-shape rule has no data or
//!    the wrong source where raw PPR without it has the right one. The plan enables the
//!    rule only when asked (`PlanParams::parallel_rule`, never by `Auto`), so in `compare`
//!    this cause is always empty and its render is skipped.
//! 4. [`Cause::HoleFilled`]: raw PPR had no data (or hole filling's replace-far rule
//!    replaced it) and hole filling supplied the colour.
//! 5. [`Cause::HoleLeft`]: no data even after hole filling: the pixel shows the fallback.
//! 6. [`Cause::WrongSource`]: raw PPR's reflection came from a source pixel more than one
//!    pixel (Chebyshev) from where the exact reflected point projects: an occluder missed
//!    or a wrong surface won `atomicMin`. (Glass and water pixels are reflected through
//!    layers whose sources the main buffer does not hold; they skip this test.)
//! 7. [`Cause::Filtered`]: filtering and anti-bleeding raised the pixel's error by more
//!    than half of its final error (full PPR without the fade against PPR with holes).
//!    Where filtering lowered the error, what remains is the earlier cause's.
//! 8. [`Cause::Residual`]: the right source, unchanged by the later steps: what is left is
//!    sampling (the source pixel's colour at its centre, sub-pixel offsets) and shading
//!    that differs between the main and the mirrored view.

pub mod scene_frame;
pub mod variants;

use glam::{DVec3, IVec2, Vec4};
use image::Rgba32FImage;
use ppr_format::{ReflectorKind, ReflectorSet};
use ppr_runtime::Camera;
use ppr_testbed::image_io::{ToneMap, tonemapped};
use ppr_testbed::{FrameImages, ReflectedPointClass};

use crate::config::Resolution;
use crate::error::BenchError;
use crate::quality::over_fallback;
pub use variants::{CauseRunner, PprVariants};

/// Which score a cause's pixels count in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Group {
    /// Reflected point on screen: `psnr_on`.
    OnScreen,
    /// Reflected point off screen, hidden or background: `psnr_off`.
    OffScreen,
}

impl Group {
    pub fn as_str(self) -> &'static str {
        match self {
            Self::OnScreen => "on screen",
            Self::OffScreen => "off screen",
        }
    }
}

/// Why a reflector pixel's reflection differs from the exact one (see the module docs for
/// the order in which they are tested).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Cause {
    Hidden,
    OffView,
    Background,
    OutsideRect,
    Fade,
    ParallelRule,
    HoleFilled,
    HoleLeft,
    WrongSource,
    Filtered,
    Residual,
}

impl Cause {
    /// Number of causes.
    pub const COUNT: usize = 11;
    /// Every cause, off-screen ones first, in report order.
    pub const ALL: [Cause; Self::COUNT] = [
        Self::Hidden,
        Self::OffView,
        Self::Background,
        Self::OutsideRect,
        Self::Fade,
        Self::ParallelRule,
        Self::HoleFilled,
        Self::HoleLeft,
        Self::WrongSource,
        Self::Filtered,
        Self::Residual,
    ];

    /// Short name (CSV, tables).
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Hidden => "hidden in the main view",
            Self::OffView => "outside the view",
            Self::Background => "background",
            Self::OutsideRect => "outside the fitted rectangle",
            Self::Fade => "border fade",
            Self::ParallelRule => "parallel rule",
            Self::HoleFilled => "hole filled",
            Self::HoleLeft => "hole left (no data)",
            Self::WrongSource => "wrong source (occluder missed)",
            Self::Filtered => "filtered",
            Self::Residual => "right source (sampling, shading)",
        }
    }

    /// The score its pixels count in.
    pub fn group(self) -> Group {
        match self {
            Self::Hidden | Self::OffView | Self::Background => Group::OffScreen,
            _ => Group::OnScreen,
        }
    }

    fn index(self) -> usize {
        Self::ALL.iter().position(|c| *c == self).expect("every cause is in ALL")
    }
}

/// Pixels and squared error per cause of one frame (or pooled over several).
///
/// Invariant: each measured reflector pixel is counted under exactly one cause, so the
/// pixels of a group's causes add up to the group's pixels and their errors to its error.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ErrorBreakdown {
    /// Pixels per cause, in [`Cause::ALL`] order.
    pub pixels: [usize; Cause::COUNT],
    /// Squared error per cause (summed over pixels and the three tonemapped channels), in
    /// [`Cause::ALL`] order.
    pub squared_error: [f64; Cause::COUNT],
    /// Whether the plan had the parallel-shape rule on (in any pooled frame).
    pub parallel_rule: bool,
}

impl ErrorBreakdown {
    /// Pixels of `cause`.
    pub fn pixels_of(&self, cause: Cause) -> usize {
        self.pixels[cause.index()]
    }

    /// Squared error of `cause`.
    pub fn error_of(&self, cause: Cause) -> f64 {
        self.squared_error[cause.index()]
    }

    /// Pixels of a group.
    pub fn group_pixels(&self, group: Group) -> usize {
        Cause::ALL.iter().filter(|c| c.group() == group).map(|c| self.pixels_of(*c)).sum()
    }

    /// Squared error of a group.
    pub fn group_error(&self, group: Group) -> f64 {
        Cause::ALL.iter().filter(|c| c.group() == group).map(|c| self.error_of(*c)).sum()
    }

    /// `cause`'s share of its group's pixels (0 for an empty group).
    pub fn pixel_share(&self, cause: Cause) -> f64 {
        let n = self.group_pixels(cause.group());
        if n == 0 { 0.0 } else { self.pixels_of(cause) as f64 / n as f64 }
    }

    /// `cause`'s share of its group's squared error (0 when the group has none).
    pub fn error_share(&self, cause: Cause) -> f64 {
        let e = self.group_error(cause.group());
        if e == 0.0 { 0.0 } else { self.error_of(cause) / e }
    }

    /// The group's PSNR (as `psnr_on` / `psnr_off` for one frame; pooled over frames, the
    /// PSNR of their pooled mean squared error).
    pub fn psnr(&self, group: Group) -> f64 {
        psnr_of(self.group_error(group), self.group_pixels(group))
    }

    /// The group's PSNR if `cause`'s error were removed (its pixels exact).
    pub fn psnr_without(&self, cause: Cause) -> f64 {
        let g = cause.group();
        psnr_of((self.group_error(g) - self.error_of(cause)).max(0.0), self.group_pixels(g))
    }

    /// Adds another frame's pixels and errors (pooling over cameras).
    pub fn add(&mut self, other: &Self) {
        for i in 0..Cause::COUNT {
            self.pixels[i] += other.pixels[i];
            self.squared_error[i] += other.squared_error[i];
        }
        self.parallel_rule |= other.parallel_rule;
    }

    fn count(&mut self, cause: Cause, error: f64) {
        self.pixels[cause.index()] += 1;
        self.squared_error[cause.index()] += error;
    }
}

fn psnr_of(error: f64, pixels: usize) -> f64 {
    let mse = if pixels == 0 { 0.0 } else { error / (3 * pixels) as f64 };
    if mse == 0.0 { f64::INFINITY } else { -10.0 * mse.log10() }
}

/// One breakdown of a `compare` run (one camera, size and full-PPR technique).
#[derive(Clone, Debug, PartialEq)]
pub struct CauseRow {
    pub scene: String,
    pub camera: String,
    pub resolution: Resolution,
    /// The full-PPR technique's label.
    pub technique: String,
    pub breakdown: ErrorBreakdown,
}

/// The frame a breakdown is computed for.
pub struct CauseFrame<'a> {
    /// The G-buffer and the exact reference as read back.
    pub images: &'a FrameImages,
    pub camera: &'a Camera,
    pub reflectors: &'a ReflectorSet,
    pub tone_map: ToneMap,
}

/// A share of more than this of a pixel's final error makes the fade or the filter its
/// cause.
const DOMINANT: f64 = 0.5;

/// Attributes every measured reflector pixel of `frame` to one cause.
///
/// # Errors
/// Image sizes differ.
pub fn classify(frame: &CauseFrame<'_>, v: &PprVariants) -> Result<ErrorBreakdown, BenchError> {
    let images = frame.images;
    let fallback = &images.color;
    let [w, h] = images.size();
    let shown = |img: &Rgba32FImage| over_fallback(img, fallback);
    let (raw, holes, unfaded, full) = (shown(&v.raw)?, shown(&v.holes)?, shown(&v.unfaded)?, shown(&v.full)?);
    let reference = &images.reference;
    let tm = frame.tone_map;
    let error = |img: &Rgba32FImage, x: u32, y: u32| {
        let (a, b) = (tonemapped(reference, x, y, tm), tonemapped(img, x, y, tm));
        (0..3).map(|c| (f64::from(a[c]) - f64::from(b[c])).powi(2)).sum::<f64>()
    };
    let projector = Projector::new(frame.camera, [w, h]);
    let mut out = ErrorBreakdown { parallel_rule: v.parallel_rule, ..ErrorBreakdown::default() };
    for y in 0..h {
        for x in 0..w {
            let class = images.class(x, y);
            if class == ReflectedPointClass::NotReflector {
                continue;
            }
            let e = error(&full, x, y);
            let i = (y * w + x) as usize;
            let point = images.reference_position.get_pixel(x, y).0;
            let reflected = projector.pixel_of(Vec4::from(point).truncate());
            let cause = match class {
                ReflectedPointClass::Background => Cause::Background,
                ReflectedPointClass::OffScreen if reflected.is_some() => Cause::Hidden,
                ReflectedPointClass::OffScreen => Cause::OffView,
                _ => {
                    let id = images.reflector_id.get(x, y) as usize;
                    let reflector = id.checked_sub(1).and_then(|k| frame.reflectors.reflectors.get(k));
                    let surface = projector.world_of([x, y], images.depth[i]);
                    let right_source =
                        |sources: &[Option<IVec2>]| match (sources.get(i).copied().flatten(), reflected) {
                            (Some(s), Some(r)) => (s - r).abs().max_element() <= 1,
                            _ => false,
                        };
                    let layered = reflector.is_some_and(|r| r.kind != ReflectorKind::Opaque);
                    let raw_has = alpha(&raw, x, y) > 0.0;
                    if reflector.is_none_or(|r| !r.contains_projection(surface, 0.0)) {
                        Cause::OutsideRect
                    } else if e > 0.0 && e - error(&unfaded, x, y) > DOMINANT * e {
                        Cause::Fade
                    } else if v.without_rule.as_ref().is_some_and(|(img, src)| {
                        !layered
                            && alpha(img, x, y) > 0.0
                            && right_source(src)
                            && !(raw_has && right_source(&v.raw_sources))
                    }) {
                        Cause::ParallelRule
                    } else if !raw_has || holes.get_pixel(x, y) != raw.get_pixel(x, y) {
                        if alpha(&full, x, y) > 0.0 { Cause::HoleFilled } else { Cause::HoleLeft }
                    } else if !layered && !right_source(&v.raw_sources) {
                        Cause::WrongSource
                    } else if error(&unfaded, x, y) - error(&holes, x, y) > DOMINANT * e {
                        Cause::Filtered
                    } else {
                        Cause::Residual
                    }
                }
            };
            out.count(cause, e);
        }
    }
    Ok(out)
}

fn alpha(img: &Rgba32FImage, x: u32, y: u32) -> f32 {
    let a = img.get_pixel(x, y).0[3];
    if a.is_finite() { a } else { 0.0 }
}

/// The main view's projection on the CPU (as the reference's resolve pass does it).
struct Projector {
    camera_position: DVec3,
    clip_from_rel: glam::Mat4,
    rel_from_clip: glam::Mat4,
    size: [u32; 2],
}

impl Projector {
    fn new(camera: &Camera, size: [u32; 2]) -> Self {
        let clip_from_rel = camera.clip_from_relative(size[0] as f32 / size[1] as f32);
        Self { camera_position: camera.position, clip_from_rel, rel_from_clip: clip_from_rel.inverse(), size }
    }

    /// The pixel a camera-relative point projects to; `None` behind the camera or outside
    /// the viewport.
    fn pixel_of(&self, rel: glam::Vec3) -> Option<IVec2> {
        let c = self.clip_from_rel * rel.extend(1.0);
        if c.w <= 0.0 {
            return None;
        }
        let (w, h) = (self.size[0] as f32, self.size[1] as f32);
        let q = glam::Vec2::new((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h);
        (q.x >= 0.0 && q.y >= 0.0 && q.x < w && q.y < h).then(|| q.floor().as_ivec2())
    }

    /// World position of the surface at pixel `p` with raw depth `depth`.
    fn world_of(&self, p: [u32; 2], depth: f32) -> DVec3 {
        let ndc = glam::Vec2::new(
            (p[0] as f32 + 0.5) / self.size[0] as f32 * 2.0 - 1.0,
            1.0 - (p[1] as f32 + 0.5) / self.size[1] as f32 * 2.0,
        );
        let h = self.rel_from_clip * glam::Vec4::new(ndc.x, ndc.y, depth, 1.0);
        self.camera_position + (h.truncate() / h.w).as_dvec3()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shares_and_psnr_without() {
        let mut b = ErrorBreakdown::default();
        b.count(Cause::HoleLeft, 0.3);
        b.count(Cause::Residual, 0.0);
        b.count(Cause::Residual, 0.0);
        b.count(Cause::Residual, 0.0);
        b.count(Cause::Hidden, 3.0);
        assert_eq!(b.group_pixels(Group::OnScreen), 4);
        assert_eq!(b.pixel_share(Cause::Residual), 0.75);
        assert_eq!(b.error_share(Cause::HoleLeft), 1.0);
        assert_eq!(b.pixel_share(Cause::Hidden), 1.0);
        // MSE 0.3 / 12 = 0.025: 16.02 dB; without the hole, exact.
        assert!((b.psnr(Group::OnScreen) - 16.0206).abs() < 1e-3);
        assert!(b.psnr_without(Cause::HoleLeft).is_infinite());
        assert_eq!(b.psnr_without(Cause::Residual), b.psnr(Group::OnScreen));
        let mut pooled = b.clone();
        pooled.add(&b);
        assert_eq!(pooled.pixel_share(Cause::Residual), 0.75);
        assert_eq!(pooled.psnr(Group::OnScreen), b.psnr(Group::OnScreen));
        assert_eq!(Cause::ALL.len(), Cause::COUNT);
    }
}
