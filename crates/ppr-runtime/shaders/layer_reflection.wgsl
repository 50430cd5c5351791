// Layer reflection pass: the reflections of surfaces that are not in the depth buffer's
// opaque layer — glass panels (bonus slides: "transparent reflectors") and water planes
// (seed 002: a reflection layer per water plane). Each such reflector was given a region
// of the atlas (sized by its screen rectangle), which the projection pass wrote. Per
// pixel: the nearest layer reflector the view ray hits in front of the depth buffer, its
// atlas value with hole filling, the same sampling as the main reflection, and for water
// optionally the hash-style edge stretch (reuse the nearest valid reflection along the
// plane's projected normal). Output: colour, alpha the confidence (as the main reflection:
// 0 where no layer reflection was found), over the 16 x 16 tiles of the layers' common
// rectangle that meet some layer's own rectangle (the others are not written; the reduced
// tiers write them all). One workgroup a tile: a grid over the common rectangle with
// PPR_FLAG_LAYER_EVERY_TILE, else a list of the tiles each layer's rectangle meets, layer
// after layer (listed_tile; FramePlan::layer_tiles on the CPU sizes the dispatch).

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var<storage, read> atlas: array<u32>;
@group(0) @binding(2) var<storage, read> layers: array<Layer>;
@group(0) @binding(3) var<storage, read> shapes: array<Shape>;
@group(0) @binding(4) var depth_tex: texture_2d<f32>;
@group(0) @binding(5) var color_tex: texture_2d<f32>;
@group(0) @binding(6) var linear_sampler: sampler;
@group(0) @binding(7) var output: texture_storage_2d<rgba16float, write>;

// Longest edge stretch, pixels.
const STRETCH_MAX: i32 = 48;
// The edge stretch ends where its steps leave the layer's rectangle (false: bench only,
// every step is read; the same image).
override STRETCH_STOPS_AT_RECT: bool = true;
// Steps of the edge stretch loaded together (divides STRETCH_MAX).
const STRETCH_BATCH: i32 = 8;

fn read_layer(l: Layer, p: vec2<i32>) -> u32 {
    if (any(p < vec2<i32>(l.rect_min)) || any(p >= vec2<i32>(l.rect_max))) {
        return PPR_CLEAR_VALUE;
    }
    let local = vec2<u32>(p) - l.rect_min;
    return atlas[l.offset + local.x + local.y * (l.rect_max.x - l.rect_min.x)];
}

// The tile (in tiles from frame.layer_origin) of entry `index` of the list of the tiles
// each layer's rectangle meets, layer after layer (a tile two rectangles meet is listed
// twice, and shaded alike by both workgroups); w 0 past the list's end.
fn listed_tile(index: u32) -> vec3<u32> {
    var rest = index;
    for (var i = 0u; i < frame.layer_count; i++) {
        let l = layers[i];
        let lo = (l.rect_min - frame.layer_origin) / 16u;
        let span = (l.rect_max - frame.layer_origin + 15u) / 16u - lo;
        let n = span.x * span.y;
        if (rest < n) {
            return vec3<u32>(lo + vec2<u32>(rest % span.x, rest / span.x), 1u);
        }
        rest -= n;
    }
    return vec3<u32>(0u);
}

@compute @workgroup_size(16, 16)
fn main(
    @builtin(local_invocation_id) lid: vec3<u32>,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    // Tiles of the layers' common rectangle that meet no layer's own are not dispatched
    // (the rectangles of a pond and a far window span much more of the screen together
    // than apart: on the demo's overview at 4K, 4.7 M pixels against 0.5 M): the
    // workgroups take the list of the tiles that do. The reduced tiers shade them all
    // (PPR_FLAG_LAYER_EVERY_TILE, a grid over the common rectangle): their upsample reads
    // the whole rectangle. Uniform branches.
    var tile = wid.xy;
    if ((frame.flags & PPR_FLAG_LAYER_EVERY_TILE) == 0u) {
        let listed = listed_tile(wid.x + wid.y * groups.x);
        if (listed.z == 0u) {
            return;
        }
        tile = listed.xy;
    }
    let local = tile * 16u + lid.xy;
    let pixel = frame.layer_origin + local;
    if (any(pixel >= frame.size) || any(local >= frame.layer_extent)) {
        return;
    }
    let vpos = vec2<i32>(pixel);
    // Pixels of such a tile outside every layer's rectangle store no reflection, before
    // the two unprojections below.
    var in_some_rect = false;
    for (var i = 0u; i < frame.layer_count; i++) {
        let l = layers[i];
        if (all(pixel >= l.rect_min) && all(pixel < l.rect_max)) {
            in_some_rect = true;
            break;
        }
    }
    if (!in_some_rect) {
        textureStore(output, vpos, vec4<f32>(0.0));
        return;
    }
    let ray = normalize(ppr_unproject(vec2<f32>(pixel) + 0.5, 0.5));
    var surface = 3.0e38;
    let d = textureLoad(depth_tex, vpos, 0).r;
    if (ppr_is_valid_depth(d)) {
        surface = length(ppr_unproject(vec2<f32>(pixel) + 0.5, d));
    }
    // The nearest layer reflector hit in front of (or on) the opaque surface.
    var best = 0xffffffffu;
    var best_t = 3.0e38;
    for (var i = 0u; i < frame.layer_count; i++) {
        let l = layers[i];
        if (any(pixel < l.rect_min) || any(pixel >= l.rect_max)) {
            continue;
        }
        let s = shapes[l.shape];
        let dn = dot(ray, s.normal);
        if (!(dn < 0.0)) {
            continue;
        }
        let t = s.plane_dist / dn;
        let local = ray * t - s.center;
        let margin = 1e-5 * t;
        if (abs(dot(local, s.axis_u)) > s.half_u + margin || abs(dot(local, s.axis_v)) > s.half_v + margin) {
            continue;
        }
        if (t > 0.0 && t <= surface * 1.001 + 1e-4 && t < best_t) {
            best = i;
            best_t = t;
        }
    }
    if (best == 0xffffffffu) {
        textureStore(output, vpos, vec4<f32>(0.0));
        return;
    }
    let l = layers[best];
    var v: array<u32, 5>;
    v[0] = read_layer(l, vpos);
    for (var k = 0u; k < 4u; k++) {
        v[k + 1u] = read_layer(l, vpos + PPR_HOLE_OFFSETS[k]);
    }
    var chosen = ppr_choose_value(v, (frame.flags & PPR_FLAG_HOLES) != 0u, (frame.flags & PPR_FLAG_REPLACE_FAR) != 0u);
    var colour = ppr_reflected_colour(vpos, chosen);
    if (colour.a == 0.0 && l.kind == PPR_KIND_WATER && (frame.flags & PPR_FLAG_WATER_STRETCH) != 0u) {
        // Edge stretch: the nearest valid reflection along the plane's projected normal
        // (up the screen for a water plane under an upright camera).
        let s = shapes[l.shape];
        let hit = ray * best_t;
        let a = ppr_project(hit);
        let b = ppr_project(hit + s.normal * (best_t * 0.01));
        let dir = normalize(b.xy - a.xy);
        if (a.z > 0.0 && b.z > 0.0 && ppr_is_finite2(dir)) {
            // STRETCH_BATCH steps a trip, their loads issued together: a pixel that finds
            // nothing (a reflection of the sky) waits on 48 / STRETCH_BATCH round trips to
            // memory instead of 48. The first valid step wins, as one step a trip would.
            // Steps past the layer's rectangle read nothing (read_layer): each coordinate
            // of a step moves monotonically with k, so the walk ends where the first
            // coordinate must have left the rectangle (a pixel near the rectangle's edge
            // that finds nothing stops there instead of after STRETCH_MAX steps).
            let room = select(
                vec2<f32>(vpos - vec2<i32>(l.rect_min)),
                vec2<f32>(vec2<i32>(l.rect_max) - 1 - vpos),
                dir > vec2<f32>(0.0),
            );
            let reach = (room + 0.5) / max(abs(dir), vec2<f32>(1e-6));
            let steps = select(STRETCH_MAX, min(i32(min(reach.x, reach.y)) + 1, STRETCH_MAX), STRETCH_STOPS_AT_RECT);
            for (var k0 = 1; k0 <= steps; k0 += STRETCH_BATCH) {
                var q: array<vec2<i32>, STRETCH_BATCH>;
                var v: array<u32, STRETCH_BATCH>;
                for (var j = 0; j < STRETCH_BATCH; j++) {
                    q[j] = vpos + vec2<i32>(round(dir * f32(k0 + j)));
                    v[j] = read_layer(l, q[j]);
                }
                // Backwards, so the first valid step is kept (constant indices once
                // unrolled: no array in local memory).
                var hit = false;
                var value = 0u;
                var at = vpos;
                for (var j = STRETCH_BATCH - 1; j >= 0; j--) {
                    if (v[j] != PPR_CLEAR_VALUE) {
                        hit = true;
                        value = v[j];
                        at = q[j];
                    }
                }
                if (hit) {
                    chosen.value = value;
                    chosen.holes_offset = at - vpos;
                    colour = ppr_reflected_colour(vpos, chosen);
                    break;
                }
            }
        }
    }
    textureStore(output, vpos, colour);
}
