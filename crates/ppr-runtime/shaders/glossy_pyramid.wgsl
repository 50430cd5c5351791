// Glossy colour pyramid (beyond the seed): the scene colour at 1/2, 1/4, 1/8, 1/16 and 1/32
// of the viewport over the region the frame's glossy reflections read (the source boxes
// of its glossy reflectors, grown by a margin: `glossy.pyramid_rect`), so that a wide
// lobe takes a few prefiltered taps (glossy.wgsl, `ppr_glossy_pyramid`) instead of many
// full-size ones. Each 16 x 16 workgroup reduces one 32 x 32 block of the colour: a
// bilinear sample at the shared corner of each 2 x 2 texels (their mean) to level 0, then
// means of 2 x 2 through workgroup memory to levels 1 to 4. Recorded beside the
// projection (no buffer or texture in common), read by the reflection.

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var color_tex: texture_2d<f32>;
@group(0) @binding(2) var linear_sampler: sampler;
// The head of glossy.wgsl's `GlossyShapes` (the same buffer part).
@group(0) @binding(3) var<uniform> glossy: GlossyPyramidHead;
@group(0) @binding(4) var level0: texture_storage_2d<rgba16float, write>;
@group(0) @binding(5) var level1: texture_storage_2d<rgba16float, write>;
@group(0) @binding(6) var level2: texture_storage_2d<rgba16float, write>;
@group(0) @binding(7) var level3: texture_storage_2d<rgba16float, write>;
@group(0) @binding(8) var level4: texture_storage_2d<rgba16float, write>;

struct GlossyPyramidHead {
    count: u32,
    max_radius_px: f32,
    max_taps: u32,
    pyramid_levels: u32,
    // The region in viewport pixels: min xy, max xy (min a multiple of 32).
    pyramid_rect: vec4<u32>,
}

// Level-0 texels a workgroup side (a 32 x 32-pixel block).
const SIDE: u32 = 16u;

var<workgroup> means: array<vec3<f32>, 256>;

fn store_level(level: u32, texel: vec2<u32>, c: vec3<f32>) {
    let v = vec4<f32>(c, 1.0);
    switch level {
        case 0u: {
            if (all(texel < textureDimensions(level0))) { textureStore(level0, texel, v); }
        }
        case 1u: {
            if (all(texel < textureDimensions(level1))) { textureStore(level1, texel, v); }
        }
        case 2u: {
            if (all(texel < textureDimensions(level2))) { textureStore(level2, texel, v); }
        }
        case 3u: {
            if (all(texel < textureDimensions(level3))) { textureStore(level3, texel, v); }
        }
        default: {
            if (all(texel < textureDimensions(level4))) { textureStore(level4, texel, v); }
        }
    }
}

@compute @workgroup_size(16, 16)
fn main(@builtin(local_invocation_id) lid: vec3<u32>, @builtin(workgroup_id) wid: vec3<u32>) {
    // The block's first level-0 texel.
    let block = glossy.pyramid_rect.xy / 2u + wid.xy * SIDE;
    let texel = block + lid.xy;
    // The corner shared by the texel's four pixels: a bilinear sample there is their mean
    // (the sampler clamps at the viewport's edge).
    let uv = vec2<f32>(texel * 2u + 1u) / vec2<f32>(frame.size);
    var c = finite_colour(textureSampleLevel(color_tex, linear_sampler, uv, 0.0).rgb);
    store_level(0u, texel, c);
    means[lid.x + lid.y * SIDE] = c;
    for (var level = 1u; level < 5u; level++) {
        let n = SIDE >> level;
        let inside = all(lid.xy < vec2<u32>(n));
        // The last level's means are written.
        workgroupBarrier();
        if (inside) {
            let b = lid.xy * 2u;
            let i = b.x + b.y * SIDE;
            c = 0.25 * (means[i] + means[i + 1u] + means[i + SIDE] + means[i + SIDE + 1u]);
        }
        // Every read of the last level's means is done.
        workgroupBarrier();
        if (inside) {
            means[lid.x + lid.y * SIDE] = c;
            store_level(level, (block >> vec2<u32>(level)) + lid.xy, c);
        }
    }
}
