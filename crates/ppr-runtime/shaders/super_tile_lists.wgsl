// Super-tile lists: for each 64x64-pixel super-tile (2x2 projection blocks), the visible
// shapes that may reflect some pixel of it, by the projection's conservative box test on
// the box of all its pixels' positions (and, with SOURCE_BOXES, the shapes' screen source
// boxes). The projection pass's blocks then test only their super-tile's list instead of
// every visible shape: with many reflectors the per-block test is O(blocks x shapes), and
// this pass does that work once per 4 blocks.
//
// Layout of `super_lists` (u32): one count per super-tile (SUPER_LIST_CAPACITY + 1 when
// the list overflowed), then SUPER_LIST_CAPACITY entries per super-tile, in the order of
// `visible` (the parallel rule walks groups in that order). Entries are positions in
// `visible`.

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var depth_tex: texture_2d<f32>;
@group(0) @binding(2) var<storage, read> tests: array<ShapeTest>;
@group(0) @binding(3) var<storage, read> source_boxes: array<vec4<u32>>;
@group(0) @binding(4) var<storage, read_write> super_lists: array<u32>;

override SOURCE_BOXES: bool = false;

@compute @workgroup_size(256)
fn main(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>) {
    // Each thread takes one column of 16 pixels (every fourth row), rows coalesced.
    let origin = wid.xy * SUPER_TILE_SIZE;
    var lo = vec3<f32>(3.0e38);
    var hi = vec3<f32>(-3.0e38);
    for (var i = 0u; i < SUPER_TILE_SIZE * SUPER_TILE_SIZE / TILE_GROUP_THREADS; i++) {
        let pixel = origin + vec2<u32>(lid % SUPER_TILE_SIZE, lid / SUPER_TILE_SIZE + 4u * i);
        let p = tile_pixel_position(pixel);
        if (p.w > 0.0) {
            lo = min(lo, p.xyz);
            hi = max(hi, p.xyz);
        }
    }
    let box = workgroup_box(lid, lo, hi);
    let empty = box.lo.x > box.hi.x;

    let grid = super_tile_grid();
    let st = wid.x + wid.y * grid.x;
    let list_start = grid.y + st * SUPER_LIST_CAPACITY;
    var count = 0u;
    for (var base = 0u; base < frame.tested_count; base += TILE_GROUP_THREADS) {
        let k = base + lid;
        var passes = false;
        if (!empty && k < frame.tested_count) {
            let b = source_boxes[min(k, frame.tested_count - 1u)];
            let meets = !SOURCE_BOXES || (all(b.xy < origin + SUPER_TILE_SIZE) && all(origin < b.zw));
            passes = meets && box_may_reflect(tests[k], box.lo, box.hi);
        }
        let r = chunk_rank(lid, base / TILE_GROUP_THREADS, passes);
        if (passes && count + r.x < SUPER_LIST_CAPACITY) {
            super_lists[list_start + count + r.x] = k;
        }
        count += r.y;
    }
    if (lid == 0u) {
        super_lists[st] = min(count, SUPER_LIST_CAPACITY + 1u);
    }
}
