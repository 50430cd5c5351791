// Glossy reflections (beyond the seed): a reflector with roughness blurs its reflection
// by a footprint that PPR knows exactly per pixel. The reflected point q and the
// reflecting point p are both on screen (the decoded offset and the two depths), so the
// reflection distance |q - p| is exact: near contact the reflection stays sharp, far away
// it spreads, as a rough mirror's does.
//
// The lobe: GGX with alpha = roughness². A microfacet normal tilted by θ turns the
// reflected ray by 2θ, so the reflected point moves by about 2 tan θ |q - p|; across the
// plane of incidence the turn shrinks by cos θi (the reflection stretches along the view,
// as wet streets do). Three samples per pixel of footprint radius (4 to glossy.max_taps) of that
// distribution (tan θ = alpha √(ξ/(1−ξ)),
// the GGX inverse CDF, at stratified ξ and golden-angle azimuths) are read around the
// reflected point's pixel, each weighted equally (importance sampling), plus the sharp
// sample. The screen footprint of a world radius at q is its projection at q's distance.
//
// Needs `frame`, `color_tex`, `linear_sampler`, `depth_tex`, VIEW, and the uniform
// `glossy: GlossyShapes` with the frame's visible glossy reflectors.

const GLOSSY_CAPACITY: u32 = 32u;
// Fewest taps, taps per pixel of footprint radius (the most: `glossy.max_taps`).
const GLOSSY_MIN_TAPS: u32 = 4u;
const GLOSSY_TAPS_PER_PX: f32 = 3.0;
// Footprints under this radius are left sharp (the bilinear sample already spans it).
const GLOSSY_MIN_RADIUS_PX: f32 = 0.5;
// cos and sin of the golden angle (2.39996323 rad), the turn between successive taps.
const GLOSSY_GOLDEN_COS: f32 = -0.73736888;
const GLOSSY_GOLDEN_SIN: f32 = 0.67549029;

struct GlossyShape {
    // Camera-relative plane: xyz the normal, w = -dot(normal, center).
    plane: vec4<f32>,
    // xyz the camera-relative centre, w the roughness.
    center: vec4<f32>,
    // Unit axes, w the half extents.
    axis_u: vec4<f32>,
    axis_v: vec4<f32>,
    // The screen rectangle, pixels: min xy, max xy.
    rect: vec4<f32>,
}

struct GlossyShapes {
    count: u32,
    // The largest footprint radius, pixels.
    max_radius_px: f32,
    // The most taps per pixel.
    max_taps: u32,
    _pad: u32,
    shapes: array<GlossyShape, GLOSSY_CAPACITY>,
}

// Whether the pixel centre `c` is inside some glossy reflector's screen rectangle (no
// depth needed: pixels outside every one are mirrors).
fn ppr_glossy_candidate(c: vec2<f32>) -> bool {
    for (var i = 0u; i < glossy.count; i++) {
        let r = glossy.shapes[i].rect;
        if (all(c >= r.xy) && all(c <= r.zw)) {
            return true;
        }
    }
    return false;
}

// The roughness of the glossy reflector the camera-relative point `p` (at pixel centre `c`)
// lies on, 0 when none.
fn ppr_glossy_roughness(p: vec3<f32>, c: vec2<f32>) -> f32 {
    let tolerance = 2e-3 * length(p) + 1e-3;
    for (var i = 0u; i < glossy.count; i++) {
        let s = glossy.shapes[i];
        if (any(c < s.rect.xy) || any(c > s.rect.zw)) {
            continue;
        }
        let d = p - s.center.xyz;
        if (abs(dot(s.plane.xyz, p) + s.plane.w) <= tolerance
            && abs(dot(d, s.axis_u.xyz)) <= s.axis_u.w + tolerance
            && abs(dot(d, s.axis_v.xyz)) <= s.axis_v.w + tolerance) {
            return s.center.w;
        }
    }
    return 0.0;
}

// The glossy reflection at `vpos` whose sharp reflection is `sharp` (source pixel `src`,
// from the decoded offset), or `sharp` where the reflector is a mirror or the footprint
// is under a pixel.
fn ppr_glossy(vpos: vec2<i32>, src: vec2<f32>, sharp: vec4<f32>) -> vec4<f32> {
    let c = vec2<f32>(vpos) + 0.5;
    if (!ppr_glossy_candidate(c)) {
        return sharp;
    }
    let d_here = valid_depth_at(vpos);
    if (d_here < 0.0) {
        return sharp;
    }
    // Mirrors leave here, before the reflected point's depth is read.
    let p = ppr_unproject(c, d_here);
    let roughness = ppr_glossy_roughness(p, c);
    // max_taps 0: the lookup only (the bench's cost profile).
    if (!(roughness > 0.0) || glossy.max_taps == 0u) {
        return sharp;
    }
    let d_src = valid_depth_at(vec2<i32>(floor(src)));
    if (d_src < 0.0) {
        return sharp;
    }
    let q = ppr_unproject(floor(src) + 0.5, d_src);
    let v = normalize(p);
    let to_q = q - p;
    let reach = length(to_q);
    let n_flat = normalize(to_q / max(reach, 1e-20) - v);
    if (!ppr_is_finite3(n_flat) || !ppr_is_finite3(q)) {
        return sharp;
    }
    let alpha = roughness * roughness;
    // World radius of the median microfacet (tan θ = alpha), projected at q: move q across
    // its view ray by it and measure on screen.
    let across = normalize(cross(q, n_flat));
    let s0 = ppr_project(q);
    let s1 = ppr_project(q + across * (2.0 * alpha * reach));
    let radius = min(length(s1.xy - s0.xy), glossy.max_radius_px);
    if (!(radius >= GLOSSY_MIN_RADIUS_PX) || s0.z == 0.0 || s1.z == 0.0) {
        return sharp;
    }
    // max_taps 1: the footprint without its taps (the bench's cost profile).
    if (glossy.max_taps == 1u) {
        return vec4<f32>(sharp.rgb * (1.0 + 1e-30 * radius), sharp.a);
    }
    // Taps scale with the footprint: a few pixels' blur needs few bilinear taps.
    let taps = clamp(u32(radius * GLOSSY_TAPS_PER_PX), min(GLOSSY_MIN_TAPS, glossy.max_taps), glossy.max_taps);
    // Along: the reflection's screen direction; across it the lobe narrows by cos θi.
    var along = src - (vec2<f32>(vpos) + 0.5);
    along = select(vec2<f32>(0.0, 1.0), along / length(along), length(along) > 1e-3);
    let side = vec2<f32>(-along.y, along.x);
    let cos_i = clamp(dot(-v, n_flat), 0.05, 1.0);
    // Tap k: radius * r_k * (cos(phi_k) along + sin(phi_k) cos_i side), phi_k = k times the
    // golden angle, r_k = sqrt(xi / (1 - xi)) at xi = (k + 0.5) / taps. In texture
    // coordinates, with one transcendental a tap: r_k = a * inverseSqrt(a * b) for
    // a = k + 0.5, b = taps - a, and (cos, sin) turned by the golden angle each tap (a
    // rotation, four products; within 1e-6 of the direct cos and sin over 12 taps).
    let src_uv = src * frame.resolution.zw;
    let along_uv = radius * along * frame.resolution.zw;
    let side_uv = radius * cos_i * side * frame.resolution.zw;
    var turn = vec2<f32>(1.0, 0.0);
    var sum = sharp.rgb;
    for (var k = 0u; k < taps; k++) {
        let a = f32(k) + 0.5;
        let r = a * inverseSqrt(a * (f32(taps) - a));
        let uv = src_uv + r * (turn.x * along_uv + turn.y * side_uv);
        sum += finite_colour(textureSampleLevel(color_tex, linear_sampler, uv, 0.0).rgb);
        turn = vec2<f32>(
            turn.x * GLOSSY_GOLDEN_COS - turn.y * GLOSSY_GOLDEN_SIN,
            turn.y * GLOSSY_GOLDEN_COS + turn.x * GLOSSY_GOLDEN_SIN,
        );
    }
    return vec4<f32>(sum / f32(taps + 1u), sharp.a);
}
