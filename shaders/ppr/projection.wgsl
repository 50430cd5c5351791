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
// Debug: record, per pixel, its tile's candidate-list length instead of write bits.
override DEBUG_TILE_LISTS: bool = false;

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

// The box of the tile's pixel positions (ordered float bits per axis).
var<workgroup> tile_box_min: array<atomic<u32>, 3>;
var<workgroup> tile_box_max: array<atomic<u32>, 3>;
var<workgroup> tile_list: array<u32, TILE_LIST_CAPACITY>;
var<workgroup> tile_list_len: u32;
// Per thread of a chunk: whether its shape passed; packed into words for the ranks.
var<workgroup> pass_flags: array<u32, GROUP_THREADS>;
var<workgroup> pass_words: array<u32, 8>;

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

// Rectangle coordinates of where a front point `c` (plane distance `d` > 0) is reflected.
fn reflected_uv(s: Shape, c: vec3<f32>, d: f32) -> vec2<f32> {
    let m = c - 2.0 * d * s.normal;
    let l = m * (s.plane_dist / dot(m, s.normal)) - s.center;
    return vec2<f32>(dot(l, s.axis_u), dot(l, s.axis_v));
}

// Bounds accumulated by the tile test: (lo.xy, hi.xy) in rectangle coordinates.
struct UvBounds {
    lo: vec2<f32>,
    hi: vec2<f32>,
}

fn add_corner(b: UvBounds, s: Shape, c: vec3<f32>, d: f32) -> UvBounds {
    if (!(d > 0.0)) {
        return b;
    }
    let uv = reflected_uv(s, c, d);
    return UvBounds(min(b.lo, uv), max(b.hi, uv));
}

// Where the edge a–b crosses the plane, if it does (a point on the plane is its own
// reflection point).
fn add_crossing(b: UvBounds, s: Shape, a: vec3<f32>, da: f32, c: vec3<f32>, dc: f32) -> UvBounds {
    if ((da > 0.0) == (dc > 0.0)) {
        return b;
    }
    let l = mix(a, c, da / (da - dc)) - s.center;
    let uv = vec2<f32>(dot(l, s.axis_u), dot(l, s.axis_v));
    return UvBounds(min(b.lo, uv), max(b.hi, uv));
}

// Conservative tile test: may any point of the box [lo, hi] (the tile's pixel positions)
// be reflected by `s` into its rectangle? Only the part of the box in front of the plane
// can be reflected; it is the convex hull of the front corners and of the points where
// the box's edges cross the plane. Mirroring is affine and the central projection from
// the camera onto the plane keeps convexity for points behind it, so the rectangle
// spanned by the projections of those points bounds every pixel's reflection point.
// Written out corner by corner and edge by edge: no dynamically indexed arrays.
fn tile_may_reflect(s: Shape, lo: vec3<f32>, hi: vec3<f32>) -> bool {
    let c0 = vec3<f32>(lo.x, lo.y, lo.z);
    let c1 = vec3<f32>(hi.x, lo.y, lo.z);
    let c2 = vec3<f32>(lo.x, hi.y, lo.z);
    let c3 = vec3<f32>(hi.x, hi.y, lo.z);
    let c4 = vec3<f32>(lo.x, lo.y, hi.z);
    let c5 = vec3<f32>(hi.x, lo.y, hi.z);
    let c6 = vec3<f32>(lo.x, hi.y, hi.z);
    let c7 = vec3<f32>(hi.x, hi.y, hi.z);
    let n = s.normal;
    let d0 = dot(c0, n) - s.plane_dist;
    let d1 = dot(c1, n) - s.plane_dist;
    let d2 = dot(c2, n) - s.plane_dist;
    let d3 = dot(c3, n) - s.plane_dist;
    let d4 = dot(c4, n) - s.plane_dist;
    let d5 = dot(c5, n) - s.plane_dist;
    let d6 = dot(c6, n) - s.plane_dist;
    let d7 = dot(c7, n) - s.plane_dist;
    if (!(max(max(max(d0, d1), max(d2, d3)), max(max(d4, d5), max(d6, d7))) > 0.0)) {
        return false;
    }
    var b = UvBounds(vec2<f32>(3.0e38), vec2<f32>(-3.0e38));
    b = add_corner(b, s, c0, d0);
    b = add_corner(b, s, c1, d1);
    b = add_corner(b, s, c2, d2);
    b = add_corner(b, s, c3, d3);
    b = add_corner(b, s, c4, d4);
    b = add_corner(b, s, c5, d5);
    b = add_corner(b, s, c6, d6);
    b = add_corner(b, s, c7, d7);
    b = add_crossing(b, s, c0, d0, c1, d1);
    b = add_crossing(b, s, c2, d2, c3, d3);
    b = add_crossing(b, s, c4, d4, c5, d5);
    b = add_crossing(b, s, c6, d6, c7, d7);
    b = add_crossing(b, s, c0, d0, c2, d2);
    b = add_crossing(b, s, c1, d1, c3, d3);
    b = add_crossing(b, s, c4, d4, c6, d6);
    b = add_crossing(b, s, c5, d5, c7, d7);
    b = add_crossing(b, s, c0, d0, c4, d4);
    b = add_crossing(b, s, c1, d1, c5, d5);
    b = add_crossing(b, s, c2, d2, c6, d6);
    b = add_crossing(b, s, c3, d3, c7, d7);
    // Margin for the f32 error of per-pixel positions against the box's.
    let reach = max(length(lo), length(hi));
    let margin = 1e-4 * reach + 1e-6 * max(s.half_u, s.half_v);
    let half = vec2<f32>(s.half_u, s.half_v) + margin;
    return all(b.hi >= -half) && all(b.lo <= half);
}

// Order-preserving map of a float to a u32 (for atomicMin/atomicMax on signed floats).
fn ordered_bits(x: f32) -> u32 {
    let b = bitcast<u32>(x);
    return select(b | 0x80000000u, ~b, (b & 0x80000000u) != 0u);
}

fn from_ordered_bits(u: u32) -> f32 {
    return bitcast<f32>(select(~u, u & 0x7fffffffu, (u & 0x80000000u) != 0u));
}

// Builds the tile's candidate list in workgroup memory (ordered like `visible`), from the
// axis-aligned box of the tile's pixel positions (`p`, valid when `has_point`): on a
// plane seen at an angle this box is a thin slab, far tighter than the tile's frustum
// slice between its nearest and farthest depth.
// Returns the list length, or TILE_LIST_CAPACITY + 1 when it overflowed.
fn build_tile_list(lid: u32, has_point: bool, p: vec3<f32>) -> u32 {
    if (lid < 3u) {
        atomicStore(&tile_box_min[lid], 0xffffffffu);
        atomicStore(&tile_box_max[lid], 0u);
    }
    if (lid == 0u) {
        tile_list_len = 0u;
    }
    workgroupBarrier();
    if (has_point) {
        for (var c = 0u; c < 3u; c++) {
            atomicMin(&tile_box_min[c], ordered_bits(p[c]));
            atomicMax(&tile_box_max[c], ordered_bits(p[c]));
        }
    }
    workgroupBarrier();
    let empty_tile = atomicLoad(&tile_box_min[0]) > atomicLoad(&tile_box_max[0]);
    var box_lo = vec3<f32>(0.0);
    var box_hi = vec3<f32>(0.0);
    for (var c = 0u; c < 3u; c++) {
        box_lo[c] = from_ordered_bits(atomicLoad(&tile_box_min[c]));
        box_hi[c] = from_ordered_bits(atomicLoad(&tile_box_max[c]));
    }
    var count = 0u;
    let word = lid / 32u;
    for (var base = 0u; base < frame.visible_count; base += GROUP_THREADS) {
        let k = base + lid;
        let passes = !empty_tile && k < frame.visible_count && tile_may_reflect(shapes[visible[k]], box_lo, box_hi);
        pass_flags[lid] = select(0u, 1u, passes);
        workgroupBarrier();
        // Ordered compaction: eight threads pack the flags into words, then a passing
        // thread's slot is the number of passing threads before it (popcounts).
        if (lid < 8u) {
            var bits = 0u;
            for (var t = 0u; t < 32u; t++) {
                bits |= pass_flags[lid * 32u + t] << t;
            }
            pass_words[lid] = bits;
        }
        workgroupBarrier();
        var rank = countOneBits(pass_words[word] & ((1u << (lid % 32u)) - 1u));
        var total = 0u;
        for (var w = 0u; w < 8u; w++) {
            let n = countOneBits(pass_words[w]);
            total += n;
            if (w < word) {
                rank += n;
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

    var p = vec3<f32>(0.0);
    if (depth_ok) {
        p = ppr_unproject(vec2<f32>(gid.xy) + 0.5, depth);
        depth_ok = ppr_is_finite2(p.xy) && ppr_is_finite(p.z) && all(abs(p) < vec3<f32>(1e30));
    }

    // In the tiled variant, the candidates are the tile's list (visible positions);
    // otherwise, or when the list overflowed, every visible shape.
    var count = frame.visible_count;
    var use_list = false;
    if (TILE_CULLING) {
        let listed = build_tile_list(lid, depth_ok, p);
        if (listed <= TILE_LIST_CAPACITY) {
            count = listed;
            use_list = true;
        }
    }
    if (DEBUG_TILE_LISTS && all(gid.xy < frame.size)) {
        debug_writes[gid.x + gid.y * frame.size.x] = select(0xffffffffu, count, use_list);
    }
    if (!depth_ok || (count == 0u && !LAYERS)) {
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
    if (DEBUG_WRITES && !DEBUG_TILE_LISTS) {
        debug_writes[gid.x + gid.y * frame.size.x] = written;
    }
}
