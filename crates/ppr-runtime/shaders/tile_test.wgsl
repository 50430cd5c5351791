// Culling shared by the block-list pass and the projection (32x32-pixel blocks) and the
// super-tile list pass (64x64 super-tiles): each visible shape's test (ShapeTest: a plane
// and two axis forms, the five planes of its pyramid), the box of a workgroup's pixel
// positions, the conservative test of a box against a shape, and the
// ordered compaction that turns per-thread pass flags into a list. Needs `frame`,
// `depth_tex` and the view module; uses the workgroup arrays below.

const TILE_GROUP_THREADS: u32 = 256u;
// Edge of a block in pixels: a workgroup of the projection and of the block-list pass,
// 16x16 threads with one pixel in each 16x16 quarter.
const BLOCK_SIZE: u32 = 32u;
const QUARTER: u32 = 16u;
// Capacity of a block's list; a block with more candidates lists nothing and its pixels
// test its super-tile's list or every visible shape.
const BLOCK_LIST_CAPACITY: u32 = 256u;
// Edge of a super-tile in pixels (2x2 projection blocks).
const SUPER_TILE_SIZE: u32 = 64u;
// Capacity of a super-tile's list; a super-tile with more candidates lists nothing and its
// blocks test every visible shape.
const SUPER_LIST_CAPACITY: u32 = 1024u;

// A visible shape's reflection test, camera-relative, built on the CPU in f64
// (crates/ppr-runtime/src/shape_tests.rs). A point p in front of the reflector's plane is
// reflected into its rectangle exactly when it lies in the pyramid from the mirrored
// camera through the rectangle: `dist = dot(p, plane.xyz) + plane.w > 0` (the distance
// from the plane) and, per rectangle axis, `|dot(p, across.xyz) + across.w| <= k * dist +
// m` (`extent` holds k_u, m_u, k_v, m_v): the pyramid's two opposite sides of that axis
// with one form and one product (test_side gives them as planes, for the box tests).
struct ShapeTest {
    plane: vec4<f32>,
    across_u: vec4<f32>,
    across_v: vec4<f32>,
    extent: vec4<f32>,
    // Index of the shape in `shapes`, its parallel group, its path blocker's index in
    // `shapes` (NO_BLOCKER without: crates/ppr-runtime/src/path_blockers.rs).
    shape: u32,
    group: u32,
    blocker: u32,
    _pad1: u32,
}

// Whether the position `p` (its distance `dist` from the test's plane) lies inside the
// test's pyramid (the per-pixel form of the four sides).
fn inside_pyramid(t: ShapeTest, p: vec3<f32>, dist: f32) -> bool {
    let lu = p.x * t.across_u.x + p.y * t.across_u.y + p.z * t.across_u.z + t.across_u.w;
    let lv = p.x * t.across_v.x + p.y * t.across_v.y + p.z * t.across_v.z + t.across_v.w;
    return abs(lu) <= t.extent.x * dist + t.extent.y && abs(lv) <= t.extent.z * dist + t.extent.w;
}

// The pyramid's side `i` as a plane (inside >= 0; not unit length): k * dist + m - L for
// sides 0 (u) and 1 (v), k * dist + m + L for sides 2 (u) and 3 (v); with `reach`, the
// magnitudes of the terms the per-pixel test sums, which the box tests' rounding margin
// must cover (they may be much larger than the side's own where the form and the bound
// nearly cancel: a camera grazing the plane).
struct TestSide {
    plane: vec4<f32>,
    reach: vec4<f32>,
}

fn test_side(t: ShapeTest, i: u32) -> TestSide {
    let on_u = (i & 1u) == 0u;
    let a = select(t.across_v, t.across_u, on_u);
    let km = select(t.extent.zw, t.extent.xy, on_u);
    let kp = km.x * t.plane;
    let bound = vec4<f32>(kp.xyz, kp.w + km.y);
    let sign = select(-1.0, 1.0, i >= 2u);
    return TestSide(bound + sign * a, abs(kp) + vec4<f32>(0.0, 0.0, 0.0, abs(km.y)) + abs(a));
}

// The largest value of a plane over the box (centre c, half extents h), plus a margin for
// the f32 rounding of per-pixel values against this one (`mag`: the magnitudes of the
// terms the per-pixel value sums, abs(pl) for a plane tested as it is).
fn ppr_box_plane_max(pl: vec4<f32>, mag: vec4<f32>, c: vec3<f32>, h: vec3<f32>) -> f32 {
    let reach = dot(abs(c) + h, mag.xyz) + mag.w;
    return dot(c, pl.xyz) + dot(h, abs(pl.xyz)) + pl.w + 1e-5 * reach;
}

// The smallest value of a plane over the box (centre c, half extents h), minus the same
// margin: every per-pixel value of a point of the box is at least this.
fn ppr_box_plane_min(pl: vec4<f32>, mag: vec4<f32>, c: vec3<f32>, h: vec3<f32>) -> f32 {
    let reach = dot(abs(c) + h, mag.xyz) + mag.w;
    return dot(c, pl.xyz) - dot(h, abs(pl.xyz)) + pl.w - 1e-5 * reach;
}

fn box_side_max(t: ShapeTest, i: u32, c: vec3<f32>, h: vec3<f32>) -> f32 {
    let s = test_side(t, i);
    return ppr_box_plane_max(s.plane, s.reach, c, h);
}

fn box_side_min(t: ShapeTest, i: u32, c: vec3<f32>, h: vec3<f32>) -> f32 {
    let s = test_side(t, i);
    return ppr_box_plane_min(s.plane, s.reach, c, h);
}

// Bit of a block-list entry: the whole box of the block's positions lies inside the
// shape's pyramid (every side's smallest value over the box >= 0, with the margin), so
// every pixel of the block passes the four side tests and the projection tests only the
// plane. The rest of the entry is the position in `visible`.
const INSIDE_ENTRY: u32 = 0x80000000u;
// Bench only (false: no entry is flagged, and subgroup culling flags no candidate: every
// pixel runs the five tests).
override INSIDE_ENTRIES: bool = true;

// Conservative box test: may some point of the box [lo, hi] (a block's pixel positions)
// be reflected by the shape into its rectangle? It may unless the whole box lies behind
// the plane or outside one side of the pyramid. Monotone in the box: a box holding
// another passes whenever the smaller one does.
fn box_may_reflect(t: ShapeTest, lo: vec3<f32>, hi: vec3<f32>) -> bool {
    let c = 0.5 * (lo + hi);
    let h = 0.5 * (hi - lo);
    return ppr_box_plane_max(t.plane, abs(t.plane), c, h) > 0.0
        && box_side_max(t, 0u, c, h) >= 0.0
        && box_side_max(t, 1u, c, h) >= 0.0
        && box_side_max(t, 2u, c, h) >= 0.0
        && box_side_max(t, 3u, c, h) >= 0.0;
}

// The block-list entry of the shape at position `k` of `visible` whose test `t` passed
// box_may_reflect for the box [lo, hi]: `k`, flagged INSIDE_ENTRY where the box lies
// inside all four sides of the pyramid.
fn list_entry(k: u32, t: ShapeTest, lo: vec3<f32>, hi: vec3<f32>) -> u32 {
    return select(k, k | INSIDE_ENTRY, box_inside_sides(t, lo, hi));
}

// Whether the whole box [lo, hi] lies inside all four sides of the shape's pyramid (every
// side's smallest value over the box > 0, with the margin): then every point of the box
// that lies in front of the plane is reflected into the rectangle. Always false without
// INSIDE_ENTRIES.
fn box_inside_sides(t: ShapeTest, lo: vec3<f32>, hi: vec3<f32>) -> bool {
    if (!INSIDE_ENTRIES) {
        return false;
    }
    let c = 0.5 * (lo + hi);
    let h = 0.5 * (hi - lo);
    let inside = min(
        min(box_side_min(t, 0u, c, h), box_side_min(t, 1u, c, h)),
        min(box_side_min(t, 2u, c, h), box_side_min(t, 3u, c, h)),
    );
    return inside > 0.0;
}

// The box reduction: BOX_SLOTS copies of each bound (ordered float bits), so that at most
// TILE_GROUP_THREADS / BOX_SLOTS threads contend for one address; then per thread its
// pass flag, packed into words for the ranks.
const BOX_SLOTS: u32 = 8u;
var<workgroup> box_min: array<array<atomic<u32>, 3>, BOX_SLOTS>;
var<workgroup> box_max: array<array<atomic<u32>, 3>, BOX_SLOTS>;
// The box's ordered bounds: min x, y, z, then max x, y, z.
var<workgroup> box_words: array<u32, 6>;
// The chunk ranks' pass bits, a word per 32 threads: two sets, used by alternate chunks (one
// is zeroed while the other is read), and a plain copy of the current set for every thread
// to read.
const PASS_WORDS: u32 = TILE_GROUP_THREADS / 32u;
var<workgroup> pass_bits: array<array<atomic<u32>, PASS_WORDS>, 2>;
var<workgroup> pass_words: array<u32, PASS_WORDS>;

// The camera-relative position of a pixel, when its depth is a rendered surface and the
// position is finite, with its on-plane tolerance as w (> 0; ppr_on_plane_tolerance), else
// w = 0. The one rule both culling levels and the per-pixel projection use, so that a
// block's box holds every position its pixels test.
fn tile_pixel_position(pixel: vec2<u32>) -> vec4<f32> {
    if (!all(pixel < frame.size)) {
        return vec4<f32>(0.0);
    }
    let depth = textureLoad(depth_tex, vec2<i32>(pixel), 0).r;
    if (!ppr_is_valid_depth(depth)) {
        return vec4<f32>(0.0);
    }
    let h = ppr_unproject_homogeneous(vec2<f32>(pixel) + 0.5, depth);
    let p = h.xyz / h.w;
    if (!(ppr_is_finite2(p.xy) && ppr_is_finite(p.z) && all(abs(p) < vec3<f32>(1e30)))) {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(p, ppr_on_plane_tolerance(depth, h.w, p));
}

// Order-preserving map of a float to a u32 (for atomicMin/atomicMax on signed floats).
fn ordered_bits(x: f32) -> u32 {
    let b = bitcast<u32>(x);
    return select(b | 0x80000000u, ~b, (b & 0x80000000u) != 0u);
}

fn from_ordered_bits(u: u32) -> f32 {
    return bitcast<f32>(select(~u, u & 0x7fffffffu, (u & 0x80000000u) != 0u));
}

// The box of the positions the workgroup's threads hold (`lo` > `hi` on an axis for a
// thread without any). Every thread gets the box; `lo.x > hi.x` when it is empty. Once a
// workgroup (the slots are not reset for a second box), from uniform control flow.
struct TileBox {
    lo: vec3<f32>,
    hi: vec3<f32>,
}

fn ordered3(v: vec3<f32>) -> vec3<u32> {
    return vec3<u32>(ordered_bits(v.x), ordered_bits(v.y), ordered_bits(v.z));
}

fn from_ordered3(u: vec3<u32>) -> vec3<f32> {
    return vec3<f32>(from_ordered_bits(u.x), from_ordered_bits(u.y), from_ordered_bits(u.z));
}

fn workgroup_box(lid: u32, lo: vec3<f32>, hi: vec3<f32>) -> TileBox {
    return workgroup_box_of(lid, lo, hi, true);
}

// workgroup_box where only the invocations with `takes_part` bring their [lo, hi] (the
// projection's SUBGROUP_BOX: one invocation a subgroup, holding the subgroup's box).
fn workgroup_box_of(lid: u32, lo: vec3<f32>, hi: vec3<f32>, takes_part: bool) -> TileBox {
    if (lid < BOX_SLOTS) {
        for (var c = 0u; c < 3u; c++) {
            atomicStore(&box_min[lid][c], 0xffffffffu);
            atomicStore(&box_max[lid][c], 0u);
        }
    }
    // The first chunk's pass bits (chunk_rank zeroes the other set itself).
    if (lid < PASS_WORDS) {
        atomicStore(&pass_bits[0][lid], 0u);
    }
    workgroupBarrier();
    let slot = lid % BOX_SLOTS;
    if (takes_part && lo.x <= hi.x) {
        let l = ordered3(lo);
        let h = ordered3(hi);
        atomicMin(&box_min[slot][0], l.x);
        atomicMin(&box_min[slot][1], l.y);
        atomicMin(&box_min[slot][2], l.z);
        atomicMax(&box_max[slot][0], h.x);
        atomicMax(&box_max[slot][1], h.y);
        atomicMax(&box_max[slot][2], h.z);
    }
    workgroupBarrier();
    // Six threads read the slots, one bound each (atomic loads of one address by a whole
    // warp would be serialised; one thread reading all 48 waits on each in turn), and
    // publish the box in plain workgroup memory.
    if (lid < 6u) {
        let c = lid % 3u;
        var bound = select(0xffffffffu, 0u, lid >= 3u);
        for (var i = 0u; i < BOX_SLOTS; i++) {
            if (lid < 3u) {
                bound = min(bound, atomicLoad(&box_min[i][c]));
            } else {
                bound = max(bound, atomicLoad(&box_max[i][c]));
            }
        }
        box_words[lid] = bound;
    }
    workgroupBarrier();
    let mins = vec3<u32>(box_words[0], box_words[1], box_words[2]);
    let maxs = vec3<u32>(box_words[3], box_words[4], box_words[5]);
    // No barrier after these reads: every caller takes one box a workgroup, so neither the
    // slots nor `box_words` are written again.
    if (mins.x <= maxs.x) {
        return TileBox(from_ordered3(mins), from_ordered3(maxs));
    }
    return TileBox(vec3<f32>(1.0), vec3<f32>(-1.0));
}

// Ordered compaction of chunk `chunk` (0, 1, ...) of TILE_GROUP_THREADS candidates:
// (rank, total), where rank is the number of passing threads before this one and total the
// chunk's passing count. The passing threads set their bits in their words (a shared
// atomic OR, no thread waits on another's flag); PASS_WORDS threads copy the words out and zero
// the next chunk's set; the ranks are popcounts. Two barriers a chunk. Call from uniform
// control flow, after workgroup_box (which zeroes the first chunk's set), chunks in order.
fn chunk_rank(lid: u32, chunk: u32, passes: bool) -> vec2<u32> {
    let half = chunk & 1u;
    if (passes) {
        atomicOr(&pass_bits[half][lid / 32u], 1u << (lid % 32u));
    }
    workgroupBarrier();
    // The other set was last read before the previous chunk's second barrier, and is next
    // written after this chunk's.
    if (lid < PASS_WORDS) {
        pass_words[lid] = atomicLoad(&pass_bits[half][lid]);
        atomicStore(&pass_bits[half ^ 1u][lid], 0u);
    }
    workgroupBarrier();
    let word = lid / 32u;
    var rank = countOneBits(pass_words[word] & ((1u << (lid % 32u)) - 1u));
    var total = 0u;
    for (var w = 0u; w < PASS_WORDS; w++) {
        let n = countOneBits(pass_words[w]);
        total += n;
        if (w < word) {
            rank += n;
        }
    }
    // No third barrier: the next chunk's copy into `pass_words` comes after its first
    // barrier, which every thread reaches only once it has read these.
    return vec2<u32>(rank, total);
}

// Blocks of the viewport: (columns, count).
fn block_grid() -> vec2<u32> {
    let cols = (frame.size.x + BLOCK_SIZE - 1u) / BLOCK_SIZE;
    let rows = (frame.size.y + BLOCK_SIZE - 1u) / BLOCK_SIZE;
    return vec2<u32>(cols, cols * rows);
}

// Rows between a thread's pixels 0, 1 and its pixels 2, 3: 16 puts one pixel in each
// 16x16 quarter of the block; 2 (the projection's compact layout) gives the threads of
// thread rows 2w and 2w + 1 (one 32-wide subgroup) the block rows 4w to 4w + 3, so a
// subgroup's pixels are close together. Every load stays coalesced either way (16
// threads read 16 adjacent pixels of one row).
override QUAD_ROW_STEP: u32 = 16u;

// Pixel `j` (0..3) of the thread whose first pixel is `base` (quad_base).
fn quad_pixel(base: vec2<u32>, j: u32) -> vec2<u32> {
    return base + vec2<u32>((j & 1u) * QUARTER, (j >> 1u) * QUAD_ROW_STEP);
}

// The first pixel of thread `local` (16x16 threads) of the block at `lo`.
fn quad_base(lo: vec2<u32>, local: vec2<u32>) -> vec2<u32> {
    if (QUAD_ROW_STEP == QUARTER) {
        return lo + local;
    }
    return lo + vec2<u32>(local.x, (local.y & ~1u) * 2u + (local.y & 1u));
}

// Super-tiles of the viewport: (columns, count).
fn super_tile_grid() -> vec2<u32> {
    let cols = (frame.size.x + SUPER_TILE_SIZE - 1u) / SUPER_TILE_SIZE;
    let rows = (frame.size.y + SUPER_TILE_SIZE - 1u) / SUPER_TILE_SIZE;
    return vec2<u32>(cols, cols * rows);
}
