// Glossy reflections (beyond the seed): a reflector with roughness blurs its reflection
// by a footprint that PPR knows exactly per pixel. The reflected point q and the
// reflecting point p are both on screen (the decoded offset and the two depths), so the
// reflection distance |q - p| is exact: near contact the reflection stays sharp, far away
// it spreads, as a rough mirror's does.
//
// With a colour pyramid (`glossy.pyramid_levels` > 0, glossy_pyramid.wgsl) a footprint of
// GLOSSY_PYRAMID_MIN_RADIUS_PX or more takes at most GLOSSY_PYRAMID_TAPS taps, each read
// from the pyramid at the level whose texel matches its share of the lobe
// (`ppr_glossy_pyramid`): a prefiltered tap stands for the area around it instead of a
// point, so fewer taps reach a smooth blur, and they read half-size or smaller texels.
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
// Needs `frame`, `color_tex`, `linear_sampler` (trilinear), `depth_tex`, `glossy_pyramid`,
// VIEW, and the uniform `glossy: GlossyShapes` with the frame's visible glossy reflectors.

const GLOSSY_CAPACITY: u32 = 32u;
// Fewest taps, taps per pixel of footprint radius (the most: `glossy.max_taps`).
const GLOSSY_MIN_TAPS: u32 = 4u;
const GLOSSY_TAPS_PER_PX: f32 = 3.0;
// Footprints under this radius are left sharp (the bilinear sample already spans it).
const GLOSSY_MIN_RADIUS_PX: f32 = 0.5;
// cos and sin of the golden angle (2.39996323 rad), the turn between successive taps.
const GLOSSY_GOLDEN_COS: f32 = -0.73736888;
const GLOSSY_GOLDEN_SIN: f32 = 0.67549029;
// With the pyramid: footprints from this radius take prefiltered taps, at most this many.
const GLOSSY_PYRAMID_MIN_RADIUS_PX: f32 = 2.0;
const GLOSSY_PYRAMID_TAPS: u32 = 12u;
const GLOSSY_PI: f32 = 3.14159265;

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
    // Levels of the colour pyramid (0: none, the taps read the full-size colour).
    pyramid_levels: u32,
    // The pyramid's region in pixels: min xy, max xy.
    pyramid_rect: vec4<u32>,
    // Added to each pyramid tap's level (negative: sharper than its share of the lobe).
    pyramid_lod_bias: f32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
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
    if (glossy.pyramid_levels > 0u && radius >= GLOSSY_PYRAMID_MIN_RADIUS_PX) {
        return ppr_glossy_pyramid(src, sharp, radius, along, side, cos_i, min(taps, GLOSSY_PYRAMID_TAPS));
    }
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

// `ppr_glossy`'s taps read from the colour pyramid: the same lobe (`taps` samples of it
// around the source pixel `src`, a footprint of `radius` pixels, `along` the reflection's
// screen direction and `side` across it, narrowed by `cos_i`), each tap at the pyramid
// level whose texel is its share of the lobe's area. Importance sampling gives each tap
// probability 1 / taps; where the lobe's density (in radii, p(r) = 1 / (π (1 + r²)²))
// is low the taps lie far apart, so tap k stands for an area of π (1 + r_k²)² cos_i /
// taps square radii: a square of side radius (1 + r_k²) √(π cos_i / taps) pixels, read
// at the level whose texel has that side (level 0 is two pixels) plus
// `glossy.pyramid_lod_bias` (crate::glossy_pyramid::LOD_BIAS says why it is negative).
fn ppr_glossy_pyramid(
    src: vec2<f32>,
    sharp: vec4<f32>,
    radius: f32,
    along: vec2<f32>,
    side: vec2<f32>,
    cos_i: f32,
    taps: u32,
) -> vec4<f32> {
    // Texture coordinates per pixel (level 0 covers a whole number of 32-pixel blocks).
    let per_px = 0.5 / vec2<f32>(textureDimensions(glossy_pyramid, 0));
    // The region built this frame, less half a level-4 texel where it ends inside the
    // viewport (its texels there hold another frame's colour).
    let rect = vec4<f32>(glossy.pyramid_rect);
    let size = frame.resolution.xy;
    let lo = select(rect.xy + 16.0, vec2<f32>(0.0), rect.xy <= vec2<f32>(0.0)) * per_px;
    let hi = max(select(rect.zw - 16.0, size, rect.zw >= size) * per_px, lo);
    let src_uv = src * per_px;
    let along_uv = radius * along * per_px;
    let side_uv = radius * cos_i * side * per_px;
    let footprint = radius * sqrt(GLOSSY_PI * cos_i / f32(taps));
    var turn = vec2<f32>(1.0, 0.0);
    var sum = sharp.rgb;
    for (var k = 0u; k < taps; k++) {
        let a = f32(k) + 0.5;
        let r = a * inverseSqrt(a * (f32(taps) - a));
        let uv = clamp(src_uv + r * (turn.x * along_uv + turn.y * side_uv), lo, hi);
        let level = max(log2(max(footprint * (1.0 + r * r), 1.0)) - 1.0 + glossy.pyramid_lod_bias, 0.0);
        sum += textureSampleLevel(glossy_pyramid, linear_sampler, uv, level).rgb;
        turn = vec2<f32>(
            turn.x * GLOSSY_GOLDEN_COS - turn.y * GLOSSY_GOLDEN_SIN,
            turn.y * GLOSSY_GOLDEN_COS + turn.x * GLOSSY_GOLDEN_SIN,
        );
    }
    return vec4<f32>(sum / f32(taps + 1u), sharp.a);
}
