// Tile classification: finds the 16x16 tiles where some pixel lies on a visible reflector
// (or on a layer reflector, through which one may be seen) and appends them to the
// active-tile list, so that the reflection pass runs only there. Per 32x32 block of 2x2
// tiles, the visible shapes and the layers whose screen rectangle touches the block are
// first gathered in workgroup memory (one thread per shape); where some visible shape is
// listed, each pixel then tests whether it lies on one of them, until its tile is found
// active. The blocks that find active tiles also raise the indirect dispatch arguments
// (append_active_tiles).
// It also clears the next encode's intermediate buffer and atlas (the renderer's other
// slot, which this encode does not touch): every pixel of its block, and the atlas whole
// over all blocks; and zeroes that slot's active-tile count and dispatch arguments. The projection then needs nothing from this pass (its slot was cleared
// by the encode before), so the two share a compute pass with no barrier between them;
// the reflection reads the active tiles only.

// The frame has layer reflectors (false: the layer list and its tests compiled out; their
// registers slowed the scan of 10 000 visible shapes).
override LAYERS: bool = true;

const TILE_SIZE: u32 = 16u;
// Edge of a workgroup's block: 2 x 2 tiles.
const BLOCK_SIZE: u32 = 32u;
const GROUP_THREADS: u32 = 256u;
const LIST_CAPACITY: u32 = 256u;
// Layers listed per block (MAX_LAYERS in plan.rs).
const LAYER_CAPACITY: u32 = 64u;
// Largest workgroup count per dispatch dimension.
const MAX_GROUPS_X: u32 = 65535u;
// Pixels closer to a plane than this times their distance count as on it (generous:
// marking a tile active that shows no reflector only costs time).
const ON_PLANE_EPSILON: f32 = 2e-3;

// common.wgsl's ActiveTileList with atomics.
struct ActiveTileCounter {
    count: atomic<u32>,
    // The indirect dispatch arguments (x, y, z).
    args: array<atomic<u32>, 3>,
    // Tile index (x + y * tiles_x) of each active tile.
    tiles: array<u32>,
}

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var depth_tex: texture_2d<f32>;
@group(0) @binding(2) var<storage, read> shapes: array<Shape>;
@group(0) @binding(3) var<storage, read> visible: array<u32>;
// Per visible shape: its screen rectangle in pixels (min x, min y, max x, max y), exclusive max.
@group(0) @binding(4) var<storage, read> screen_rects: array<vec4<u32>>;
@group(0) @binding(5) var<storage, read_write> active_tiles: ActiveTileCounter;
// The next encode's active-tile count and dispatch arguments (the other slot's list),
// zeroed here: the next classification appends from zero without a clear before it.
@group(0) @binding(6) var<storage, read_write> next_counters: array<u32, 4>;
// Per tile: 1 when active, 0 when not (so that reads across a tile border can tell
// whether the neighbouring tile was cleared this frame).
@group(0) @binding(7) var<storage, read_write> tile_flags: array<u32>;
// Layer reflectors (glass, water): a reflector seen through one has the layer's depth, so
// a pixel on a layer also makes its tile active.
@group(0) @binding(8) var<storage, read> layers: array<Layer>;
// The next encode's intermediate buffer and layers' atlas, cleared whole.
@group(0) @binding(9) var<storage, read_write> next_intermediate: array<u32>;
@group(0) @binding(10) var<storage, read_write> next_atlas: array<u32>;

var<workgroup> list: array<u32, LIST_CAPACITY>;
var<workgroup> list_len: atomic<u32>;
var<workgroup> layer_list: array<u32, LAYER_CAPACITY>;
var<workgroup> layer_list_len: atomic<u32>;
var<workgroup> shows_reflector: array<atomic<u32>, 4>;

// Whether `p` (at distance `reach` from the camera) lies on `s`.
fn lies_on(p: vec3<f32>, reach: f32, s: Shape) -> bool {
    let dist = dot(p, s.normal) - s.plane_dist;
    if (abs(dist) > ON_PLANE_EPSILON * reach) {
        return false;
    }
    let l = p - s.center;
    let margin = ON_PLANE_EPSILON * reach;
    return abs(dot(l, s.axis_u)) <= s.half_u + margin && abs(dot(l, s.axis_v)) <= s.half_v + margin;
}

// Whether the pixel (its depth `depth`) shows a visible reflector of the block's list
// (every visible shape when it overflowed) or a layer reflector of the block's layer list.
fn shows_a_reflector(pixel: vec2<u32>, depth: f32, listed: u32, layers_listed: u32) -> bool {
    if (!ppr_is_valid_depth(depth)) {
        return false;
    }
    let p = ppr_unproject(vec2<f32>(pixel) + 0.5, depth);
    let reach = length(p);
    let overflow = listed > LIST_CAPACITY;
    let n = select(listed, frame.visible_count, overflow);
    for (var i = 0u; i < n; i++) {
        if (lies_on(p, reach, shapes[select(list[i], visible[i], overflow)])) {
            return true;
        }
    }
    for (var l = 0u; LAYERS && l < layers_listed; l++) {
        if (lies_on(p, reach, shapes[layer_list[l]])) {
            return true;
        }
    }
    return false;
}

// Clears the next encode's buffers: the block's pixels of the intermediate buffer, and the
// atlas whole (the next encode's layers may differ from this one's), each thread of the
// dispatch a value in turn.
fn clear_next(lid: u32, local: vec2<u32>, wid: vec2<u32>, groups: vec2<u32>) {
    if (all(wid == vec2<u32>(0u)) && lid < 4u) {
        next_counters[lid] = 0u;
    }
    for (var q = 0u; q < 4u; q++) {
        let pixel = wid * BLOCK_SIZE + vec2<u32>(q & 1u, q >> 1u) * TILE_SIZE + local;
        if (all(pixel < frame.size)) {
            next_intermediate[pixel.x + pixel.y * frame.size.x] = PPR_CLEAR_VALUE;
        }
    }
    let threads = groups.x * groups.y * GROUP_THREADS;
    for (var i = (wid.x + wid.y * groups.x) * GROUP_THREADS + lid; i < arrayLength(&next_atlas); i += threads) {
        next_atlas[i] = PPR_CLEAR_VALUE;
    }
}

// One workgroup per 32 x 32-pixel block: its 2 x 2 tiles share one list of the shapes
// (and one of the layers) whose rectangle touches the block, and each thread takes one
// pixel of each tile.
@compute @workgroup_size(16, 16)
fn classify(
    @builtin(local_invocation_id) local: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    clear_next(lid, local.xy, wid.xy, groups.xy);
    if (lid == 0u) {
        atomicStore(&list_len, 0u);
        if (LAYERS) {
            atomicStore(&layer_list_len, 0u);
        }
    }
    if (lid < 4u) {
        atomicStore(&shows_reflector[lid], 0u);
    }
    workgroupBarrier();
    let block_lo = wid.xy * BLOCK_SIZE;
    let block_hi = block_lo + BLOCK_SIZE;
    for (var base = 0u; base < frame.visible_count; base += GROUP_THREADS) {
        let k = base + lid;
        if (k < frame.visible_count) {
            let r = screen_rects[k];
            if (r.x < block_hi.x && r.z > block_lo.x && r.y < block_hi.y && r.w > block_lo.y) {
                let slot = atomicAdd(&list_len, 1u);
                if (slot < LIST_CAPACITY) {
                    list[slot] = visible[k];
                }
            }
        }
    }
    for (var l = lid; LAYERS && l < min(frame.layer_count, LAYER_CAPACITY); l += GROUP_THREADS) {
        let layer = layers[l];
        if (all(layer.rect_min < block_hi) && all(layer.rect_max > block_lo)) {
            layer_list[atomicAdd(&layer_list_len, 1u)] = layer.shape;
        }
    }
    workgroupBarrier();
    let listed = atomicLoad(&list_len);
    let layers_listed = select(0u, atomicLoad(&layer_list_len), LAYERS);
    if (listed > 0u) {
        // The four depths are loaded before any test (one wait instead of four in turn).
        var depth = vec4<f32>(0.0);
        for (var q = 0u; q < 4u; q++) {
            let pixel = block_lo + vec2<u32>(q & 1u, q >> 1u) * TILE_SIZE + local.xy;
            let d = textureLoad(depth_tex, vec2<i32>(min(pixel, frame.size - 1u)), 0).r;
            depth = select(depth, vec4<f32>(d), vec4<u32>(0u, 1u, 2u, 3u) == vec4<u32>(q));
        }
        for (var q = 0u; q < 4u; q++) {
            let pixel = block_lo + vec2<u32>(q & 1u, q >> 1u) * TILE_SIZE + local.xy;
            let d = select(select(depth.x, depth.y, q == 1u), select(depth.z, depth.w, q == 3u), q > 1u);
            // A tile another thread found active needs no more tests.
            if (all(pixel < frame.size) && atomicLoad(&shows_reflector[q]) == 0u
                && shows_a_reflector(pixel, d, listed, layers_listed)) {
                atomicOr(&shows_reflector[q], 1u);
            }
        }
    }
    workgroupBarrier();
    if (lid < 4u) {
        let t = wid.xy * 2u + vec2<u32>(lid & 1u, lid >> 1u);
        let tiles = (frame.size + TILE_SIZE - 1u) / TILE_SIZE;
        if (all(t < tiles)) {
            tile_flags[t.x + t.y * tiles.x] = select(0u, 1u, atomicLoad(&shows_reflector[lid]) != 0u);
        }
    }
    if (lid == 0u) {
        append_active_tiles(wid.xy);
    }
}

// The block's active tiles, appended to the list with one atomic, and the indirect
// dispatch arguments (x, y, 1) covering the list so far, in rows of MAX_GROUPS_X: each
// block raises them to its own end of the list with atomicMax, so that once every block
// has run they cover the whole list (no pass of their own). The arguments and the count
// are zero before the pass.
fn append_active_tiles(block: vec2<u32>) {
    let tiles = (frame.size + TILE_SIZE - 1u) / TILE_SIZE;
    var found = 0u;
    for (var q = 0u; q < 4u; q++) {
        let t = block * 2u + vec2<u32>(q & 1u, q >> 1u);
        if (all(t < tiles) && atomicLoad(&shows_reflector[q]) != 0u) {
            found += 1u;
        }
    }
    if (found == 0u) {
        return;
    }
    var slot = atomicAdd(&active_tiles.count, found);
    for (var q = 0u; q < 4u; q++) {
        let t = block * 2u + vec2<u32>(q & 1u, q >> 1u);
        if (all(t < tiles) && atomicLoad(&shows_reflector[q]) != 0u) {
            active_tiles.tiles[slot] = t.x + t.y * tiles.x;
            slot += 1u;
        }
    }
    atomicMax(&active_tiles.args[0], min(slot, MAX_GROUPS_X));
    atomicMax(&active_tiles.args[1], (slot + MAX_GROUPS_X - 1u) / MAX_GROUPS_X);
    // The block that appended first sets the constant one.
    if (slot == found) {
        atomicStore(&active_tiles.args[2], 1u);
    }
}
