// Hi-Z build: the min-depth pyramid of the Hi-Z trace (seed 004). Level 0 is the linear
// view depth of each pixel (`linearize`); each further level holds, per texel, the minimum
// of its 2 × 2 children (`downsample`, one dispatch per level), so a texel is the depth of
// the closest surface anywhere in its footprint. Linear depth makes one pyramid serve
// standard and reversed Z alike. Where a level has an odd width or height, its last
// column or row also goes into the last texel of the next level, so every pixel is
// covered at every level.
// Needs common.wgsl and hiz_layout.wgsl.

// Workgroup edge (threads per side); set from Rust.
override GROUP_EDGE: u32 = 8u;

@group(0) @binding(1) var depth_tex: texture_2d<f32>;
@group(0) @binding(2) var atlas_out: texture_storage_2d<r32float, write>;

@compute @workgroup_size(GROUP_EDGE, GROUP_EDGE)
fn linearize(@builtin(global_invocation_id) gid: vec3<u32>) {
    if (any(gid.xy >= frame.size)) {
        return;
    }
    let w = baseline_view_depth(textureLoad(depth_tex, gid.xy, 0).x);
    textureStore(atlas_out, gid.xy, vec4<f32>(w, 0.0, 0.0, 0.0));
}

struct DownsampleParams {
    // The level written (≥ 1); it reads the level below.
    level: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

@group(0) @binding(3) var<uniform> levels: HiZLevels;
@group(0) @binding(4) var<uniform> downsample_params: DownsampleParams;
@group(0) @binding(5) var atlas: texture_storage_2d<r32float, read_write>;

@compute @workgroup_size(GROUP_EDGE, GROUP_EDGE)
fn downsample(@builtin(global_invocation_id) gid: vec3<u32>) {
    let dst = levels.rects[downsample_params.level];
    let src = levels.rects[downsample_params.level - 1u];
    if (any(gid.xy >= dst.zw)) {
        return;
    }
    let last = gid.xy == dst.zw - 1u;
    let odd = (src.zw & vec2<u32>(1u)) == vec2<u32>(1u);
    let span = vec2<u32>(2u) + select(vec2<u32>(0u), vec2<u32>(1u), last & odd);
    var m = BASELINE_SKY_DEPTH;
    for (var dy = 0u; dy < span.y; dy = dy + 1u) {
        for (var dx = 0u; dx < span.x; dx = dx + 1u) {
            let c = min(2u * gid.xy + vec2<u32>(dx, dy), src.zw - 1u);
            m = min(m, textureLoad(atlas, src.xy + c).x);
        }
    }
    textureStore(atlas, dst.xy + gid.xy, vec4<f32>(m, 0.0, 0.0, 0.0));
}
