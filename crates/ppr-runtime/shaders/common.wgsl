// Declarations shared by the PPR passes: frame uniforms, reflector shapes, flags.
// Mirrors crates/ppr-runtime/src/gpu_types.rs byte for byte (sizes asserted there).

const PPR_FLAG_HOLES: u32 = 1u;
const PPR_FLAG_FILTERING: u32 = 2u;
const PPR_FLAG_ANTI_BLEEDING: u32 = 4u;
const PPR_FLAG_OCCLUDER_TESTS: u32 = 8u;
const PPR_FLAG_WRITE_LAST: u32 = 16u;
const PPR_FLAG_WRITE_MAX: u32 = 32u;
const PPR_FLAG_WATER_STRETCH: u32 = 64u;
const PPR_FLAG_REPLACE_FAR: u32 = 128u;
const PPR_FLAG_LAYER_EVERY_TILE: u32 = 256u;

// Reflector kinds (Layer::kind).
const PPR_KIND_OPAQUE: u32 = 0u;
const PPR_KIND_TRANSPARENT: u32 = 1u;
const PPR_KIND_WATER: u32 = 2u;

// Shape flags.
const PPR_SHAPE_OCCLUDES: u32 = 1u;

struct FrameUniforms {
    clip_from_rel: mat4x4<f32>,
    rel_from_clip: mat4x4<f32>,
    // width, height, 1 / width, 1 / height
    resolution: vec4<f32>,
    size: vec2<u32>,
    visible_count: u32,
    flags: u32,
    far_depth: f32,
    // Points closer to a reflector's plane than this times their distance from the
    // camera are taken as lying on it (they would reflect onto themselves).
    plane_epsilon: f32,
    // Layer reflectors (glass, water) with an atlas region this frame.
    layer_count: u32,
    // Projection tests before the layers': visible shapes and merged plane groups.
    tested_count: u32,
    // The screen rectangle the layer reflection pass covers.
    layer_origin: vec2<u32>,
    layer_extent: vec2<u32>,
    encoding: EncodingParams,
    // Confidence fade at the screen borders, pixels (0: none): the output's alpha falls to
    // 0 as the reflected point nears an edge of the viewport.
    border_fade_px: f32,
    _pad1: u32,
    _pad2: u32,
    _pad3: u32,
}

// A layer reflector's atlas region: its screen rectangle (exclusive max) and where its
// rows start in the atlas.
struct Layer {
    rect_min: vec2<u32>,
    rect_max: vec2<u32>,
    offset: u32,
    shape: u32,
    kind: u32,
    _pad: u32,
}

// The tiles that show a visible reflector (written by tile_classify.wgsl, whose own view
// of the buffer has atomics): tile index = x + y * tiles_x. `args` are the indirect
// dispatch arguments (x, y, z) of one workgroup per tile.
struct ActiveTileList {
    count: u32,
    args: array<u32, 3>,
    tiles: array<u32>,
}

// Active tile `slot` of an indirect dispatch in rows of 65535 workgroups.
fn ppr_active_slot(wid: vec3<u32>) -> u32 {
    return wid.x + wid.y * 65535u;
}

// A reflector rectangle, camera-relative.
struct Shape {
    center: vec3<f32>,
    half_u: f32,
    axis_u: vec3<f32>,
    half_v: f32,
    axis_v: vec3<f32>,
    // dot(center, normal), computed in f64 on the CPU.
    plane_dist: f32,
    normal: vec3<f32>,
    flags: u32,
    occluder_start: u32,
    occluder_count: u32,
    parallel_group: u32,
    // dot(center, axis_u), dot(center, axis_v), computed in f64 on the CPU.
    center_u: f32,
    center_v: f32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}
