// Projection pass: for every pixel, mirror its position against the candidate reflectors,
// test the reflection point against the rectangle and its occluders, and atomicMin the
// encoded screen offset into the intermediate buffer where the pixel is reflected.
// Seed: PPR_ProjectionPassWrite, and the bonus slides' "multiple parallel shapes".
//
// Variants (pipeline-overridable constants, chosen by the FramePlan):
// - TILE_CULLING: each 16x16 workgroup first builds, in workgroup memory, the list of
//   visible shapes that may reflect some pixel of its tile (one thread per shape; a
//   conservative test of the tile's mirrored world-space bounds against the rectangle);
//   a tile without candidates does nothing more. Otherwise every pixel loops over all
//   visible shapes.
// - PARALLEL_RULE: among shapes of one parallel group that reflect a pixel, only the one
//   with the smallest plane distance writes (each pixel reflected at most once per
//   orientation). The visible list is sorted by group, and so are the tile lists.
// - OCCLUDER_TESTS: test the ray to the reflection point against the shape's occluders.
// - LAYERS: glass panels and water planes with atlas regions exist this frame (without
//   them the layer loop is compiled out).
// - DEBUG_WRITES: record, per source pixel, a bit per visible shape it wrote for.

override TILE_CULLING: bool = false;
override PARALLEL_RULE: bool = false;
override OCCLUDER_TESTS: bool = false;
override LAYERS: bool = false;
override DEBUG_WRITES: bool = false;

const TILE_SIZE: u32 = 16u;
const GROUP_THREADS: u32 = 256u;
// Capacity of a tile's shape list; a tile with more candidates loops over all shapes.
const TILE_LIST_CAPACITY: u32 = 256u;

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var depth_tex: texture_2d<f32>;
@group(0) @binding(2) var<storage, read> shapes: array<Shape>;
@group(0) @binding(3) var<storage, read> visible: array<u32>;
@group(0) @binding(4) var<storage, read> occluders: array<u32>;
@group(0) @binding(5) var<storage, read_write> intermediate: array<atomic<u32>>;
@group(0) @binding(6) var<storage, read_write> debug_writes: array<u32>;
// Layer reflectors (glass, water) and their atlas (layer_reflection.wgsl reads it).
@group(0) @binding(7) var<storage, read> layers: array<Layer>;
@group(0) @binding(8) var<storage, read_write> atlas: array<atomic<u32>>;

var<workgroup> tile_depth_min: atomic<u32>;
var<workgroup> tile_depth_max: atomic<u32>;
var<workgroup> tile_list: array<u32, TILE_LIST_CAPACITY>;
var<workgroup> tile_list_len: u32;
// One bit per thread of a chunk: which shapes passed (ranks come from popcounts).
var<workgroup> pass_bits: array<atomic<u32>, 8>;

fn is_occluded(hit: vec3<f32>, s: Shape) -> bool {
    for (var k = 0u; k < s.occluder_count; k++) {
        let o = shapes[occluders[s.occluder_start + k]];
        if ((o.flags & PPR_SHAPE_OCCLUDES) != 0u && ppr_segment_hits_shape(hit, o)) {
            return true;
        }
    }
    return false;
}

// Where the reflection of `pixel` (camera-relative position `mirrored` once mirrored)
// lands: (target x, target y, encoded value); the value is PPR_CLEAR_VALUE when it does
// not land on screen or does not fit the encoding.
fn projection_target(pixel: vec2<u32>, mirrored: vec3<f32>) -> vec3<u32> {
    let clip = frame.clip_from_rel * vec4<f32>(mirrored, 1.0);
    if (!(clip.w > 0.0)) {
        return vec3<u32>(0u, 0u, PPR_CLEAR_VALUE);
    }
    let ndc = clip.xy / clip.w;
    if (!all(abs(ndc) < vec2<f32>(1.0))) {
        return vec3<u32>(0u, 0u, PPR_CLEAR_VALUE);
    }
    let target_crd = (ndc * vec2<f32>(0.5, -0.5) + 0.5) * frame.resolution.xy;
    // Whole part from integer pixels, so that it points exactly at the source pixel.
    let t = min(vec2<u32>(target_crd), frame.size - 1u);
    let whole = vec2<i32>(t) - vec2<i32>(pixel);
    return vec3<u32>(t, ppr_encode_parts(whole, target_crd - vec2<f32>(t) - 0.5, frame.encoding));
}

// Writes the reflection of `pixel` into the main intermediate buffer.
fn write_projection(pixel: vec2<u32>, mirrored: vec3<f32>) -> bool {
    let tv = projection_target(pixel, mirrored);
    let value = tv.z;
    if (value == PPR_CLEAR_VALUE) {
        return false;
    }
    let t = tv.xy;
    let index = t.x + t.y * frame.size.x;
    if ((frame.flags & (PPR_FLAG_WRITE_LAST | PPR_FLAG_WRITE_MAX)) == 0u) {
        // A plain load first: where a squeezed reflection maps many pixels onto one, most
        // writes lose, and a load is cheaper than an atomic.
        if (atomicLoad(&intermediate[index]) > value) {
            atomicMin(&intermediate[index], value);
        }
    } else if ((frame.flags & PPR_FLAG_WRITE_LAST) != 0u) {
        atomicStore(&intermediate[index], value);
    } else {
        // The largest offset wins; the clear value counts as empty, so plain atomicMax
        // would never write: a compare-exchange loop instead (debug path only).
        var old = atomicLoad(&intermediate[index]);
        loop {
            if (old != PPR_CLEAR_VALUE && old >= value) {
                break;
            }
            let r = atomicCompareExchangeWeak(&intermediate[index], old, value);
            if (r.exchanged) {
                break;
            }
            old = r.old_value;
        }
    }
    return true;
}

// Writes the reflection of `pixel` into layer `l`'s atlas region (if it lands there).
fn write_layer(pixel: vec2<u32>, mirrored: vec3<f32>, l: Layer) {
    let tv = projection_target(pixel, mirrored);
    if (tv.z == PPR_CLEAR_VALUE || any(tv.xy < l.rect_min) || any(tv.xy >= l.rect_max)) {
        return;
    }
    let local = tv.xy - l.rect_min;
    atomicMin(&atlas[l.offset + local.x + local.y * (l.rect_max.x - l.rect_min.x)], tv.z);
}

// The per-pixel test of shape `s`: the pixel is in front of its plane and its reflection
// point lies in the rectangle. Returns the plane distance, or -1 when the test fails.
fn reflecting_distance(p: vec3<f32>, min_dist: f32, s: Shape) -> f32 {
    let dist = dot(p, s.normal) - s.plane_dist;
    if (!(dist > min_dist)) {
        return -1.0;
    }
    let mirrored = p - 2.0 * dist * s.normal;
    let hit = mirrored * (s.plane_dist / dot(mirrored, s.normal));
    let l = hit - s.center;
    if (abs(dot(l, s.axis_u)) > s.half_u || abs(dot(l, s.axis_v)) > s.half_v) {
        return -1.0;
    }
    return dist;
}

// Occluder tests and the write, for a shape that passed `reflecting_distance`.
fn reflect_pixel(pixel: vec2<u32>, p: vec3<f32>, dist: f32, s: Shape) -> bool {
    let mirrored = p - 2.0 * dist * s.normal;
    if (OCCLUDER_TESTS) {
        let hit = mirrored * (s.plane_dist / dot(mirrored, s.normal));
        if (is_occluded(hit, s)) {
            return false;
        }
    }
    return write_projection(pixel, mirrored);
}

// Conservative tile test: may any point of the tile's world-space bounds (the convex hull
// of `corners`, indexed by bits: x = 1, y = 2, depth = 4) be reflected by `s` into its
// rectangle? Only the part of the hull in front of the plane can be reflected; it is the
// convex hull of the front corners and of the points where the hull's edges cross the
// plane. Mirroring is affine and the central projection from the camera onto the plane
// keeps convexity for points behind it, so the rectangle spanned by the projections of
// those points bounds every pixel's reflection point. (A crossing point lies on the plane:
// it is its own reflection point.)
fn tile_may_reflect(s: Shape, corners: array<vec3<f32>, 8>) -> bool {
    var d: array<f32, 8>;
    var any_front = false;
    var reach = 0.0;
    for (var i = 0u; i < 8u; i++) {
        d[i] = dot(corners[i], s.normal) - s.plane_dist;
        any_front = any_front || d[i] > 0.0;
        reach = max(reach, length(corners[i]));
    }
    if (!any_front) {
        return false;
    }
    var lo = vec2<f32>(3.0e38);
    var hi = vec2<f32>(-3.0e38);
    for (var i = 0u; i < 8u; i++) {
        let c = corners[i];
        if (d[i] > 0.0) {
            let m = c - 2.0 * d[i] * s.normal;
            let hit = m * (s.plane_dist / dot(m, s.normal));
            let l = hit - s.center;
            let uv = vec2<f32>(dot(l, s.axis_u), dot(l, s.axis_v));
            lo = min(lo, uv);
            hi = max(hi, uv);
        }
        // The three edges from corner i to corners with one more bit set.
        for (var b = 1u; b < 8u; b <<= 1u) {
            let j = i | b;
            if (j == i || (d[i] > 0.0) == (d[j] > 0.0)) {
                continue;
            }
            let crossing = mix(c, corners[j], d[i] / (d[i] - d[j]));
            let l = crossing - s.center;
            let uv = vec2<f32>(dot(l, s.axis_u), dot(l, s.axis_v));
            lo = min(lo, uv);
            hi = max(hi, uv);
        }
    }
    // Margin for the f32 error of per-pixel positions against the corners'.
    let margin = 1e-4 * reach + 1e-6 * max(s.half_u, s.half_v);
    let half = vec2<f32>(s.half_u, s.half_v) + margin;
    return all(hi >= -half) && all(lo <= half);
}

// Builds the tile's candidate list in workgroup memory (ordered like `visible`).
// Returns the list length, or TILE_LIST_CAPACITY + 1 when it overflowed.
fn build_tile_list(lid: u32, tile_origin: vec2<u32>, depth_ok: bool, depth: f32) -> u32 {
    if (lid == 0u) {
        atomicStore(&tile_depth_min, 0x7f800000u);
        atomicStore(&tile_depth_max, 0u);
        tile_list_len = 0u;
    }
    workgroupBarrier();
    if (depth_ok) {
        // Non-negative floats order like their bits.
        atomicMin(&tile_depth_min, bitcast<u32>(depth));
        atomicMax(&tile_depth_max, bitcast<u32>(depth));
    }
    workgroupBarrier();
    let dmin_bits = atomicLoad(&tile_depth_min);
    let dmax_bits = atomicLoad(&tile_depth_max);
    var corners: array<vec3<f32>, 8>;
    let lo = vec2<f32>(tile_origin);
    let hi = min(lo + f32(TILE_SIZE), frame.resolution.xy);
    let dmin = bitcast<f32>(dmin_bits);
    let dmax = bitcast<f32>(dmax_bits);
    for (var i = 0u; i < 8u; i++) {
        let x = select(lo.x, hi.x, (i & 1u) != 0u);
        let y = select(lo.y, hi.y, (i & 2u) != 0u);
        corners[i] = ppr_unproject(vec2<f32>(x, y), select(dmin, dmax, (i & 4u) != 0u));
    }
    let empty_tile = dmin_bits > dmax_bits;
    var count = 0u;
    let word = lid / 32u;
    let below = (1u << (lid % 32u)) - 1u;
    for (var base = 0u; base < frame.visible_count; base += GROUP_THREADS) {
        if (lid < 8u) {
            atomicStore(&pass_bits[lid], 0u);
        }
        workgroupBarrier();
        let k = base + lid;
        let passes = !empty_tile && k < frame.visible_count && tile_may_reflect(shapes[visible[k]], corners);
        if (passes) {
            atomicOr(&pass_bits[word], 1u << (lid % 32u));
        }
        workgroupBarrier();
        // Ordered compaction: a passing thread's slot is the number of passing threads
        // before it, so the list keeps the visible order (sorted by parallel group).
        var rank = countOneBits(atomicLoad(&pass_bits[word]) & below);
        var total = 0u;
        for (var w = 0u; w < 8u; w++) {
            let bits = countOneBits(atomicLoad(&pass_bits[w]));
            total += bits;
            if (w < word) {
                rank += bits;
            }
        }
        if (passes && count + rank < TILE_LIST_CAPACITY) {
            tile_list[count + rank] = k;
        }
        count += total;
        workgroupBarrier();
    }
    return min(count, TILE_LIST_CAPACITY + 1u);
}

@compute @workgroup_size(16, 16)
fn main(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
) {
    let in_view = all(gid.xy < frame.size);
    var depth = 1.0;
    var depth_ok = false;
    if (in_view) {
        depth = textureLoad(depth_tex, vec2<i32>(gid.xy), 0).r;
        depth_ok = ppr_is_valid_depth(depth);
    }

    // In the tiled variant, the candidates are the tile's list (visible positions);
    // otherwise, or when the list overflowed, every visible shape.
    var count = frame.visible_count;
    var use_list = false;
    if (TILE_CULLING) {
        let listed = build_tile_list(lid, wid.xy * TILE_SIZE, depth_ok, depth);
        if (listed <= TILE_LIST_CAPACITY) {
            count = listed;
            use_list = true;
        }
    }
    if (!depth_ok || (count == 0u && !LAYERS)) {
        return;
    }

    let p = ppr_unproject(vec2<f32>(gid.xy) + 0.5, depth);
    if (!(ppr_is_finite2(p.xy) && ppr_is_finite(p.z)) || any(abs(p) >= vec3<f32>(1e30))) {
        return;
    }
    let min_dist = frame.plane_epsilon * length(p);
    var written = 0u;
    // Parallel rule: the best (smallest distance) shape of the current group so far.
    var group = 0xffffffffu;
    var best_k = 0xffffffffu;
    var best_dist = 0.0;
    for (var i = 0u; i < count; i++) {
        var k = i;
        if (use_list) {
            k = tile_list[i];
        }
        let s = shapes[visible[k]];
        if (PARALLEL_RULE && s.parallel_group != group) {
            if (best_k != 0xffffffffu && reflect_pixel(gid.xy, p, best_dist, shapes[visible[best_k]])) {
                written |= 1u << (best_k & 31u);
            }
            group = s.parallel_group;
            best_k = 0xffffffffu;
        }
        let dist = reflecting_distance(p, min_dist, s);
        if (dist < 0.0) {
            continue;
        }
        if (PARALLEL_RULE) {
            if (best_k == 0xffffffffu || dist < best_dist) {
                best_k = k;
                best_dist = dist;
            }
        } else if (reflect_pixel(gid.xy, p, dist, s)) {
            written |= 1u << (k & 31u);
        }
    }
    if (PARALLEL_RULE && best_k != 0xffffffffu && reflect_pixel(gid.xy, p, best_dist, shapes[visible[best_k]])) {
        written |= 1u << (best_k & 31u);
    }
    // Layer reflectors (few): each writes its own atlas region.
    for (var l = 0u; LAYERS && l < frame.layer_count; l++) {
        let layer = layers[l];
        let s = shapes[layer.shape];
        let dist = reflecting_distance(p, min_dist, s);
        if (dist < 0.0) {
            continue;
        }
        let mirrored = p - 2.0 * dist * s.normal;
        if (OCCLUDER_TESTS) {
            let hit = mirrored * (s.plane_dist / dot(mirrored, s.normal));
            if (is_occluded(hit, s)) {
                continue;
            }
        }
        write_layer(gid.xy, mirrored, layer);
    }
    if (DEBUG_WRITES) {
        debug_writes[gid.x + gid.y * frame.size.x] = written;
    }
}
