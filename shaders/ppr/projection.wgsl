// Projection pass: for every pixel, mirror its position against the candidate reflectors,
// test the reflection point against the rectangle and its occluders, and atomicMin the
// encoded screen offset into the intermediate buffer where the pixel is reflected.
// Seed: PPR_ProjectionPassWrite, and the bonus slides' "multiple parallel shapes".
//
// Variants (pipeline-overridable constants, chosen by the FramePlan):
// - TILE_CULLING: each 16x16 workgroup first builds, in workgroup memory, the list of
//   visible shapes that may reflect some pixel of its tile (one thread per shape; a
//   conservative test of the tile's mirrored world-space bounds against the rectangle,
//   tile_test.wgsl); a tile without candidates does nothing more. Otherwise every pixel
//   loops over all visible shapes.
// - SUPER_TILES (with TILE_CULLING): the candidates a tile tests are its 64x64
//   super-tile's list (super_tile_lists.wgsl, dispatched just before) instead of every
//   visible shape; a tile whose own list overflows falls back to that list.
// - PARALLEL_RULE: among shapes of one parallel group that reflect a pixel, only the one
//   with the smallest plane distance writes (each pixel reflected at most once per
//   orientation). The visible list is sorted by group, and so are the tile lists.
// - OCCLUDER_TESTS: test the ray to the reflection point against the shape's occluders.
// - LAYERS: glass panels and water planes with atlas regions exist this frame (without
//   them the layer loop is compiled out).
// - DEBUG_WRITES: record, per source pixel, a bit per visible shape it wrote for.

override TILE_CULLING: bool = false;
override SUPER_TILES: bool = false;
override PARALLEL_RULE: bool = false;
override OCCLUDER_TESTS: bool = false;
override LAYERS: bool = false;
override DEBUG_WRITES: bool = false;
// Debug: record, per pixel, its tile's candidate-list length instead of write bits.
override DEBUG_TILE_LISTS: bool = false;

const TILE_SIZE: u32 = 16u;
// Capacity of a tile's shape list; a tile with more candidates loops over all of them.
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
// Super-tile counts and lists (super_tile_lists.wgsl), read with SUPER_TILES.
@group(0) @binding(9) var<storage, read> super_lists: array<u32>;

var<workgroup> tile_list: array<u32, TILE_LIST_CAPACITY>;

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

// The shapes a tile considers: `count` positions in `visible`, listed in `super_lists`
// from `start` (`listed`) or all of them.
struct Candidates {
    count: u32,
    start: u32,
    listed: bool,
}

fn tile_candidates(wid: vec3<u32>) -> Candidates {
    var c = Candidates(frame.visible_count, 0u, false);
    if (SUPER_TILES) {
        let grid = super_tile_grid();
        let st = wid.x / (SUPER_TILE_SIZE / TILE_SIZE) + (wid.y / (SUPER_TILE_SIZE / TILE_SIZE)) * grid.x;
        let n = super_lists[st];
        if (n <= SUPER_LIST_CAPACITY) {
            c = Candidates(n, grid.y + st * SUPER_LIST_CAPACITY, true);
        }
    }
    return c;
}

// Position in `visible` of candidate `i`.
fn candidate(c: Candidates, i: u32) -> u32 {
    if (c.listed) {
        return super_lists[c.start + i];
    }
    return i;
}

// Builds the tile's list in workgroup memory (positions in `visible`, in its order) from
// the candidates and the axis-aligned box of the tile's pixel positions (`p`, valid when
// `has_point`): on a plane seen at an angle this box is a thin slab, far tighter than the
// tile's frustum slice between its nearest and farthest depth.
// Returns the list length, or TILE_LIST_CAPACITY + 1 when it overflowed.
fn build_tile_list(lid: u32, has_point: bool, p: vec3<f32>, cand: Candidates) -> u32 {
    var lo = vec3<f32>(3.0e38);
    var hi = vec3<f32>(-3.0e38);
    if (has_point) {
        lo = p;
        hi = p;
    }
    let box = workgroup_box(lid, lo, hi);
    let empty_tile = box.lo.x > box.hi.x;
    var count = 0u;
    for (var base = 0u; base < cand.count; base += TILE_GROUP_THREADS) {
        let i = base + lid;
        var k = 0u;
        var passes = false;
        if (!empty_tile && i < cand.count) {
            k = candidate(cand, i);
            passes = tile_may_reflect(shapes[visible[k]], box.lo, box.hi);
        }
        let r = chunk_rank(lid, passes);
        if (passes && count + r.x < TILE_LIST_CAPACITY) {
            tile_list[count + r.x] = k;
        }
        count += r.y;
    }
    workgroupBarrier();
    return min(count, TILE_LIST_CAPACITY + 1u);
}

@compute @workgroup_size(16, 16)
fn main(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
) {
    let position = tile_pixel_position(gid.xy);
    let depth_ok = position.w > 0.0;
    let p = position.xyz;

    // In the tiled variant, the candidates are the tile's list (positions in `visible`);
    // otherwise, or when the list overflowed, every candidate (the super-tile's list or
    // every visible shape).
    var cand = Candidates(frame.visible_count, 0u, false);
    var count = frame.visible_count;
    var use_list = false;
    if (TILE_CULLING) {
        cand = tile_candidates(wid);
        count = cand.count;
        let listed = build_tile_list(lid, depth_ok, p, cand);
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
        } else if (cand.listed) {
            k = super_lists[cand.start + i];
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
