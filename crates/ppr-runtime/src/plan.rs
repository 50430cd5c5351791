//! The frame plan: which reflectors are visible and which passes run, decided on the CPU.

use std::fmt;

use glam::Vec4;
use ppr_format::ReflectorKind;

use crate::camera::Camera;
use crate::encoding::EncodingLayout;
use crate::shapes::ShapeTable;

/// A reflector's rectangle on screen, in pixels (inclusive min, exclusive max).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ScreenRect {
    pub min: [u32; 2],
    pub max: [u32; 2],
}

/// What one frame will do, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct FramePlan {
    /// Viewport size in pixels.
    pub viewport: [u32; 2],
    /// Indices (into the set) of the shapes the main buffer renders this frame.
    pub visible: Vec<u32>,
    /// Screen rectangle of each visible shape (same order as `visible`).
    pub screen_rects: Vec<ScreenRect>,
    /// Shapes disabled in the set.
    pub disabled: usize,
    /// Shapes whose reflecting side faces away from the camera (or the camera is on the plane).
    pub culled_back_side: usize,
    /// Shapes outside the view frustum.
    pub culled_frustum: usize,
    /// Visible glass panels, which the main buffer does not render (they need the
    /// transparent atlas).
    pub transparent_skipped: usize,
    /// Whether the projection pass tests occluders (some visible shape has one).
    pub occluder_tests: bool,
    /// The encoding layout for this viewport.
    pub encoding: EncodingLayout,
}

impl FramePlan {
    /// Culls the table's shapes for `camera` and decides the passes.
    pub fn build(table: &ShapeTable, camera: &Camera, viewport: [u32; 2]) -> Self {
        let [w, h] = viewport;
        let clip_from_rel = camera.clip_from_relative(w as f32 / h.max(1) as f32);
        let mut plan = FramePlan {
            viewport,
            visible: Vec::new(),
            screen_rects: Vec::new(),
            disabled: 0,
            culled_back_side: 0,
            culled_frustum: 0,
            transparent_skipped: 0,
            occluder_tests: false,
            encoding: EncodingLayout::for_resolution(w.max(1), h.max(1)),
        };
        for (i, s) in table.shapes.iter().enumerate() {
            if !s.enabled {
                plan.disabled += 1;
                continue;
            }
            // In front means a negative plane distance; NaN (a broken camera) culls too.
            let in_front = s.plane_dist_from(camera.position) < 0.0;
            if !in_front {
                plan.culled_back_side += 1;
                continue;
            }
            let clip = s.corners().map(|c| clip_from_rel * (c - camera.position).as_vec3().extend(1.0));
            if outside_frustum(&clip) {
                plan.culled_frustum += 1;
                continue;
            }
            if s.kind == ReflectorKind::Transparent {
                plan.transparent_skipped += 1;
                continue;
            }
            plan.occluder_tests |= table.has_blocking_occluders(i);
            plan.visible.push(i as u32);
            plan.screen_rects.push(screen_rect(&clip, viewport));
        }
        plan
    }

    /// True when no pass runs this frame (nothing is dispatched; the output is not written).
    pub fn is_empty(&self) -> bool {
        self.visible.is_empty()
    }

    /// Names of the passes this frame records, in order.
    pub fn passes(&self) -> &'static [&'static str] {
        if self.is_empty() { &[] } else { &["clear", "projection", "reflection"] }
    }
}

/// Whether all corners lie outside one of the clip volume's planes (conservative).
fn outside_frustum(clip: &[Vec4; 4]) -> bool {
    let planes: [fn(&Vec4) -> f32; 5] = [
        |c| c.w + c.x,
        |c| c.w - c.x,
        |c| c.w + c.y,
        |c| c.w - c.y,
        // Near plane: z ≥ 0 for standard Z, z ≤ w for reversed Z; w > 0 covers both
        // conservatively (everything in front of the camera).
        |c| c.w,
    ];
    planes.iter().any(|inside| clip.iter().all(|c| inside(c) < 0.0))
}

/// Bounding rectangle of the corners on screen; the whole viewport if any corner is
/// behind the camera (the projection is unbounded then).
fn screen_rect(clip: &[Vec4; 4], [w, h]: [u32; 2]) -> ScreenRect {
    if clip.iter().any(|c| c.w <= 1e-6) {
        return ScreenRect { min: [0, 0], max: [w, h] };
    }
    let (mut lo, mut hi) = (glam::Vec2::splat(f32::MAX), glam::Vec2::splat(f32::MIN));
    for c in clip {
        let ndc = c.truncate().truncate() / c.w;
        let px = (ndc * glam::Vec2::new(0.5, -0.5) + 0.5) * glam::Vec2::new(w as f32, h as f32);
        lo = lo.min(px);
        hi = hi.max(px);
    }
    let clamp = |v: f32, max: u32| v.clamp(0.0, max as f32) as u32;
    ScreenRect {
        min: [clamp(lo.x.floor(), w), clamp(lo.y.floor(), h)],
        max: [clamp(hi.x.ceil(), w), clamp(hi.y.ceil(), h)],
    }
}

impl fmt::Display for FramePlan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [w, h] = self.viewport;
        writeln!(
            f,
            "frame {w}x{h}: {} visible reflector(s); culled {} back-side, {} off-screen; {} disabled{}",
            self.visible.len(),
            self.culled_back_side,
            self.culled_frustum,
            self.disabled,
            if self.transparent_skipped > 0 {
                format!("; {} glass panel(s) skipped (no transparent atlas)", self.transparent_skipped)
            } else {
                String::new()
            }
        )?;
        if self.is_empty() {
            return write!(f, "passes: none (nothing dispatched)");
        }
        let l = &self.encoding;
        write!(
            f,
            "passes: {}; occluder tests {}; encoding {}.{}/{}.{} bits (major/minor whole.fraction)",
            self.passes().join(" -> "),
            if self.occluder_tests { "on" } else { "off" },
            l.major_int_bits,
            l.major_frac_bits,
            l.minor_int_bits,
            l.minor_frac_bits,
        )
    }
}
