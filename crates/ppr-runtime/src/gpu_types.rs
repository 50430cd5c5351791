//! `#[repr(C)]` mirrors of the WGSL structs in `crates/ppr-runtime/shaders/common.wgsl`, sizes asserted.

use crate::encoding::EncodingParams;

/// Bit of [`FrameUniforms::flags`]: fill holes.
pub const FLAG_HOLES: u32 = 1;
/// Bit of [`FrameUniforms::flags`]: filtered colour sampling.
pub const FLAG_FILTERING: u32 = 2;
/// Bit of [`FrameUniforms::flags`]: anti-bleeding.
pub const FLAG_ANTI_BLEEDING: u32 = 4;
/// Bit of [`FrameUniforms::flags`]: occluder tests in the projection pass.
pub const FLAG_OCCLUDER_TESTS: u32 = 8;

/// Bit of [`FrameUniforms::flags`]: plain stores instead of `atomicMin` (debug).
pub const FLAG_WRITE_LAST: u32 = 16;
/// Bit of [`FrameUniforms::flags`]: `atomicMax` instead of `atomicMin` (debug).
pub const FLAG_WRITE_MAX: u32 = 32;

/// Bit of [`FrameUniforms::flags`]: stretch water reflections into missing borders.
pub const FLAG_WATER_STRETCH: u32 = 64;
/// Hole filling also replaces a reflection by a neighbour's more than 6 px shorter one
/// (the seed's rule; [`crate::ReflectionSettings::replace_far_reflections`]).
pub const FLAG_REPLACE_FAR: u32 = 128;
/// The layer reflection writes every tile of the layers' common rectangle, also those that
/// meet no layer's own (the reduced tiers, whose upsample reads the whole rectangle; and
/// the bench's `layers: every tile`).
pub const FLAG_LAYER_EVERY_TILE: u32 = 256;

/// Bit of [`GpuShape::flags`]: the shape blocks reflections of the main buffer behind it
/// (opaque and water shapes do; glass does not).
pub const SHAPE_OCCLUDES: u32 = 1;

/// `FrameUniforms` of `common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniforms {
    pub clip_from_rel: [[f32; 4]; 4],
    pub rel_from_clip: [[f32; 4]; 4],
    pub resolution: [f32; 4],
    pub size: [u32; 2],
    pub visible_count: u32,
    pub flags: u32,
    pub far_depth: f32,
    pub plane_epsilon: f32,
    pub layer_count: u32,
    /// Projection tests before the layers' ([`crate::FramePlan::tested`]): visible shapes
    /// and merged plane groups.
    pub tested_count: u32,
    pub layer_origin: [u32; 2],
    pub layer_extent: [u32; 2],
    pub encoding: EncodingParams,
    /// Width of the confidence fade at the screen borders, pixels (0: no fade).
    pub border_fade_px: f32,
    pub _pad1: [u32; 3],
}
const _: () = assert!(std::mem::size_of::<FrameUniforms>() == 240);

/// `Layer` of `common.wgsl`: a glass or water reflector's atlas region.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuLayer {
    pub rect_min: [u32; 2],
    pub rect_max: [u32; 2],
    pub offset: u32,
    pub shape: u32,
    pub kind: u32,
    pub _pad: u32,
}
const _: () = assert!(std::mem::size_of::<GpuLayer>() == 32);

/// `PPR_KIND_*` of `common.wgsl`.
pub fn kind_code(kind: ppr_format::ReflectorKind) -> u32 {
    match kind {
        ppr_format::ReflectorKind::Opaque => 0,
        ppr_format::ReflectorKind::Transparent => 1,
        ppr_format::ReflectorKind::Water => 2,
    }
}

/// `Shape` of `common.wgsl`: one reflector rectangle, camera-relative.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuShape {
    pub center: [f32; 3],
    pub half_u: f32,
    pub axis_u: [f32; 3],
    pub half_v: f32,
    pub axis_v: [f32; 3],
    pub plane_dist: f32,
    pub normal: [f32; 3],
    pub flags: u32,
    pub occluder_start: u32,
    pub occluder_count: u32,
    pub parallel_group: u32,
    /// `dot(center, axis_u)` and `dot(center, axis_v)` (the division-free rectangle test).
    pub center_u: f32,
    pub center_v: f32,
    pub _pad: [u32; 3],
}
const _: () = assert!(std::mem::size_of::<GpuShape>() == 96);

/// `ShapeTest` of `tile_test.wgsl`: a visible shape's reflection test, camera-relative. A
/// point `p` is reflected into the rectangle when its distance from the reflector's plane,
/// `dist = plane.xyz · p + plane.w`, is positive and, for each rectangle axis, the axis'
/// form `L = across.xyz · p + across.w` (the reflection point's offset from the centre
/// along the axis, multiplied out by the positive `dist + h`, `h` the camera's height over
/// the plane) lies within `±(k · dist + m)` (the half extent, multiplied out the same way):
/// `extent` holds `(k_u, m_u, k_v, m_v)`. The two bounds of an axis are the pyramid's two
/// opposite sides ([`GpuShapeTest::sides`]), tested with one form and one product instead of
/// two planes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuShapeTest {
    pub plane: [f32; 4],
    pub across_u: [f32; 4],
    pub across_v: [f32; 4],
    pub extent: [f32; 4],
    /// Index of the shape in the shape table.
    pub shape: u32,
    /// Its parallel group.
    pub group: u32,
    /// Its path blocker's index in the shape table ([`crate::path_blockers`]), or
    /// [`crate::path_blockers::NO_BLOCKER`] (always, unless the frame tests blockers).
    pub blocker: u32,
    pub _pad: u32,
}
const _: () = assert!(std::mem::size_of::<GpuShapeTest>() == 80);

impl GpuShapeTest {
    /// Axes' forms and extents every point passes (a parallel tree's entry: its members
    /// test their own rectangles).
    pub const NO_SIDES: ([f32; 4], [f32; 4], [f32; 4]) = ([0.0; 4], [0.0; 4], [0.0, 1.0, 0.0, 1.0]);

    /// The per-pixel test of `projection.wgsl` (`quad_test`), in the same f32 operations:
    /// the distance from the plane where `p` (on-plane tolerance `tolerance`) is reflected
    /// into the rectangle, else `None`.
    pub fn reflects(&self, p: glam::Vec3, tolerance: f32) -> Option<f32> {
        let form = |a: [f32; 4]| p.x * a[0] + p.y * a[1] + p.z * a[2] + a[3];
        let dist = form(self.plane);
        let [ku, mu, kv, mv] = self.extent;
        let inside =
            form(self.across_u).abs() <= ku * dist + mu && form(self.across_v).abs() <= kv * dist + mv;
        (tolerance > 0.0 && dist > tolerance && inside).then_some(dist)
    }

    /// The pyramid's four sides as planes (`xyz · p + w ≥ 0` inside; not unit length): per
    /// axis `k · dist + m ∓ L`, the bounds the block culling tests a box against.
    pub fn sides(&self) -> [[f32; 4]; 4] {
        let bound = |k: f32, m: f32, a: [f32; 4], sign: f32| {
            let pl = self.plane;
            [
                k * pl[0] + sign * a[0],
                k * pl[1] + sign * a[1],
                k * pl[2] + sign * a[2],
                k * pl[3] + m + sign * a[3],
            ]
        };
        let [ku, mu, kv, mv] = self.extent;
        [
            bound(ku, mu, self.across_u, -1.0),
            bound(kv, mv, self.across_v, -1.0),
            bound(ku, mu, self.across_u, 1.0),
            bound(kv, mv, self.across_v, 1.0),
        ]
    }
}

/// Most glossy reflectors one frame blurs (`GLOSSY_CAPACITY` of `glossy.wgsl`): the largest
/// on screen; the others are reflected as mirrors ([`crate::FramePlan::glossy_dropped`]).
pub const GLOSSY_CAPACITY: usize = 32;

/// `GlossyShape` of `glossy.wgsl`: a visible glossy reflector, camera-relative.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuGlossyShape {
    /// Normal, and `-dot(normal, center)`.
    pub plane: [f32; 4],
    /// Centre, and the roughness.
    pub center: [f32; 4],
    /// Axis u, and the half extent along it.
    pub axis_u: [f32; 4],
    /// Axis v, and the half extent along it.
    pub axis_v: [f32; 4],
    /// The screen rectangle in pixels: min x, min y, max x, max y.
    pub rect: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuGlossyShape>() == 80);

/// `GlossyShapes` of `glossy.wgsl`: the uniform the glossy reflection pass reads.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuGlossyShapes {
    pub count: u32,
    /// The largest footprint radius, pixels.
    pub max_radius_px: f32,
    /// The most taps per pixel.
    pub max_taps: u32,
    pub _pad: u32,
    pub shapes: [GpuGlossyShape; GLOSSY_CAPACITY],
}
const _: () = assert!(std::mem::size_of::<GpuGlossyShapes>() == 16 + 80 * GLOSSY_CAPACITY);
