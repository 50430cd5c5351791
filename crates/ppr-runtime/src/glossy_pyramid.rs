//! The glossy colour pyramid: the texture (`GlossyPyramid`, the scene colour at 1/2 to
//! 1/32 of the viewport) and the region a frame builds (`pyramid_rect`: where its glossy
//! reflections read). Built by `passes::glossy_pyramid`, read by `glossy.wgsl`.

use glam::{DVec3, Mat4};

use crate::plan::{FramePlan, ScreenRect};
use crate::shapes::ShapeTable;
use crate::source_box::{SourceBoxes, union_rect};

/// Viewport pixels a side of the block one workgroup reduces (level 0's 16 × 16 texels).
pub const BLOCK: u32 = 32;

/// Levels of the pyramid: 1/2, 1/4, 1/8, 1/16 and 1/32 of the viewport (`BLOCK` = 2⁵).
pub const LEVELS: u32 = 5;

/// Pixels the region reaches past the glossy reflectors' source boxes: the taps around a
/// source pixel near a box's edge read colour beyond it (taps further out are clamped into
/// the region).
pub const MARGIN_PX: u32 = 32;

/// What each pyramid tap adds to its level (`glossy.wgsl`'s `ppr_glossy_pyramid`). A tap
/// read at the level of its share of the lobe blurs more than the glossy reference of
/// `tests/it/glossy.rs` does (its rough floor at 160 × 120, 12 taps at most; on-screen PSNR
/// at roughness 0.2 / 0.35): bias 0 29.8 / 24.9 dB, −1 29.9 / 25.7, −1.5 30.1 / 26.1, −2
/// 30.2 / 26.3, **−2.5 30.1 / 26.4**, always level 0 30.0 / 26.8, against the full-size
/// taps' 29.7 / 26.8 (at most 8 taps: 29.3 / 24.0 at bias 0, 28.5 / 23.9 at −2).
pub const LOD_BIAS: f32 = -2.5;

/// Texture format of every level.
pub const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// The pyramid's texture: level 0 has `BLOCK / 2` texels for every started block of the
/// viewport, so that every level covers the same whole blocks.
pub struct GlossyPyramid {
    /// The viewport it was made for.
    pub viewport: [u32; 2],
    texture: wgpu::Texture,
    /// Every level, for the reflection to sample.
    pub view: wgpu::TextureView,
    /// One view per level, for the build to write.
    pub levels: Vec<wgpu::TextureView>,
}

/// Level 0's size for a viewport.
pub fn level0_size([w, h]: [u32; 2]) -> [u32; 2] {
    [w.div_ceil(BLOCK) * (BLOCK / 2), h.div_ceil(BLOCK) * (BLOCK / 2)]
}

impl GlossyPyramid {
    pub fn new(device: &wgpu::Device, viewport: [u32; 2]) -> Self {
        let [w, h] = level0_size(viewport);
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("ppr glossy pyramid"),
            size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
            mip_level_count: LEVELS,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: FORMAT,
            usage: wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        let levels = (0..LEVELS)
            .map(|level| {
                texture.create_view(&wgpu::TextureViewDescriptor {
                    label: Some("ppr glossy pyramid level"),
                    base_mip_level: level,
                    mip_level_count: Some(1),
                    ..Default::default()
                })
            })
            .collect();
        Self { viewport, texture, view, levels }
    }

    /// The texture (tests read its levels back).
    pub fn texture(&self) -> &wgpu::Texture {
        &self.texture
    }
}

/// The region a frame's pyramid covers: the union of its glossy reflectors' source boxes
/// (the pixels that may reflect into them), `MARGIN_PX` wider each side, its start rounded
/// down and its end up to whole blocks, within the viewport. Empty without glossy shapes.
pub fn pyramid_rect(table: &ShapeTable, plan: &FramePlan, eye: DVec3, clip_from_rel: &Mat4) -> ScreenRect {
    let [w, h] = plan.viewport;
    let boxes = SourceBoxes::new(eye, clip_from_rel, plan.viewport);
    let union = plan
        .glossy
        .iter()
        .map(|&i| boxes.rect(&table.shapes[i as usize]))
        .fold(ScreenRect { min: [0, 0], max: [0, 0] }, union_rect);
    if union.area() == 0 {
        return union;
    }
    let lo = |v: u32| v.saturating_sub(MARGIN_PX) / BLOCK * BLOCK;
    let hi = |v: u32, end: u32| (v + MARGIN_PX).div_ceil(BLOCK).saturating_mul(BLOCK).min(end);
    ScreenRect { min: [lo(union.min[0]), lo(union.min[1])], max: [hi(union.max[0], w), hi(union.max[1], h)] }
}

/// Workgroups of the build over `rect` (one a block).
pub fn groups(rect: ScreenRect) -> (u32, u32) {
    let side = |a: usize| rect.max[a].saturating_sub(rect.min[a]).div_ceil(BLOCK);
    (side(0), side(1))
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3, Vec3};
    use ppr_format::{Reflector, ReflectorKind, ReflectorSet};

    use super::{BLOCK, MARGIN_PX, groups, level0_size, pyramid_rect};
    use crate::camera::{Camera, Projection};
    use crate::plan::{FramePlan, PlanParams};
    use crate::shapes::ShapeTable;
    use crate::source_box::source_rect;

    #[test]
    fn every_level_covers_whole_blocks() {
        assert_eq!(level0_size([3840, 2160]), [1920, 1088]);
        assert_eq!(level0_size([160, 120]), [80, 64]);
        let [w, h] = level0_size([1366, 768]);
        for level in 0..super::LEVELS {
            // Level `level` has 2^level times fewer texels, still whole.
            assert_eq!((w % (16 >> level), h % (16 >> level)), (0, 0));
        }
    }

    /// A rough floor tile and a mirror wall, seen from above at an angle.
    fn scene() -> (ShapeTable, Camera) {
        let mut set = ReflectorSet::new("room");
        let mut floor = Reflector::new(
            0,
            "floor",
            ReflectorKind::Opaque,
            DVec3::new(0.0, 0.0, -4.0),
            DVec3::Y,
            DVec3::X,
            DVec2::ONE,
        );
        floor.roughness = 0.3;
        set.reflectors.push(floor);
        set.reflectors.push(Reflector::new(
            1,
            "wall",
            ReflectorKind::Opaque,
            DVec3::new(0.0, 1.0, -6.0),
            DVec3::Z,
            DVec3::X,
            DVec2::new(2.0, 1.0),
        ));
        let camera = Camera::look_at(
            DVec3::new(0.0, 2.0, 1.0),
            DVec3::new(0.0, 0.0, -4.0),
            Vec3::Y,
            Projection::default(),
        );
        (ShapeTable::from_set(&set), camera)
    }

    #[test]
    fn the_region_holds_the_glossy_source_box_and_its_margin_in_whole_blocks() {
        let (table, camera) = scene();
        let viewport = [640, 360];
        let plan = FramePlan::build(&table, &camera, viewport, &PlanParams::default());
        assert_eq!(plan.glossy, [0], "{plan}");
        let clip = camera.clip_from_relative(plan.aspect);
        let rect = pyramid_rect(&table, &plan, camera.position, &clip);
        let source = source_rect(&table.shapes[0], camera.position, &clip, viewport);
        assert!(source.area() > 0 && source.area() < 640 * 360, "{source:?}");
        for (a, &end) in viewport.iter().enumerate() {
            assert!(rect.min[a].is_multiple_of(BLOCK), "{rect:?}");
            assert!(rect.max[a].is_multiple_of(BLOCK) || rect.max[a] == end, "{rect:?}");
            assert!(rect.min[a] <= source.min[a].saturating_sub(MARGIN_PX), "{rect:?} {source:?}");
            assert!(rect.max[a] >= (source.max[a] + MARGIN_PX).min(end), "{rect:?} {source:?}");
            // No more than a block's rounding past the margin.
            assert!(rect.min[a] + BLOCK + MARGIN_PX > source.min[a], "{rect:?} {source:?}");
        }
        let (x, y) = groups(rect);
        assert_eq!(
            (x * BLOCK >= rect.max[0] - rect.min[0], y * BLOCK >= rect.max[1] - rect.min[1]),
            (true, true)
        );
        // The mirror wall alone: no region.
        let mut mirrors = plan.clone();
        mirrors.glossy.clear();
        assert_eq!(pyramid_rect(&table, &mirrors, camera.position, &clip).area(), 0);
    }
}
