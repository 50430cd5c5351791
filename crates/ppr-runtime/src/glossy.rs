//! The uniform of the glossy reflection (`shaders/glossy.wgsl`): the frame's visible
//! glossy reflectors, camera-relative, and the largest footprint.

use glam::DVec3;

use crate::gpu_types::{GLOSSY_CAPACITY, GpuGlossyShape, GpuGlossyShapes};
use crate::plan::FramePlan;
use crate::shapes::ShapeTable;

/// Largest footprint radius of the glossy blur (of its median tap), as a fraction of the
/// viewport's shorter side: a guard against lobes wider than the screen. Chosen on the
/// software adapter (tests/it/glossy.rs, 160 × 120): capping at 0.04 or 0.1 of the side
/// cost 3.4 and 3.4 dB at roughness 0.35 against the glossy reference, 0.25 nothing
/// measurable.
pub const MAX_FOOTPRINT: f32 = 0.25;

/// Default most taps per pixel of the glossy blur ([`crate::DebugOptions::glossy_taps`]).
pub const GLOSSY_TAPS: u32 = 12;

/// The plan's glossy shapes (at most [`GLOSSY_CAPACITY`]) as the shader reads them,
/// relative to `eye`, each with its screen rectangle grown by a pixel.
pub fn glossy_shapes(table: &ShapeTable, plan: &FramePlan, eye: DVec3, max_taps: u32) -> GpuGlossyShapes {
    let [w, h] = plan.viewport;
    let glossy = &plan.glossy;
    let mut shapes = [GpuGlossyShape::default(); GLOSSY_CAPACITY];
    for (slot, &i) in shapes.iter_mut().zip(glossy) {
        let s = &table.shapes[i as usize];
        let rect = plan.visible.iter().position(|&v| v == i).map_or([0.0, 0.0, w as f32, h as f32], |k| {
            let r = plan.screen_rects[k];
            [r.min[0] as f32 - 1.0, r.min[1] as f32 - 1.0, r.max[0] as f32 + 1.0, r.max[1] as f32 + 1.0]
        });
        let center = (s.center - eye).as_vec3();
        *slot = GpuGlossyShape {
            plane: s.normal.extend(-s.normal.dot(center)).to_array(),
            center: center.extend(s.roughness).to_array(),
            axis_u: s.axis_u.extend(s.half_extents[0]).to_array(),
            axis_v: s.axis_v.extend(s.half_extents[1]).to_array(),
            rect,
        };
    }
    GpuGlossyShapes {
        count: glossy.len().min(GLOSSY_CAPACITY) as u32,
        max_radius_px: MAX_FOOTPRINT * w.min(h) as f32,
        max_taps,
        _pad: 0,
        shapes,
    }
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3, Vec3};
    use ppr_format::{Reflector, ReflectorKind, ReflectorSet};

    use crate::camera::{Camera, Projection};
    use crate::plan::{FramePlan, PlanParams};
    use crate::shapes::ShapeTable;

    /// Three floor tiles side by side with the given roughness, seen from above.
    fn plan(roughness: [f64; 3], params: &PlanParams) -> FramePlan {
        let mut set = ReflectorSet::new("tiles");
        for (k, r) in roughness.into_iter().enumerate() {
            let center = DVec3::new(3.0 * k as f64 - 3.0, 0.0, -4.0);
            let mut tile = Reflector::new(
                k as u32,
                format!("tile {k}"),
                ReflectorKind::Opaque,
                center,
                DVec3::Y,
                DVec3::X,
                DVec2::ONE,
            );
            tile.roughness = r;
            set.reflectors.push(tile);
        }
        let camera = Camera::look_at(
            DVec3::new(0.0, 3.0, 2.0),
            DVec3::new(0.0, 0.0, -4.0),
            Vec3::Y,
            Projection::default(),
        );
        FramePlan::build(&ShapeTable::from_set(&set), &camera, [320, 180], params)
    }

    #[test]
    fn rough_reflectors_are_blurred_up_to_the_limit_and_left_to_the_fallback_past_it() {
        let p = plan([0.0, 0.3, 0.7], &PlanParams::default());
        assert_eq!((p.visible.len(), p.glossy.as_slice(), p.too_rough), (2, &[1][..], 1), "{p}");
        assert!(p.passes().iter().any(|pass| pass.ends_with("glossy)")), "{:?}", p.passes());
        let lenient = plan([0.0, 0.3, 0.7], &PlanParams { max_roughness: 1.0, ..Default::default() });
        assert_eq!((lenient.visible.len(), lenient.glossy.len(), lenient.too_rough), (3, 2, 0), "{lenient}");
        let mirrors = plan([0.0; 3], &PlanParams::default());
        assert!(mirrors.glossy.is_empty(), "{mirrors}");
        assert!(!mirrors.passes().iter().any(|pass| pass.contains("glossy")), "{:?}", mirrors.passes());
    }

    #[test]
    fn the_uniform_holds_each_glossy_shape_camera_relative() {
        let p = plan([0.2, 0.0, 0.4], &PlanParams::default());
        let mut set = ReflectorSet::new("tiles");
        for k in 0..3u32 {
            let center = DVec3::new(3.0 * f64::from(k) - 3.0, 0.0, -4.0);
            let mut r = Reflector::new(k, "t", ReflectorKind::Opaque, center, DVec3::Y, DVec3::X, DVec2::ONE);
            r.roughness = [0.2, 0.0, 0.4][k as usize];
            set.reflectors.push(r);
        }
        let eye = DVec3::new(0.0, 3.0, 2.0);
        let u = super::glossy_shapes(&ShapeTable::from_set(&set), &p, eye, 12);
        assert_eq!(u.count, 2);
        for (slot, &i) in u.shapes.iter().zip(&p.glossy) {
            let expected_center = (set.reflectors[i as usize].center - eye).as_vec3();
            assert_eq!(slot.center[..3], expected_center.to_array());
            assert_eq!(slot.center[3], set.reflectors[i as usize].roughness as f32);
            // The centre lies on the plane: n · c + w = 0.
            let n = Vec3::from_slice(&slot.plane[..3]);
            assert!((n.dot(expected_center) + slot.plane[3]).abs() < 1e-6);
            // The screen rectangle is the plan's, a pixel larger each side.
            let k = p.visible.iter().position(|&v| v == i).expect("glossy shapes are visible");
            let r = p.screen_rects[k];
            let grown =
                [r.min[0] as f32 - 1.0, r.min[1] as f32 - 1.0, r.max[0] as f32 + 1.0, r.max[1] as f32 + 1.0];
            assert_eq!(slot.rect, grown);
        }
        assert_eq!(u.max_radius_px, super::MAX_FOOTPRINT * 180.0);
    }
}
