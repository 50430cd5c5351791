// Reflection pass: decode the intermediate buffer, fill holes from the neighbour with the
// smallest offset, take filtered and unfiltered colour samples and reduce bleeding in
// YCoCg. Output: reflected colour, alpha 1 where a reflection was found, 0 elsewhere.
// Seed: PPR_ReflectionPass and PPR_FixColorBleeding.

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var<storage, read> intermediate: array<u32>;
@group(0) @binding(2) var color_tex: texture_2d<f32>;
@group(0) @binding(3) var linear_sampler: sampler;
@group(0) @binding(4) var output: texture_storage_2d<rgba16float, write>;

@group(0) @binding(5) var<storage, read> active_tiles: ActiveTileList;

@group(0) @binding(6) var<storage, read> tile_flags: array<u32>;

// When set, the pass is dispatched indirectly with one workgroup per active tile, and
// only active tiles of the intermediate buffer were cleared this frame.
override INDIRECT: bool = false;

// Reads the intermediate buffer; outside the viewport, and (with indirect dispatch) in
// a tile that was not cleared this frame, reads as "no data".
fn read_value(p: vec2<i32>) -> u32 {
    if (any(p < vec2<i32>(0)) || any(p >= vec2<i32>(frame.size))) {
        return PPR_CLEAR_VALUE;
    }
    if (INDIRECT) {
        let tiles_x = (frame.size.x + 15u) / 16u;
        if (tile_flags[u32(p.x) / 16u + u32(p.y) / 16u * tiles_x] == 0u) {
            return PPR_CLEAR_VALUE;
        }
    }
    return intermediate[u32(p.x) + u32(p.y) * frame.size.x];
}

fn rgb_to_ycocg(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(
        0.25 * c.r + 0.5 * c.g + 0.25 * c.b,
        0.5 * c.r - 0.5 * c.b,
        -0.25 * c.r + 0.5 * c.g - 0.25 * c.b,
    );
}

fn ycocg_to_rgb(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z);
}

// PPR_FixColorBleeding: keep the filtered colour perceptually close to the unfiltered one.
fn fix_color_bleeding(filtered: vec3<f32>, unfiltered: vec3<f32>) -> vec3<f32> {
    var f = rgb_to_ycocg(filtered);
    var u = rgb_to_ycocg(unfiltered);
    let f_chroma = f.yz / max(0.0001, f.x);
    let u_chroma = u.yz / max(0.0001, u.x);
    let luma_factor = saturate(3.0 * abs(f.x - u.x));
    let chroma_factor = saturate(1.4 * length(f_chroma - u_chroma));
    let y = mix(f.x, u.x, luma_factor);
    let cocg = mix(f_chroma, u_chroma, chroma_factor);
    return ycocg_to_rgb(vec3<f32>(y, cocg * y));
}

@compute @workgroup_size(16, 16)
fn main(
    @builtin(global_invocation_id) global_id: vec3<u32>,
    @builtin(local_invocation_id) lid: vec3<u32>,
    @builtin(workgroup_id) wid: vec3<u32>,
) {
    var gid = global_id.xy;
    if (INDIRECT) {
        let slot = ppr_active_slot(wid);
        if (slot >= active_tiles.count) {
            return;
        }
        let tiles_x = (frame.size.x + 15u) / 16u;
        let tile = active_tiles.tiles[slot];
        gid = vec2<u32>(tile % tiles_x, tile / tiles_x) * 16u + lid.xy;
    }
    if (any(gid >= frame.size)) {
        return;
    }
    let vpos = vec2<i32>(gid);
    var vposread = vpos;
    var holes_offset = vec2<f32>(0.0);

    if ((frame.flags & PPR_FLAG_HOLES) != 0u) {
        let v0 = read_value(vpos);
        let h1 = vec2<i32>(1, 0);
        let h2 = vec2<i32>(0, 1);
        let h3 = vec2<i32>(1, 1);
        let h4 = vec2<i32>(-1, 0);
        let v1 = read_value(vpos + h1);
        let v2 = read_value(vpos + h2);
        let v3 = read_value(vpos + h3);
        let v4 = read_value(vpos + h4);
        let minv = min(min(min(v0, v1), min(v2, v3)), v4);

        // Fill if this pixel has no data, or a neighbour's reflection is much closer.
        var allow_hole_fill = true;
        if (v0 != PPR_CLEAR_VALUE) {
            let d0 = ppr_decoded_offset(ppr_decode(v0, frame.encoding));
            let dmin = ppr_decoded_offset(ppr_decode(minv, frame.encoding));
            let diff = d0 - dmin;
            let min_dist = 6.0;
            allow_hole_fill = dot(diff, diff) > min_dist * min_dist;
        }
        if (allow_hole_fill) {
            if (minv == v1) { vposread = vpos + h1; }
            if (minv == v2) { vposread = vpos + h2; }
            if (minv == v3) { vposread = vpos + h3; }
            if (minv == v4) { vposread = vpos + h4; }
            holes_offset = vec2<f32>(vposread - vpos);
        }
    }

    let v = read_value(vposread);
    if (v == PPR_CLEAR_VALUE) {
        textureStore(output, vpos, vec4<f32>(0.0));
        return;
    }
    let decoded = ppr_decode(v, frame.encoding);
    var predicted = ppr_decoded_offset(decoded);
    // The fraction is ignored for the unfiltered sample: with a non axis-aligned offset it
    // could land on the neighbouring pixel.
    var predicted_unfiltered = ppr_decoded_whole_offset(decoded);
    if (any(predicted != vec2<f32>(0.0))) {
        let dir = normalize(predicted);
        predicted_unfiltered -= holes_offset;
        predicted -= 2.0 * dir * dot(dir, holes_offset);
    }
    if (all(predicted == vec2<f32>(0.0))) {
        textureStore(output, vpos, vec4<f32>(0.0));
        return;
    }

    let target_crd = vec2<f32>(vpos) + 0.5 - predicted;
    let target_unfiltered = vec2<f32>(vpos) + 0.5 - predicted_unfiltered;
    let unfiltered_px = clamp(vec2<i32>(floor(target_unfiltered)), vec2<i32>(0), vec2<i32>(frame.size) - 1);
    let unfiltered = textureLoad(color_tex, unfiltered_px, 0).rgb;
    var result = unfiltered;
    if ((frame.flags & PPR_FLAG_FILTERING) != 0u) {
        let filtered = textureSampleLevel(color_tex, linear_sampler, target_crd * frame.resolution.zw, 0.0).rgb;
        if ((frame.flags & PPR_FLAG_ANTI_BLEEDING) != 0u) {
            result = fix_color_bleeding(filtered, unfiltered);
        } else {
            result = filtered;
        }
    }
    textureStore(output, vpos, vec4<f32>(finite_colour(result), 1.0));
}

// NaN and infinities in the scene colour never reach the output: NaN becomes 0 and
// infinities the largest f16. (Bit tests: a driver may fold `x != x` away.)
fn finite_colour(c: vec3<f32>) -> vec3<f32> {
    let bits = bitcast<vec3<u32>>(c);
    let non_finite = (bits & vec3<u32>(0x7f800000u)) == vec3<u32>(0x7f800000u);
    let has_mantissa = (bits & vec3<u32>(0x007fffffu)) != vec3<u32>(0u);
    let is_nan = select(vec3<bool>(false), has_mantissa, non_finite);
    return clamp(select(c, vec3<f32>(0.0), is_nan), vec3<f32>(-65504.0), vec3<f32>(65504.0));
}
