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

/// `ShapeTest` of `tile_test.wgsl`: a visible shape's reflection test as five planes
/// (`xyz · p + w`), camera-relative. A point is reflected into the rectangle when the
/// first is positive (its distance from the reflector's plane) and the four others are not
/// negative (the sides of the pyramid from the mirrored camera through the rectangle).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuShapeTest {
    pub plane: [f32; 4],
    pub sides: [[f32; 4]; 4],
    /// Index of the shape in the shape table.
    pub shape: u32,
    /// Its parallel group.
    pub group: u32,
    pub _pad: [u32; 2],
}
const _: () = assert!(std::mem::size_of::<GpuShapeTest>() == 96);

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
