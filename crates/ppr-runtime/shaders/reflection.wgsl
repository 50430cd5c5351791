// Reflection pass: decode the intermediate buffer, fill holes from the neighbour with the
// smallest offset (a second ring, two pixels away and the pixel above, where the first has
// no data), take filtered and unfiltered colour samples and reduce bleeding in
// YCoCg (shading.wgsl). Output: reflected colour, alpha its confidence (shading.wgsl's
// ppr_confidence: 1 inside the screen, fading towards the borders; 0 where no reflection
// was found). Seed: PPR_ReflectionPass.
//
// In direct dispatch (CLEAR_NEXT) each invocation also clears its pixels of the intermediate
// buffer and atlas that the next encode uses (the renderer's two slots, used by turns), so
// that the next frame needs no clear pass.
//
// Variants: INDIRECT (the active tiles only, walked by a fixed number of workgroups or one
// workgroup each), NORMAL_MAPS (bonus slides: perturb the reflection with the surface normal,
// project, fetch; a 4-tap march toward the reflecting pixel rejects disoccluded samples;
// the flat reflection is the fallback), GLOSSY (glossy.wgsl: reflectors with roughness
// blur their reflection by a footprint set by roughness and reflection distance).

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var<storage, read> intermediate: array<u32>;
@group(0) @binding(2) var color_tex: texture_2d<f32>;
@group(0) @binding(3) var linear_sampler: sampler;
@group(0) @binding(4) var output: texture_storage_2d<rgba16float, write>;
@group(0) @binding(5) var<storage, read> active_tiles: ActiveTileList;
@group(0) @binding(7) var depth_tex: texture_2d<f32>;
// World-space (= camera-relative) shading normals, xyz.
@group(0) @binding(8) var normal_tex: texture_2d<f32>;
// The frame's visible glossy reflectors (glossy.wgsl).
@group(0) @binding(9) var<uniform> glossy: GlossyShapes;
// The next encode's intermediate buffer and layer atlas (the other slot), cleared here with
// CLEAR_NEXT.
@group(0) @binding(10) var<storage, read_write> next_intermediate: array<u32>;
@group(0) @binding(11) var<storage, read_write> next_atlas: array<u32>;

override INDIRECT: bool = false;
override NORMAL_MAPS: bool = false;
override GLOSSY: bool = false;
override CLEAR_NEXT: bool = false;
// With INDIRECT: a fixed number of workgroups (a direct dispatch) walk the active-tile list,
// instead of one workgroup per active tile by indirect dispatch (which wgpu, unless the
// instance turns VALIDATION_INDIRECT_CALL off, precedes with a dispatch and barriers of its
// own that check the arguments).
override TILE_LOOP: bool = false;
// Bench only (never a correct image): 1 returns at once; 2 stores the chosen offset (no
// colour read, no blur); 3 stores the sharp colour (no glossy blur).
override ABLATION: u32 = 0u;

// Reads the intermediate buffer; outside the viewport it reads as "no data". The whole
// buffer was clear before the projection (the last encode's reflection or classification
// cleared it), so with indirect dispatch too a neighbour in an inactive tile holds what the
// projection wrote there, as in direct dispatch.
fn read_value(p: vec2<i32>) -> u32 {
    if (any(p < vec2<i32>(0)) || any(p >= vec2<i32>(frame.size))) {
        return PPR_CLEAR_VALUE;
    }
    return intermediate[u32(p.x) + u32(p.y) * frame.size.x];
}

// Clears the pixel's value in the next encode's intermediate buffer, and the atlas values
// whose index is the pixel's plus a multiple of the pixel count (the atlas may be larger
// than the viewport).
fn clear_next(pixel: vec2<u32>) {
    let i = pixel.x + pixel.y * frame.size.x;
    next_intermediate[i] = PPR_CLEAR_VALUE;
    let pixels = frame.size.x * frame.size.y;
    for (var j = i; j < arrayLength(&next_atlas); j += pixels) {
        next_atlas[j] = PPR_CLEAR_VALUE;
    }
}

fn valid_depth_at(p: vec2<i32>) -> f32 {
    let d = textureLoad(depth_tex, clamp(p, vec2<i32>(0), vec2<i32>(frame.size) - 1), 0).r;
    if (ppr_is_valid_depth(d)) {
        return d;
    }
    return -1.0;
}

// The normal-mapped reflection at `vpos`, or `flat` when the normal does not perturb it
// or no tap of the march is accepted.
fn normal_mapped(vpos: vec2<i32>, chosen: PprChosen, flat: vec4<f32>) -> vec4<f32> {
    let d_here = valid_depth_at(vpos);
    let decoded = ppr_decode(chosen.value, frame.encoding);
    let src = vec2<f32>(vpos) + 0.5 - (ppr_decoded_whole_offset(decoded) - vec2<f32>(chosen.holes_offset));
    let src_px = vec2<i32>(floor(src));
    let d_src = valid_depth_at(src_px);
    // The reflected point in the pixel itself (a surface just above the plane reflects into
    // its own pixel): there is no direction `q - p` to perturb.
    if (d_here < 0.0 || d_src < 0.0 || all(src_px == vpos)) {
        return flat;
    }
    let p = ppr_unproject(vec2<f32>(vpos) + 0.5, d_here);
    let q = ppr_unproject(floor(src) + 0.5, d_src);
    let v = normalize(p);
    let r = normalize(q - p);
    // The flat reflection's plane normal: r - v is parallel to it.
    let n_flat = normalize(r - v);
    // Coincident points (equal depths through two pixels) or r == v still give NaN; a
    // compiler may fold NaN comparisons, so test the bits.
    if (!ppr_is_finite3(v) || !ppr_is_finite3(r) || !ppr_is_finite3(n_flat)) {
        return flat;
    }
    let n = textureLoad(normal_tex, vpos, 0).xyz;
    let len = length(n);
    if (!(len > 0.5)) {
        return flat;
    }
    let n_map = n / len;
    if (dot(n_map, n_flat) > 0.99999 || dot(n_map, -v) <= 0.0) {
        return flat;
    }
    let r_map = reflect(v, n_map);
    let q_map = p + r_map * length(q - p);
    // March from the perturbed point toward the reflecting pixel; accept the first tap
    // that is not behind the depth buffer (a disoccluded sample would be).
    for (var k = 0u; k < 4u; k++) {
        let c = mix(p, q_map, 1.0 - f32(k) * 0.25);
        let s = ppr_project(c);
        if (s.z == 0.0 || any(s.xy < vec2<f32>(0.0)) || any(s.xy >= frame.resolution.xy)) {
            continue;
        }
        let d = valid_depth_at(vec2<i32>(s.xy));
        if (d < 0.0) {
            continue;
        }
        let surface = ppr_unproject(floor(s.xy) + 0.5, d);
        if (length(c) <= length(surface) * 1.02) {
            let colour = textureSampleLevel(color_tex, linear_sampler, s.xy * frame.resolution.zw, 0.0).rgb;
            return vec4<f32>(finite_colour(colour), ppr_confidence(s.xy));
        }
    }
    return flat;
}

// The reflection at `vpos` from its own intermediate value and its neighbours' (`v[0]` the
// pixel's, `v[1..4]` at PPR_HOLE_OFFSETS): hole filling, the second ring where the first has
// no data, colour, normal maps and glossy blur. What `main` and `main_quads` store.
fn reflect_pixel(vpos: vec2<i32>, v: array<u32, 5>) -> vec4<f32> {
    let holes = (frame.flags & PPR_FLAG_HOLES) != 0u;
    var chosen = ppr_choose_value(v, holes, (frame.flags & PPR_FLAG_REPLACE_FAR) != 0u);
    if (holes && chosen.value == PPR_CLEAR_VALUE) {
        var w: array<u32, 4>;
        for (var k = 0u; k < 4u; k++) {
            w[k] = read_value(vpos + PPR_HOLE_OFFSETS_WIDE[k]);
        }
        chosen = ppr_choose_wide(w);
    }
    if (ABLATION == 2u) {
        let d = ppr_decoded_offset(ppr_decode(chosen.value, frame.encoding));
        return vec4<f32>(d, vec2<f32>(chosen.holes_offset));
    }
    var colour = ppr_reflected_colour(vpos, chosen);
    if (ABLATION == 3u) {
        return colour;
    }
    if (NORMAL_MAPS && colour.a > 0.0) {
        colour = normal_mapped(vpos, chosen, colour);
    }
    if (GLOSSY && colour.a > 0.0) {
        let decoded = ppr_decode(chosen.value, frame.encoding);
        let src = vec2<f32>(vpos) + 0.5 - (ppr_decoded_whole_offset(decoded) - vec2<f32>(chosen.holes_offset));
        colour = ppr_glossy(vpos, src, colour);
    }
    return colour;
}

// One pixel per invocation: 16 x 16 pixels per workgroup (direct), or one active 16 x 16
// tile (INDIRECT).
@compute @workgroup_size(16, 16)
fn main(
    @builtin(global_invocation_id) global_id: vec3<u32>,
    @builtin(local_invocation_id) lid: vec3<u32>,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    if (CLEAR_NEXT && all(global_id.xy < frame.size)) {
        clear_next(global_id.xy);
    }
    if (ABLATION == 1u) {
        return;
    }
    if (!INDIRECT) {
        shade(global_id.xy);
        return;
    }
    let tiles_x = (frame.size.x + 15u) / 16u;
    if (TILE_LOOP) {
        // The same slot for every invocation of the workgroup: a uniform loop.
        let stride = groups.x * groups.y;
        for (var slot = wid.x + wid.y * groups.x; slot < active_tiles.count; slot += stride) {
            let tile = active_tiles.tiles[slot];
            shade(vec2<u32>(tile % tiles_x, tile / tiles_x) * 16u + lid.xy);
        }
        return;
    }
    let slot = ppr_active_slot(wid);
    if (slot >= active_tiles.count) {
        return;
    }
    let tile = active_tiles.tiles[slot];
    shade(vec2<u32>(tile % tiles_x, tile / tiles_x) * 16u + lid.xy);
}

// The reflection at pixel `gid` (none outside the viewport).
fn shade(gid: vec2<u32>) {
    if (any(gid >= frame.size)) {
        return;
    }
    let vpos = vec2<i32>(gid);
    var v: array<u32, 5>;
    v[0] = read_value(vpos);
    for (var k = 0u; k < 4u; k++) {
        v[k + 1u] = read_value(vpos + PPR_HOLE_OFFSETS[k]);
    }
    textureStore(output, vpos, reflect_pixel(vpos, v));
}

// Two by two pixels per invocation, sharing their neighbourhood: the four pixels' first
// rings (PPR_HOLE_OFFSETS: right, below, below right, left) lie in a 4 x 3 block of which
// 11 values are used, read once instead of 20 times; and a quarter of the invocations to
// launch. Mirrors in direct dispatch, 32 x 32 pixels per workgroup, when the bench asks
// (ReflectionVariant::runs_quads says why not by default); the same image as `main`, bit for bit.
@compute @workgroup_size(16, 16)
fn main_quads(@builtin(global_invocation_id) global_id: vec3<u32>) {
    let base = global_id.xy * 2u;
    if (any(base >= frame.size)) {
        return;
    }
    for (var q = 0u; CLEAR_NEXT && q < 4u; q++) {
        let p = base + vec2<u32>(q & 1u, q >> 1u);
        if (all(p < frame.size)) {
            clear_next(p);
        }
    }
    if (ABLATION == 1u) {
        return;
    }
    let b = vec2<i32>(base);
    // r<row><col> is the value at b + (col - 1, row); written out, not a private array
    // indexed in loops (which a driver may keep in local memory).
    let r00 = read_value(b + vec2<i32>(-1, 0));
    let r01 = read_value(b);
    let r02 = read_value(b + vec2<i32>(1, 0));
    let r03 = read_value(b + vec2<i32>(2, 0));
    let r10 = read_value(b + vec2<i32>(-1, 1));
    let r11 = read_value(b + vec2<i32>(0, 1));
    let r12 = read_value(b + vec2<i32>(1, 1));
    let r13 = read_value(b + vec2<i32>(2, 1));
    let r21 = read_value(b + vec2<i32>(0, 2));
    let r22 = read_value(b + vec2<i32>(1, 2));
    let r23 = read_value(b + vec2<i32>(2, 2));
    // Each pixel's own value, then right, below, below right, left (PPR_HOLE_OFFSETS).
    let c00 = reflect_pixel(b, array<u32, 5>(r01, r02, r11, r12, r00));
    let c10 = reflect_pixel(b + vec2<i32>(1, 0), array<u32, 5>(r02, r03, r12, r13, r01));
    let c01 = reflect_pixel(b + vec2<i32>(0, 1), array<u32, 5>(r11, r12, r21, r22, r10));
    let c11 = reflect_pixel(b + vec2<i32>(1, 1), array<u32, 5>(r12, r13, r22, r23, r11));
    let size = vec2<i32>(frame.size);
    textureStore(output, b, c00);
    if (b.x + 1 < size.x) {
        textureStore(output, b + vec2<i32>(1, 0), c10);
    }
    if (b.y + 1 < size.y) {
        textureStore(output, b + vec2<i32>(0, 1), c01);
        if (b.x + 1 < size.x) {
            textureStore(output, b + vec2<i32>(1, 1), c11);
        }
    }
}
