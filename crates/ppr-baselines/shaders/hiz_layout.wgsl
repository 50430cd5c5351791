// Where the levels of the Hi-Z pyramid lie in its atlas (prepended after common.wgsl to
// the Hi-Z passes). The pyramid is one R32Float texture with level 0 at the origin and
// the further levels stacked in a column to its right; each pass reads it with
// `textureLoad(..., 0)` at `rect.xy + texel`. (A mip chain read with a dynamic level
// gave wrong values through naga's GLSL on llvmpipe; an atlas reads the same everywhere.)
// Mirrors crates/ppr-baselines/src/hiz_pyramid.rs (HIZ_MAX_LEVELS, level_rects).

const HIZ_MAX_LEVELS: u32 = 16u;

struct HiZLevels {
    // Per level: xy = origin in the atlas, zw = width and height.
    rects: array<vec4<u32>, 16>,
    // Levels in use.
    count: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}
