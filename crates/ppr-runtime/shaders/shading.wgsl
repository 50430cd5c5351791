// What the reflection passes share (prepended, after view.wgsl, to reflection.wgsl and
// layer_reflection.wgsl, which declare `frame`, `color_tex` and `linear_sampler`): hole
// filling, decoding into filtered and unfiltered samples, YCoCg anti-bleeding, the
// confidence (output alpha) and the finite-colour guard. Seed: PPR_ReflectionPass and
// PPR_FixColorBleeding.

// Neighbours read for hole filling, in the seed's order.
const PPR_HOLE_OFFSETS = array<vec2<i32>, 4>(vec2<i32>(1, 0), vec2<i32>(0, 1), vec2<i32>(1, 1), vec2<i32>(-1, 0));

// Read when the first ring has no data either: the pixel above (the seed reads none) and
// the pixels two away, so that gaps of two pixels close too (a mirror seen at a steep angle
// in another mirror spreads one source pixel over several targets).
const PPR_HOLE_OFFSETS_WIDE = array<vec2<i32>, 4>(vec2<i32>(0, -1), vec2<i32>(2, 0), vec2<i32>(0, 2), vec2<i32>(-2, 0));

// The value a pixel's reflection is computed from, and the neighbour it came from.
struct PprChosen {
    value: u32,
    // Neighbour offset (0 when the pixel's own value is used).
    holes_offset: vec2<i32>,
}

// Hole filling: take the neighbour with the smallest offset when this pixel has no data,
// or, with `replace_far` (the seed's rule, off by default), when that neighbour's
// reflection is much closer (more than 6 px) than this one's. `v[0]` is the pixel's own
// value, `v[1..4]` the neighbours at PPR_HOLE_OFFSETS.
fn ppr_choose_value(v: array<u32, 5>, holes: bool, replace_far: bool) -> PprChosen {
    var chosen: PprChosen;
    chosen.value = v[0];
    chosen.holes_offset = vec2<i32>(0);
    if (!holes) {
        return chosen;
    }
    let minv = min(min(min(v[0], v[1]), min(v[2], v[3])), v[4]);
    var allow_hole_fill = true;
    if (v[0] != PPR_CLEAR_VALUE) {
        if (!replace_far) {
            return chosen;
        }
        let d0 = ppr_decoded_offset(ppr_decode(v[0], frame.encoding));
        let dmin = ppr_decoded_offset(ppr_decode(minv, frame.encoding));
        let diff = d0 - dmin;
        let min_dist = 6.0;
        allow_hole_fill = dot(diff, diff) > min_dist * min_dist;
    }
    if (allow_hole_fill) {
        // As the seed: the last matching neighbour wins.
        for (var k = 0u; k < 4u; k++) {
            if (minv == v[k + 1u]) {
                chosen.holes_offset = PPR_HOLE_OFFSETS[k];
            }
        }
        chosen.value = minv;
    }
    return chosen;
}

// Hole filling's second ring: the neighbour of `w` (at PPR_HOLE_OFFSETS_WIDE) with the
// smallest offset, the last of equal ones as in the first ring; no data when none has any.
fn ppr_choose_wide(w: array<u32, 4>) -> PprChosen {
    var chosen: PprChosen;
    chosen.value = min(min(w[0], w[1]), min(w[2], w[3]));
    chosen.holes_offset = vec2<i32>(0);
    if (chosen.value != PPR_CLEAR_VALUE) {
        for (var k = 0u; k < 4u; k++) {
            if (chosen.value == w[k]) {
                chosen.holes_offset = PPR_HOLE_OFFSETS_WIDE[k];
            }
        }
    }
    return chosen;
}

// Confidence of a reflection whose colour was sampled at `source` (pixels): 1 more than
// frame.border_fade_px from every screen edge, falling linearly towards the edge. A sample
// is never taken nearer than half a pixel from it, so found reflections keep alpha > 0.
fn ppr_confidence(source: vec2<f32>) -> f32 {
    let margin = frame.border_fade_px;
    if (!(margin > 0.0)) {
        return 1.0;
    }
    let to_edge = min(source, frame.resolution.xy - source);
    return saturate(max(min(to_edge.x, to_edge.y), 0.5) / margin);
}

// The reflected colour at `vpos` from a chosen value, alpha its confidence (0 when there is
// none).
fn ppr_reflected_colour(vpos: vec2<i32>, chosen: PprChosen) -> vec4<f32> {
    if (chosen.value == PPR_CLEAR_VALUE) {
        return vec4<f32>(0.0);
    }
    let decoded = ppr_decode(chosen.value, frame.encoding);
    var predicted = ppr_decoded_offset(decoded);
    // The fraction is ignored for the unfiltered sample: with a non axis-aligned offset it
    // could land on the neighbouring pixel.
    var predicted_unfiltered = ppr_decoded_whole_offset(decoded);
    let holes_offset = vec2<f32>(chosen.holes_offset);
    if (any(predicted != vec2<f32>(0.0))) {
        let dir = normalize(predicted);
        predicted_unfiltered -= holes_offset;
        predicted -= 2.0 * dir * dot(dir, holes_offset);
    }
    if (all(predicted == vec2<f32>(0.0))) {
        return vec4<f32>(0.0);
    }
    let target_crd = vec2<f32>(vpos) + 0.5 - predicted;
    let target_unfiltered = vec2<f32>(vpos) + 0.5 - predicted_unfiltered;
    let unfiltered_px = clamp(vec2<i32>(floor(target_unfiltered)), vec2<i32>(0), vec2<i32>(frame.size) - 1);
    // The colour is larger than the frame in the reduced-resolution tiers (they read the
    // full-size colour): there each sample is prefiltered over the reduced pixel's
    // footprint, bilinear taps between texels, as a reduced colour would be. At full
    // resolution the loads are the seed's.
    let reduced = any(vec2<f32>(textureDimensions(color_tex)) != frame.resolution.xy);
    var unfiltered: vec3<f32>;
    if (reduced) {
        let uv = (vec2<f32>(unfiltered_px) + 0.5) * frame.resolution.zw;
        unfiltered = textureSampleLevel(color_tex, linear_sampler, uv, 0.0).rgb;
    } else {
        unfiltered = textureLoad(color_tex, unfiltered_px, 0).rgb;
    }
    var result = unfiltered;
    var source = vec2<f32>(unfiltered_px) + 0.5;
    if ((frame.flags & PPR_FLAG_FILTERING) != 0u) {
        var filtered: vec3<f32>;
        if (reduced) {
            let q = 0.25 * frame.resolution.zw;
            let uv = target_crd * frame.resolution.zw;
            filtered = 0.25 * (textureSampleLevel(color_tex, linear_sampler, uv + vec2<f32>(-q.x, -q.y), 0.0).rgb
                + textureSampleLevel(color_tex, linear_sampler, uv + vec2<f32>(q.x, -q.y), 0.0).rgb
                + textureSampleLevel(color_tex, linear_sampler, uv + vec2<f32>(-q.x, q.y), 0.0).rgb
                + textureSampleLevel(color_tex, linear_sampler, uv + vec2<f32>(q.x, q.y), 0.0).rgb);
        } else {
            filtered = textureSampleLevel(color_tex, linear_sampler, target_crd * frame.resolution.zw, 0.0).rgb;
        }
        source = target_crd;
        if ((frame.flags & PPR_FLAG_ANTI_BLEEDING) != 0u) {
            result = fix_color_bleeding(filtered, unfiltered);
        } else {
            result = filtered;
        }
    }
    return vec4<f32>(finite_colour(result), ppr_confidence(source));
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
// The seed's thresholds are absolute luma (for colour in [0, 1]); on linear HDR input they
// saturate where the scene is bright (always unfiltered) and vanish where it is dark
// (always filtered). Here luma is measured relative to the brighter of the two samples,
// which is the seed's scale where that luma is 1, and the same decision at any exposure.
fn fix_color_bleeding(filtered: vec3<f32>, unfiltered: vec3<f32>) -> vec3<f32> {
    let f = rgb_to_ycocg(filtered);
    let u = rgb_to_ycocg(unfiltered);
    // 1e-10: far below the smallest f16 colour (6e-8), only keeps black from dividing by 0.
    let scale = max(max(f.x, u.x), 1e-10);
    let f_chroma = f.yz / max(0.0001 * scale, f.x);
    let u_chroma = u.yz / max(0.0001 * scale, u.x);
    let luma_factor = saturate(3.0 * abs(f.x - u.x) / scale);
    let chroma_factor = saturate(1.4 * length(f_chroma - u_chroma));
    let y = mix(f.x, u.x, luma_factor);
    let cocg = mix(f_chroma, u_chroma, chroma_factor);
    return ycocg_to_rgb(vec3<f32>(y, cocg * y));
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
