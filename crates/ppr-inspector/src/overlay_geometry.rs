//! Where the overlay draws: rectangles projected to the screen (clipped at the near plane)
//! and the colours for kind and fit quality.

use egui::Color32;
use glam::{DVec3, Vec2, Vec4};
use ppr_format::{Reflector, ReflectorKind};

use crate::camera_control::{CameraRig, clip_to_screen};

/// What the rectangles' colour shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ColorBy {
    /// Opaque, transparent, water.
    #[default]
    Kind,
    /// Coverage: red (poor fit) to green (tight fit).
    Coverage,
}

/// Colour of a reflector kind.
pub fn kind_color(kind: ReflectorKind) -> Color32 {
    match kind {
        ReflectorKind::Opaque => Color32::from_rgb(90, 160, 255),
        ReflectorKind::Transparent => Color32::from_rgb(120, 235, 235),
        ReflectorKind::Water => Color32::from_rgb(70, 110, 230),
    }
}

/// Colour of a coverage in `[0, 1]`: red below 0.5, through yellow, green at 1.
pub fn coverage_color(coverage: f64) -> Color32 {
    let t = ((coverage - 0.5) / 0.5).clamp(0.0, 1.0) as f32;
    let (r, g) = if t < 0.5 { (1.0, t * 2.0) } else { (2.0 - t * 2.0, 1.0) };
    Color32::from_rgb((r * 230.0) as u8, (g * 210.0) as u8, 60)
}

/// The colour of `r` under `by`.
pub fn reflector_color(r: &Reflector, by: ColorBy) -> Color32 {
    match by {
        ColorBy::Kind => kind_color(r.kind),
        ColorBy::Coverage => coverage_color(r.coverage),
    }
}

/// A world-space convex polygon on screen: clipped at the near plane, in pixels from the
/// viewport's top-left. Empty when wholly behind the camera.
pub fn project_polygon(rig: &CameraRig, corners: &[DVec3], size: Vec2) -> Vec<Vec2> {
    let clip: Vec<Vec4> = corners.iter().map(|&p| rig.clip(p, size)).collect();
    // Sutherland–Hodgman against z >= 0 (standard depth: the near plane).
    let mut out = Vec::with_capacity(clip.len() + 2);
    for i in 0..clip.len() {
        let (a, b) = (clip[i], clip[(i + 1) % clip.len()]);
        let (da, db) = (a.z, b.z);
        if da >= 0.0 {
            out.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let t = da / (da - db);
            out.push(a + (b - a) * t);
        }
    }
    out.into_iter().filter(|c| c.w > 0.0).map(|c| clip_to_screen(c, size)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygons_behind_the_camera_vanish_and_crossing_ones_are_clipped() {
        let rig = CameraRig::default();
        let size = Vec2::new(400.0, 300.0);
        let eye = rig.eye();
        let f = rig.forward();
        let side = f.cross(DVec3::Y).normalize();
        let up = side.cross(f);
        let quad =
            |center: DVec3| [center - side - up, center + side - up, center + side + up, center - side + up];
        assert_eq!(project_polygon(&rig, &quad(eye + f * 5.0), size).len(), 4);
        assert!(project_polygon(&rig, &quad(eye - f * 5.0), size).is_empty());
        let crossing =
            [eye - f * 2.0 - side, eye + f * 2.0 - side, eye + f * 2.0 + side, eye - f * 2.0 + side];
        let clipped = project_polygon(&rig, &crossing, size);
        assert_eq!(clipped.len(), 4);
        assert!(clipped.iter().all(|p| p.x.is_finite() && p.y.is_finite()));
    }

    #[test]
    fn coverage_colours_run_from_red_to_green() {
        assert_eq!(coverage_color(0.2), Color32::from_rgb(230, 0, 60));
        assert_eq!(coverage_color(1.0), Color32::from_rgb(0, 210, 60));
    }
}
