// Block lists: for each 32x32-pixel block (a projection workgroup), the visible shapes
// that may reflect some pixel of it, by the conservative box test on the box of its
// pixels' positions (and, with SOURCE_BOXES, the shapes' screen source boxes). The
// candidates are the block's super-tile's list with SUPER_TILES, else every visible shape.
// A pass of its own: the projection then has no barrier (and shader compilers that turn
// barriers into coroutines, as llvmpipe's does, compile it in a second, not minutes).
//
// Layout of `block_lists` (u32): one count per block (BLOCK_LIST_CAPACITY + 1 when the
// list overflowed), then BLOCK_LIST_CAPACITY entries per block, in the order of `visible`
// (the parallel rule walks groups in that order). Entries are positions in `visible`,
// flagged INSIDE_ENTRY where the block's box lies inside the shape's pyramid (list_entry).

override SOURCE_BOXES: bool = false;
override SUPER_TILES: bool = false;
// Bench only (never a correct list): stop after the box of the block's positions.
override BOX_ONLY: bool = false;

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var depth_tex: texture_2d<f32>;
@group(0) @binding(2) var<storage, read> tests: array<ShapeTest>;
@group(0) @binding(3) var<storage, read> source_boxes: array<vec4<u32>>;
@group(0) @binding(4) var<storage, read> super_lists: array<u32>;
@group(0) @binding(5) var<storage, read_write> block_lists: array<u32>;

@compute @workgroup_size(16, 16)
fn main(
    @builtin(local_invocation_id) local: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
) {
    let lo = wid.xy * BLOCK_SIZE;
    let hi = lo + vec2<u32>(BLOCK_SIZE);
    var own = TileBox(vec3<f32>(3.0e38), vec3<f32>(-3.0e38));
    for (var j = 0u; j < 4u; j++) {
        let p = tile_pixel_position(quad_pixel(quad_base(lo, local.xy), j));
        if (p.w > 0.0) {
            own = TileBox(min(own.lo, p.xyz), max(own.hi, p.xyz));
        }
    }
    let box = workgroup_box(lid, own.lo, own.hi);
    let empty = box.lo.x > box.hi.x;
    if (BOX_ONLY) {
        if (lid == 0u && box.lo.x == 1234.5) {
            block_lists[0] = 0u;
        }
        return;
    }

    // Candidates: the super-tile's list, or every visible shape.
    var count = frame.tested_count;
    var start = 0u;
    var listed = false;
    if (SUPER_TILES) {
        let grid = super_tile_grid();
        let per = SUPER_TILE_SIZE / BLOCK_SIZE;
        let st = wid.x / per + (wid.y / per) * grid.x;
        let n = super_lists[st];
        if (n <= SUPER_LIST_CAPACITY) {
            count = n;
            start = grid.y + st * SUPER_LIST_CAPACITY;
            listed = true;
        }
    }
    let blocks = block_grid();
    let b = wid.x + wid.y * blocks.x;
    let list_start = blocks.y + b * BLOCK_LIST_CAPACITY;
    var written = 0u;
    for (var base = 0u; base < count; base += TILE_GROUP_THREADS) {
        let i = base + lid;
        var entry = 0u;
        var passes = false;
        if (!empty && i < count) {
            let k = select(i, super_lists[start + min(i, SUPER_LIST_CAPACITY - 1u)], listed);
            let sb = source_boxes[k];
            let meets = !SOURCE_BOXES || (all(sb.xy < hi) && all(lo < sb.zw));
            if (meets) {
                let t = tests[k];
                passes = box_may_reflect(t, box.lo, box.hi);
                // The inside test only for the entries that are listed.
                if (passes) {
                    entry = list_entry(k, t, box.lo, box.hi);
                }
            }
        }
        let r = chunk_rank(lid, base / TILE_GROUP_THREADS, passes);
        if (passes && written + r.x < BLOCK_LIST_CAPACITY) {
            block_lists[list_start + written + r.x] = entry;
        }
        written += r.y;
    }
    if (lid == 0u) {
        block_lists[b] = min(written, BLOCK_LIST_CAPACITY + 1u);
    }
}
