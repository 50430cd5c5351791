// Projection pass: for every pixel, mirror its position against the candidate reflectors,
// test the reflection point against the rectangle and its occluders, and atomicMin the
// encoded screen offset into the intermediate buffer where the pixel is reflected.
// Seed: PPR_ProjectionPassWrite, and the bonus slides' "multiple parallel shapes".
//
// Each workgroup covers a 32x32-pixel block, each thread four pixels (two rows of two
// pixels 16 apart, so that every load of the block is coalesced; QUAD_ROW_STEP in
// tile_test.wgsl says how far apart the rows are): the four depths are loaded before any
// work, and each shape's test (its plane and two axis forms, ShapeTest in tile_test.wgsl)
// is loaded once for the four pixels.
//
// Variants (pipeline-overridable constants, chosen by the FramePlan):
// - TILE_CULLING: each block's pixels test only the block's list of the visible shapes
//   that may reflect some pixel of it (block_lists.wgsl, dispatched just before: the box
//   of the block's pixel positions against each shape's five planes). Otherwise every
//   pixel loops over all visible shapes.
// - FUSED_LISTS (with TILE_CULLING): the projection builds its block's list itself, into
//   workgroup memory, from the positions it has loaded anyway (block_list_in_workgroup:
//   the same box, test and order as block_lists.wgsl, whose pass then does not run). Saves
//   that pass's launch, depth reads and unprojections and the list's trip through memory;
//   costs the projection barriers. Its code and workgroup memory are in fused_lists.wgsl,
//   only in the module of the fused variants (fused_lists_stub.wgsl in the others: a
//   kernel with workgroup memory, even unused, ran 0.004 ms slower on the H200). The
//   renderer keeps it off on CPU adapters by default
//   (Mesa's llvmpipe turns barriers into coroutines; an earlier projection with its list
//   in workgroup memory took 27 s to compile there, docs/perf/runtime.md).
// - SUPER_TILES (with TILE_CULLING): the block lists were built from 64x64 super-tiles'
//   lists (super_tile_lists.wgsl); a block whose own list overflowed takes its
//   super-tile's list instead of every visible shape.
// - SOURCE_BOXES: each visible shape comes with the screen box of the pixels that may
//   reflect into it (computed on the CPU, source_box.rs); a block that does not overlap
//   it skips the shape (a uniform branch: the whole workgroup skips together).
// - PARALLEL_RULE: among shapes of one parallel group that reflect a pixel, only the one
//   with the smallest plane distance writes (each pixel reflected at most once per
//   orientation). The visible list is sorted by group, and so are the block lists.
// - DEPTH_OCCLUSION: a reflection is not written where the surface seen at its target
//   pixel lies in front of the reflector's plane (something stands between the camera
//   and the reflection point there): one depth read per write, whatever occludes.
// - OCCLUDER_TESTS: the seed's test instead: the ray to the reflection point against the
//   shape's list of occluding reflectors (from the extractor).
// - PATH_BLOCKERS: a write into a member of a parallel family first tests whether its
//   path, from the pixel down to the reflection point, crosses the member in front of it
//   (its test's `blocker`, a plane group member's rectangle's last word;
//   crates/ppr-runtime/src/path_blockers.rs): a flight of treads writes the nearest
//   tread's reflection, not the four behind the tread above it.
// - LAYERS: glass panels and water planes with atlas regions exist this frame (without
//   them the layer loop is compiled out).
// - DEBUG_WRITES: record, per source pixel, a bit per visible shape it wrote for.
// - UNIFORM_TESTS: the shape tests are read from a uniform copy (constant cache) instead
//   of the storage buffer.
// - SUBGROUP_CULL: each subgroup takes the box of its pixels' positions and tests its
//   candidates' boxes against it, one candidate per invocation (subgroup_cull.wgsl, a
//   ballot per 32 candidates, no barrier): the loop then visits only the candidates that
//   may reflect some pixel of the subgroup, and those whose pyramid holds the subgroup's
//   whole box test the plane only (a second ballot, as block lists' INSIDE_ENTRY). The
//   block-list pass's test at the subgroup's scale, without its pass; with
//   subgroup_cull_fallback.wgsl (no subgroup operations) each invocation alone, for the
//   tests.
// - ABLATION (bench only, never a correct image): 1 returns at once, 2 reads depth and
//   positions only, 3 also runs the shape tests, 4 writes without encoding, 5 encodes
//   without writing, 6 does all but the atomic.
// Not a variant (the plan decides per frame): a test whose `shape` has GROUP_TEST_FLAG
// stands for a merged group of coplanar shapes, tested by the pyramid of their bounding
// rectangle; a pixel that passes writes only if its reflection point lies on a member
// (group_member, a grid lookup).
// - PARALLEL_TREES: some test (its `shape` flagged TREE_TEST_FLAG) stands for the visible
//   shapes of a parallel family at many plane offsets (crates/ppr-runtime/src/
//   parallel_trees.rs): its plane is the lowest member's, and a pixel in front of it walks
//   the family's tree, testing the members it reaches with their own tests (tree_pixel).
// - OCCLUSION_FIRST (the plan's occlusion_first): a write tests the depth occlusion at its
//   target before its encoding, not after (the same buffer: a write happens where it is
//   not occluded and lowers the stored value, in either order). Occluded writes then skip
//   the encoding; writes that lose to the stored value pay the test before they find out.

override TILE_CULLING: bool = false;
override SUPER_TILES: bool = false;
override FUSED_LISTS: bool = false;
override PARALLEL_RULE: bool = false;
override OCCLUDER_TESTS: bool = false;
override PATH_BLOCKERS: bool = false;
override DEPTH_OCCLUSION: bool = false;
override LAYERS: bool = false;
override DEBUG_WRITES: bool = false;
// Debug: record, per pixel, its block's candidate-list length instead of write bits.
override DEBUG_TILE_LISTS: bool = false;
override SOURCE_BOXES: bool = false;
override UNIFORM_TESTS: bool = false;
override PARALLEL_TREES: bool = false;
override OCCLUSION_FIRST: bool = false;
override SUBGROUP_CULL: bool = false;
// How the fused lists reduce the box of the block's positions (fused_lists.wgsl): 0 the
// workgroup's atomics, 1 per subgroup first, 2 per subgroup into slots, one barrier.
override SUBGROUP_BOX: u32 = 0u;
// The fused lists' first chunk of candidates loaded before the box reduction's barriers
// (fused_lists.wgsl), so that the loads wait beside them instead of after them.
override LIST_PREFETCH: bool = false;
override ABLATION: u32 = 0u;

const NO_SHAPE: u32 = 0xffffffffu;

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var depth_tex: texture_2d<f32>;
@group(0) @binding(2) var<storage, read> shapes: array<Shape>;
// Per visible shape (in plan order), then per layer: its test planes, shape index, group.
@group(0) @binding(3) var<storage, read> tests: array<ShapeTest>;
@group(0) @binding(4) var<storage, read> occluders: array<u32>;
@group(0) @binding(5) var<storage, read_write> intermediate: array<atomic<u32>>;
@group(0) @binding(6) var<storage, read_write> debug_writes: array<u32>;
// Layer reflectors (glass, water) and their atlas (layer_reflection.wgsl reads it).
@group(0) @binding(7) var<storage, read> layers: array<Layer>;
@group(0) @binding(8) var<storage, read_write> atlas: array<atomic<u32>>;
// Super-tile counts and lists (super_tile_lists.wgsl), read with SUPER_TILES.
@group(0) @binding(9) var<storage, read> super_lists: array<u32>;
// Per visible shape, then per layer: the screen box (min.xy, max.xy exclusive) of the
// pixels that may reflect into it, read with SOURCE_BOXES.
@group(0) @binding(10) var<storage, read> source_boxes: array<vec4<u32>>;
// Block counts and lists (block_lists.wgsl), read with TILE_CULLING.
@group(0) @binding(11) var<storage, read> block_lists: array<u32>;
// The first entries of `tests` again, read with UNIFORM_TESTS (the plan sets it when every
// visible shape and layer fits): uniform loads go through the constant cache.
@group(0) @binding(12) var<uniform> uniform_tests: array<ShapeTest, 128>;
// Merged plane groups (crates/ppr-runtime/src/plane_groups.rs): per group a header of 16
// words (PlaneGroup), then the frame's parallel trees (parallel_trees.rs), then the grids'
// static words.
@group(0) @binding(13) var<storage, read> plane_groups: array<u32>;
// The same words as vec4s, for the parallel trees' nodes (8 words each, 32-byte aligned,
// parallel_trees.rs): two loads a node instead of eight. Only there: the plane groups'
// lookups through vec4 words with a computed lane were slower (runtime.md).
@group(0) @binding(14) var<storage, read> tree_nodes: array<vec4<u32>>;

// Bit of ShapeTest.shape: the test is a merged plane group's, the rest its header slot.
const GROUP_TEST_FLAG: u32 = 0x80000000u;
// Words per member rectangle in the grids.
const GROUP_RECT_WORDS: u32 = 8u;

fn group_f32(i: u32) -> f32 {
    return bitcast<f32>(plane_groups[i]);
}

fn group_vec3(i: u32) -> vec3<f32> {
    return vec3<f32>(group_f32(i), group_f32(i + 1u), group_f32(i + 2u));
}

// The member of the merged group in header slot `slot` on which the reflection point
// `hit` (camera-relative, on the group's plane) lies, as the word position of its
// rectangle (words: centre, half extents, axis, shape, path blocker), NO_SHAPE where none:
// the grid cell holding it lists the members that overlap the cell, each tested by its
// own axes.
fn group_member(slot: u32, hit: vec3<f32>) -> u32 {
    let h = slot * 16u;
    let l = hit - group_vec3(h);
    let cells_start = plane_groups[h + 3u];
    let u = dot(l, group_vec3(h + 4u));
    let v = dot(l, group_vec3(h + 8u));
    let cells = vec2<u32>(plane_groups[h + 7u], plane_groups[h + 11u]);
    let c = floor(vec2<f32>(u, v) * vec2<f32>(group_f32(h + 12u), group_f32(h + 13u)));
    if (!(all(c >= vec2<f32>(0.0)) && all(c < vec2<f32>(cells)))) {
        return NO_SHAPE;
    }
    let cell = cells_start + u32(c.x) + u32(c.y) * cells.x;
    let rects = plane_groups[h + 14u];
    let end = cells_start + plane_groups[cell + 1u];
    for (var i = cells_start + plane_groups[cell]; i < end; i++) {
        let r = rects + GROUP_RECT_WORDS * plane_groups[i];
        let d = vec2<f32>(u - group_f32(r), v - group_f32(r + 1u));
        let axis = vec2<f32>(group_f32(r + 4u), group_f32(r + 5u));
        let lu = d.x * axis.x + d.y * axis.y;
        let lv = d.y * axis.x - d.x * axis.y;
        if (abs(lu) <= group_f32(r + 2u) && abs(lv) <= group_f32(r + 3u)) {
            return r;
        }
    }
    return NO_SHAPE;
}

// Bit of ShapeTest.shape: the test is a parallel tree's, the rest its header's word.
const TREE_TEST_FLAG: u32 = 0x40000000u;
const TREE_NODE_WORDS: u32 = 8u;

// Whether a member of the tree node at word `w` may reflect the pixel (its coordinate
// `zp` along the family's normal, `uv` in its plane; members must lie below `reach`). The
// reflection point for a plane offset d is t(d) * uv, t(d) = d / (2d - zp), monotone in d:
// its u over the node's offsets is a segment, tested against the node's u range; its
// v - alpha * d (alpha: the node's slope of v against d) is a hyperbola plus a line in d,
// whose range is its values at the ends and, where it turns inside, at its stationary
// point; tested against the node's range of v - alpha * d. Boxes widened by `m`. The CPU
// model is parallel_trees.rs's node_meets. The node at word `w` is read from `tree_nodes`.
fn tree_node_meets(w: u32, zp: f32, uv: vec2<f32>, reach: f32, m: f32) -> bool {
    let a = bitcast<vec4<f32>>(tree_nodes[w >> 2u]);
    let b = bitcast<vec4<f32>>(tree_nodes[(w >> 2u) + 1u]);
    let lo = a.x;
    if (!(lo < reach)) {
        return false;
    }
    let hi = min(a.y, reach);
    let ta = lo / (2.0 * lo - zp);
    let tb = hi / (2.0 * hi - zp);
    // u = t * uv.x is linear in t: its range is its values at the ends.
    let ua = ta * uv.x;
    let ub = tb * uv.x;
    if (max(ua, ub) + m < a.z || min(ua, ub) - m > a.w) {
        return false;
    }
    let alpha = b.z;
    let wa = ta * uv.y - alpha * lo;
    let wb = tb * uv.y - alpha * hi;
    var w0 = min(wa, wb);
    var w1 = max(wa, wb);
    // The stationary point: (2d - zp)^2 = -uv.y * zp / alpha (word 7 holds 1 / alpha, 0
    // for alpha = 0).
    let q = -uv.y * zp * b.w;
    if (q > 0.0) {
        let d = 0.5 * (zp - sqrt(q));
        if (lo < d && d < hi) {
            let v = d / (2.0 * d - zp) * uv.y - alpha * d;
            w0 = min(w0, v);
            w1 = max(w1, v);
        }
    }
    let mw = m + 1e-5 * abs(alpha) * (abs(lo) + abs(zp));
    return w1 + mw >= b.x && w0 - mw <= b.y;
}

// Tests member test `k` of a tree for one pixel (position `p`, on-plane tolerance `tol`)
// and writes the pixel's reflection in it where it passes, as the plain loop would.
fn tree_member(k: u32, pixel: vec2<u32>, p: vec3<f32>, tol: f32) {
    let t = tests[k];
    let dist = p.x * t.plane.x + p.y * t.plane.y + p.z * t.plane.z + t.plane.w;
    let inside = inside_pyramid(t, p, dist);
    if (ABLATION == 3u) {
        // Tests only: the walk and the members' tests, no write.
        if (dist == 1234.5 && inside) {
            atomicStore(&intermediate[0], 0u);
        }
    } else if (dist > tol && inside) {
        reflect_pixel(pixel, p, dist, t.plane, t.shape, t.blocker);
    }
}

// Most candidates a pixel takes from a tree's offset index before it walks the tree
// instead (parallel_trees.rs, INDEX_MOST_MEMBERS).
const INDEX_MOST_MEMBERS: u32 = 64u;
// Buckets by which a pixel widens each offset interval (parallel_trees.rs, INDEX_SLACK).
const INDEX_SLACK: f32 = 0.25;

// {d in [a, b] : qa d^2 + qb d + qc >= 0} as two intervals (x, y) and (z, w), empty where
// the first end is above the second; a superset (a negative discriminant counts as a
// double root). The CPU model is parallel_trees.rs's quadratic_set.
fn quadratic_set(qa: f32, qb: f32, qc: f32, a: f32, b: f32) -> vec4<f32> {
    let none = vec2<f32>(1.0, 0.0);
    if (qa == 0.0) {
        if (qb == 0.0) {
            return select(vec4<f32>(none, none), vec4<f32>(a, b, none), qc >= 0.0);
        }
        let r = -qc / qb;
        return select(vec4<f32>(a, min(b, r), none), vec4<f32>(max(a, r), b, none), qb > 0.0);
    }
    let disc = qb * qb - 4.0 * qa * qc;
    let s = sqrt(max(disc, 0.0));
    let q = -0.5 * (qb + select(s, -s, qb < 0.0));
    let r1 = q / qa;
    // No real roots (or one): the vertex twice.
    let r2 = select(qc / q, r1, disc <= 0.0 || q == 0.0);
    let lo = min(r1, r2);
    let hi = max(r1, r2);
    if (qa > 0.0) {
        return vec4<f32>(a, min(b, lo), max(a, hi), b);
    }
    return vec4<f32>(max(a, lo), min(b, hi), none);
}

// The plane offsets d at which the root node `a`, `b` (its two vec4s) may hold a member
// that reflects the pixel (`zp`, `uv`, `reach`, margin `m` as tree_node_meets'), as two
// intervals in ascending order (xy, zw; each empty where x > y). Below the camera (d < 0,
// where members face it) 2d - zp < 0, so each bound times it is a polynomial in d: t u >=
// U iff (2U - u) d - U zp >= 0, t u <= U iff (u - 2U) d + U zp >= 0; t v - alpha d >= W
// iff 2 alpha d^2 - (v + alpha zp - 2W) d - W zp >= 0, <= W the same negated. t v - alpha
// d has one stationary point at most: one of the slab's bounds passes in two pieces at
// most, so all of them in two. The CPU model is parallel_trees.rs's index_interval.
fn index_interval(a: vec4<f32>, b: vec4<f32>, zp: f32, uv: vec2<f32>, reach: f32, m: f32) -> vec4<f32> {
    let u0 = a.z - m;
    let u1 = a.w + m;
    let d = quadratic_set(0.0, 2.0 * u0 - uv.x, -u0 * zp, a.x, min(min(a.y, reach), 0.0)).xy;
    let e = quadratic_set(0.0, uv.x - 2.0 * u1, u1 * zp, d.x, d.y).xy;
    let alpha = b.z;
    let mw = m + 1e-5 * abs(alpha) * (abs(a.x) + abs(zp));
    let w0 = b.x - mw;
    let w1 = b.y + mw;
    let above = quadratic_set(2.0 * alpha, -(uv.y + alpha * zp - 2.0 * w0), -w0 * zp, e.x, e.y);
    let below = quadratic_set(-2.0 * alpha, uv.y + alpha * zp - 2.0 * w1, w1 * zp, e.x, e.y);
    if (above.z <= above.w) {
        // Above in two pieces: below's hull (one piece, in exact arithmetic) cuts each.
        var h = below.xy;
        if (below.z <= below.w) {
            h = select(below.zw, vec2<f32>(below.x, below.w), below.x <= below.y);
        }
        return vec4<f32>(max(above.x, h.x), min(above.y, h.y), max(above.z, h.x), min(above.w, h.y));
    }
    return vec4<f32>(max(above.x, below.x), min(above.y, below.y), max(above.x, below.z), min(above.y, below.w));
}

// The members of a tree's offset index (at word `index`, `count` buckets, lowest offset
// `d0`, buckets per metre `per_metre`) whose bucket meets offsets `iv`, widened by
// INDEX_SLACK buckets a side, as index positions [x, y), from `start` on.
fn index_range(index: u32, count: u32, d0: f32, per_metre: f32, iv: vec2<f32>, start: u32) -> vec2<u32> {
    let last = f32(count - 1u);
    let b0 = u32(clamp(floor((iv.x - d0) * per_metre - INDEX_SLACK), 0.0, last));
    let b1 = u32(clamp(floor((iv.y - d0) * per_metre + INDEX_SLACK), 0.0, last));
    let first = max(plane_groups[index + b0], start);
    return vec2<u32>(first, max(plane_groups[index + b1 + 1u], first));
}

// The parallel tree at header word `h` through its offset index, for one pixel (zp, uv in
// the family's frame): the members of the offsets that pass the root's test
// (index_interval), looked up in the index's offset buckets, each tested with its own
// test. False where the tree has no index or the pixel must walk it instead (more than
// INDEX_MOST_MEMBERS candidates, an interval not a number). The CPU model is
// parallel_trees.rs's indexed_leaves.
fn tree_index_pixel(h: u32, pixel: vec2<u32>, p: vec3<f32>, tol: f32, zp: f32, uv: vec2<f32>, reach: f32, m: f32) -> bool {
    let index = plane_groups[h + 13u];
    if (index == 0u) {
        return false;
    }
    let w = plane_groups[h + 3u] >> 2u;
    let iv = index_interval(bitcast<vec4<f32>>(tree_nodes[w]), bitcast<vec4<f32>>(tree_nodes[w + 1u]), zp, uv, reach, m);
    let has = vec2<bool>(iv.x <= iv.y, iv.z <= iv.w);
    // Not a number (no comparison holds) or out of range: walk.
    let big = abs(iv) >= vec4<f32>(1e30);
    if (!(has.x || iv.x > iv.y) || !(has.y || iv.z > iv.w) || (has.x && any(big.xy)) || (has.y && any(big.zw))) {
        return false;
    }
    let count = plane_groups[h + 11u];
    let d0 = bitcast<f32>(plane_groups[h + 14u]);
    let per_metre = bitcast<f32>(plane_groups[h + 15u]);
    var r0 = vec2<u32>(0u);
    var r1 = vec2<u32>(0u);
    if (has.x) {
        r0 = index_range(index, count, d0, per_metre, iv.xy, 0u);
    }
    if (has.y) {
        r1 = index_range(index, count, d0, per_metre, iv.zw, r0.y);
    }
    if ((r0.y - r0.x) + (r1.y - r1.x) > INDEX_MOST_MEMBERS) {
        return false;
    }
    let tests_start = plane_groups[h + 12u];
    let order = index + count + 1u;
    for (var i = r0.x; i < r0.y; i++) {
        tree_member(tests_start + plane_groups[order + i], pixel, p, tol);
    }
    for (var i = r1.x; i < r1.y; i++) {
        tree_member(tests_start + plane_groups[order + i], pixel, p, tol);
    }
    return true;
}

// Walks the parallel tree whose header is at word `h` for one pixel (position `p`, on-plane
// tolerance `tol`) and writes its reflection in every member that passes the member's own
// test, as the plain loop would; through the tree's offset index where it has one and the
// pixel's candidates are few.
fn tree_pixel(h: u32, pixel: vec2<u32>, p: vec3<f32>, tol: f32) {
    let n = group_vec3(h);
    let node_start = plane_groups[h + 3u];
    let leaves = plane_groups[h + 7u];
    let tests_start = plane_groups[h + 12u];
    let zp = dot(p, n);
    let uv = vec2<f32>(dot(p, group_vec3(h + 4u)), dot(p, group_vec3(h + 8u)));
    let reach = zp - 0.5 * tol;
    let m = 1e-5 * (abs(uv.x) + abs(uv.y) + abs(zp));
    if (tree_index_pixel(h, pixel, p, tol, zp, uv, reach, m)) {
        return;
    }
    var node = 1u;
    loop {
        if (tree_node_meets(node_start + (node - 1u) * TREE_NODE_WORDS, zp, uv, reach, m)) {
            if (node < leaves) {
                node = node * 2u;
                continue;
            }
            tree_member(tests_start + node - leaves, pixel, p, tol);
        }
        // The next node in walk order: up past right children (the trailing ones of the
        // node's number, one shift for all: no loop whose count differs between the lanes),
        // then the right sibling.
        node = node >> countTrailingZeros(~node);
        if (node == 0u) {
            break;
        }
        node += 1u;
    }
}

fn shape_test(k: u32) -> ShapeTest {
    if (UNIFORM_TESTS) {
        return uniform_tests[k];
    }
    return tests[k];
}

// Whether the ray from the camera to `hit` crosses occluder `o` before reaching it
// (strictly between, so that a point on a coplanar neighbour is not occluded), without a
// division: t = plane_dist / dot(hit, n) must lie in (0, 0.9999), and the crossing point in
// the rectangle, each multiplied out by dn.
fn occluder_hit(hit: vec3<f32>, o: Shape) -> bool {
    let dn = dot(hit, o.normal);
    let pd = o.plane_dist;
    if (!(abs(dn) > 1e-20) || !((pd > 0.0) == (dn > 0.0)) || !(abs(pd) < 0.9999 * abs(dn))) {
        return false;
    }
    let lu = dot(hit, o.axis_u) * pd - o.center_u * dn;
    let lv = dot(hit, o.axis_v) * pd - o.center_v * dn;
    return abs(lu) <= o.half_u * abs(dn) && abs(lv) <= o.half_v * abs(dn);
}

fn is_occluded(hit: vec3<f32>, s: Shape) -> bool {
    for (var k = 0u; k < s.occluder_count; k++) {
        let o = shapes[occluders[s.occluder_start + k]];
        if ((o.flags & PPR_SHAPE_OCCLUDES) != 0u && occluder_hit(hit, o)) {
            return true;
        }
    }
    return false;
}

// Where the reflection of `pixel` (camera-relative position `mirrored` once mirrored)
// lands: its target pixel and the encoding's parts (target pixel - pixel, and the point in
// the target pixel from its centre); `on_screen` false where it does not land on screen.
struct ProjectedPoint {
    t: vec2<u32>,
    whole: vec2<i32>,
    fract: vec2<f32>,
    on_screen: bool,
}

fn projection_point(pixel: vec2<u32>, mirrored: vec3<f32>) -> ProjectedPoint {
    var out = ProjectedPoint(vec2<u32>(0u), vec2<i32>(0), vec2<f32>(0.0), false);
    let clip = frame.clip_from_rel * vec4<f32>(mirrored, 1.0);
    if (!(clip.w > 0.0)) {
        return out;
    }
    let ndc = clip.xy / clip.w;
    if (!all(abs(ndc) < vec2<f32>(1.0))) {
        return out;
    }
    let target_crd = (ndc * vec2<f32>(0.5, -0.5) + 0.5) * frame.resolution.xy;
    // Whole part from integer pixels, so that it points exactly at the source pixel.
    out.t = min(vec2<u32>(target_crd), frame.size - 1u);
    out.whole = vec2<i32>(out.t) - vec2<i32>(pixel);
    out.fract = target_crd - vec2<f32>(out.t) - 0.5;
    out.on_screen = true;
    return out;
}

// The encoded value of a projected point (PPR_CLEAR_VALUE where it does not fit the
// encoding).
fn projected_value(pt: ProjectedPoint) -> u32 {
    if (ABLATION == 4u) {
        return (pt.t.x ^ (pt.t.y << 12u)) & 0x7fffffffu;
    }
    return ppr_encode_parts(pt.whole, pt.fract, frame.encoding);
}

// Where the reflection of `pixel` lands: (target x, target y, encoded value); the value is
// PPR_CLEAR_VALUE when it does not land on screen or does not fit the encoding.
fn projection_target(pixel: vec2<u32>, mirrored: vec3<f32>) -> vec3<u32> {
    let pt = projection_point(pixel, mirrored);
    if (!pt.on_screen) {
        return vec3<u32>(0u, 0u, PPR_CLEAR_VALUE);
    }
    return vec3<u32>(pt.t, projected_value(pt));
}

// Whether the surface the depth buffer shows at pixel `t` lies in front of the plane
// (normal `n`, distance `d` from the camera) by more than its on-plane tolerance: then
// something stands between the camera and any reflection point of that plane there.
// A glass panel with a layer this frame does not count: games may write glass to depth,
// and what lies behind it is still seen (and reflected) through it.
fn occluded_at(t: vec2<u32>, n: vec3<f32>, d: f32) -> bool {
    let q = tile_pixel_position(t);
    if (!(q.w > 0.0 && dot(q.xyz, n) - d > q.w)) {
        return false;
    }
    for (var l = 0u; LAYERS && l < frame.layer_count; l++) {
        if (layers[l].kind == PPR_KIND_TRANSPARENT && on_shape(q, shapes[layers[l].shape])) {
            return false;
        }
    }
    return true;
}

// Whether the position `q` (its on-plane tolerance in w) lies on shape `s`'s rectangle.
fn on_shape(q: vec4<f32>, s: Shape) -> bool {
    let l = q.xyz - s.center;
    return abs(dot(q.xyz, s.normal) - s.plane_dist) <= q.w
        && abs(dot(l, s.axis_u)) <= s.half_u + q.w
        && abs(dot(l, s.axis_v)) <= s.half_v + q.w;
}

// Writes the reflection of `pixel` into the main intermediate buffer (not where the plane
// `n`, `d` is occluded at the target, with DEPTH_OCCLUSION).
fn write_projection(pixel: vec2<u32>, mirrored: vec3<f32>, n: vec3<f32>, d: f32) -> bool {
    let pt = projection_point(pixel, mirrored);
    if (!pt.on_screen) {
        return false;
    }
    let t = pt.t;
    let index = t.x + t.y * frame.size.x;
    let mode = frame.flags & (PPR_FLAG_WRITE_LAST | PPR_FLAG_WRITE_MAX);
    // A plain load first: where a squeezed reflection maps many pixels onto one, most
    // writes lose, and a load is cheaper than the encoding, the occlusion test and the
    // atomic. Where the stored value's major whole part (its top field) is smaller than
    // this one's, this write loses without its encoding's divisions. Not with DEBUG_WRITES:
    // what a pixel is recorded as having written must not depend on the order of other
    // writes (the buffer ends the same: an occluded write never lowers a value).
    let pre_load = mode == 0u && !DEBUG_WRITES && ABLATION != 5u;
    var stored = PPR_CLEAR_VALUE;
    if (pre_load) {
        stored = atomicLoad(&intermediate[index]);
        if (ABLATION == 0u
            && ppr_parts_major_whole(pt.whole, pt.fract) > ppr_value_major_whole(stored, frame.encoding)) {
            return true;
        }
    }
    if (OCCLUSION_FIRST && DEPTH_OCCLUSION && occluded_at(t, n, d)) {
        return false;
    }
    let value = projected_value(pt);
    if (value == PPR_CLEAR_VALUE) {
        return false;
    }
    if (ABLATION == 5u) {
        if (value == 0x12345u) {
            atomicStore(&intermediate[index], value);
        }
        return true;
    }
    if (pre_load && stored <= value) {
        return true;
    }
    if (!OCCLUSION_FIRST && DEPTH_OCCLUSION && occluded_at(t, n, d)) {
        return false;
    }
    if (ABLATION == 6u) {
        if (value == 0x12345u) {
            atomicStore(&intermediate[index], value);
        }
    } else if (mode == 0u) {
        atomicMin(&intermediate[index], value);
    } else if ((mode & PPR_FLAG_WRITE_LAST) != 0u) {
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

// Writes the reflection of `pixel` into layer `l`'s atlas region (if it lands there and,
// with DEPTH_OCCLUSION, the layer's plane `s` is not occluded there).
fn write_layer(pixel: vec2<u32>, mirrored: vec3<f32>, l: Layer, s: Shape) {
    let tv = projection_target(pixel, mirrored);
    if (tv.z == PPR_CLEAR_VALUE || any(tv.xy < l.rect_min) || any(tv.xy >= l.rect_max)) {
        return;
    }
    if (DEPTH_OCCLUSION && occluded_at(tv.xy, s.normal, s.plane_dist)) {
        return;
    }
    let local = tv.xy - l.rect_min;
    atomicMin(&atlas[l.offset + local.x + local.y * (l.rect_max.x - l.rect_min.x)], tv.z);
}

// The rounding margin of path_blocked per metre (PATH_MARGIN of path_blockers.rs).
const PATH_MARGIN: f32 = 4e-6;
const NO_BLOCKER: u32 = 0xffffffffu;

// PATH_BLOCKERS: whether the path from the pixel's position `p` (at `dist` in front of
// `plane`) down to its reflection point (`mirrored` its mirror image) crosses the
// rectangle of the shape's blocker `b`, a parallel reflector in front of the plane,
// strictly inside: the mirror cannot show `p` there (crates/ppr-runtime/src/
// path_blockers.rs, whose path_blocked is this test on the CPU).
fn path_blocked(p: vec3<f32>, mirrored: vec3<f32>, dist: f32, plane: vec4<f32>, b: u32) -> bool {
    let s = shapes[b];
    let rise = s.plane_dist + plane.w;
    let margin = PATH_MARGIN * (length(p) + dist);
    if (!(rise > margin && rise < dist - margin)) {
        return false;
    }
    let hit = mirrored * (-plane.w / dot(mirrored, plane.xyz));
    let x = hit + (p - hit) * (rise / dist);
    let lu = dot(x, s.axis_u) - s.center_u;
    let lv = dot(x, s.axis_v) - s.center_v;
    return abs(lu) < s.half_u - margin && abs(lv) < s.half_v - margin;
}

// Occluder tests and the write, for a shape (index `shape`, path blocker `blocker`) that
// passed its test. `plane` is its test's plane (`ShapeTest.plane`: the shape's normal and
// minus its plane distance, bit for bit what `shapes` holds), so that the write needs no
// load of the shape.
fn reflect_pixel(pixel: vec2<u32>, p: vec3<f32>, dist: f32, plane: vec4<f32>, shape: u32, blocker: u32) -> bool {
    let n = plane.xyz;
    let mirrored = p - 2.0 * dist * n;
    if ((shape & GROUP_TEST_FLAG) != 0u) {
        // A merged plane group (never with occluder lists): does the reflection point lie
        // on a member, not just in the group's bounding rectangle?
        let hit = mirrored * (-plane.w / dot(mirrored, n));
        let r = group_member(shape & ~GROUP_TEST_FLAG, hit);
        if (r == NO_SHAPE) {
            return false;
        }
        // Its member's own path blocker.
        let b = plane_groups[r + 7u];
        if (PATH_BLOCKERS && b != NO_BLOCKER && path_blocked(p, mirrored, dist, plane, b)) {
            return false;
        }
    } else if (OCCLUDER_TESTS) {
        let s = shapes[shape];
        let hit = mirrored * (s.plane_dist / dot(mirrored, s.normal));
        if (is_occluded(hit, s)) {
            return false;
        }
    }
    if (PATH_BLOCKERS && blocker != NO_BLOCKER && path_blocked(p, mirrored, dist, plane, blocker)) {
        return false;
    }
    return write_projection(pixel, mirrored, n, -plane.w);
}

// The four pixels of a thread (one per 16x16 quarter of the block), as vectors: pixel j
// is lane j of each. Invalid pixels (no rendered surface) have tolerance 0.
struct Quad {
    x: vec4<f32>,
    y: vec4<f32>,
    z: vec4<f32>,
    // On-plane tolerance (ppr_on_plane_tolerance): points closer to a plane than this are
    // taken as lying on it; 0 for an invalid pixel.
    tolerance: vec4<f32>,
}

// Lane `j` of a vector, by selects: no dynamic indexing, which would put the vector in
// local memory on some GPUs.
fn lane_f32(v: vec4<f32>, j: u32) -> f32 {
    return select(select(v.x, v.y, j == 1u), select(v.z, v.w, j == 3u), j > 1u);
}

fn lane_u32(v: vec4<u32>, j: u32) -> u32 {
    return select(select(v.x, v.y, j == 1u), select(v.z, v.w, j == 3u), j > 1u);
}

// The mask of lane `j`.
fn lane_mask(j: u32) -> vec4<bool> {
    return vec4<u32>(0u, 1u, 2u, 3u) == vec4<u32>(j);
}

fn quad_position(q: Quad, j: u32) -> vec3<f32> {
    return vec3<f32>(lane_f32(q.x, j), lane_f32(q.y, j), lane_f32(q.z, j));
}

// The four depth loads go out before any of them is used.
fn load_quad(base: vec2<u32>) -> Quad {
    let a = tile_pixel_position(quad_pixel(base, 0u));
    let b = tile_pixel_position(quad_pixel(base, 1u));
    let c = tile_pixel_position(quad_pixel(base, 2u));
    let d = tile_pixel_position(quad_pixel(base, 3u));
    return Quad(
        vec4<f32>(a.x, b.x, c.x, d.x),
        vec4<f32>(a.y, b.y, c.y, d.y),
        vec4<f32>(a.z, b.z, c.z, d.z),
        vec4<f32>(a.w, b.w, c.w, d.w),
    );
}

fn quad_plane(q: Quad, pl: vec4<f32>) -> vec4<f32> {
    return q.x * pl.x + q.y * pl.y + q.z * pl.z + pl.w;
}

// Each pixel's distance from the shape's plane where the shape reflects it into its
// rectangle (in front of the plane by more than the tolerance, inside the pyramid), else -1.
// `inside_block`: the block's box lies inside the pyramid (its list entry says so,
// INSIDE_ENTRY), so the sides pass for every pixel and only the plane is tested.
fn quad_test(q: Quad, t: ShapeTest, inside_block: bool) -> vec4<f32> {
    let dist = quad_plane(q, t.plane);
    let front = q.tolerance > vec4<f32>(0.0) & dist > q.tolerance;
    if (inside_block) {
        return select(vec4<f32>(-1.0), dist, front);
    }
    // The pyramid's sides only for a thread with some pixel in front of the plane: per
    // axis, the form within the bound (inside_pyramid, four pixels at once).
    if (!any(front)) {
        return vec4<f32>(-1.0);
    }
    let inside_u = abs(quad_plane(q, t.across_u)) <= t.extent.x * dist + t.extent.y;
    let inside_v = abs(quad_plane(q, t.across_v)) <= t.extent.z * dist + t.extent.w;
    return select(vec4<f32>(-1.0), dist, front & inside_u & inside_v);
}

// The reflection of one pixel (position `p`, `dist` in front of the layer's plane, inside
// its pyramid) into layer `layer`'s atlas region.
fn layer_pixel(pixel: vec2<u32>, p: vec3<f32>, dist: f32, layer: Layer) {
    let s = shapes[layer.shape];
    let mirrored = p - 2.0 * dist * s.normal;
    if (OCCLUDER_TESTS) {
        let hit = mirrored * (s.plane_dist / dot(mirrored, s.normal));
        if (is_occluded(hit, s)) {
            return;
        }
    }
    write_layer(pixel, mirrored, layer, s);
}

// The shapes a block considers: `count` positions in `visible`, listed in `super_lists`
// from `start` (`listed`) or all of them.
struct Candidates {
    count: u32,
    start: u32,
    listed: bool,
}

fn block_candidates(wid: vec3<u32>) -> Candidates {
    var c = Candidates(frame.tested_count, 0u, false);
    if (SUPER_TILES) {
        let grid = super_tile_grid();
        let per = SUPER_TILE_SIZE / BLOCK_SIZE;
        let st = wid.x / per + (wid.y / per) * grid.x;
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

// Whether the block [lo, hi) overlaps the source box of the shape at position `k` of
// `visible` (always, without SOURCE_BOXES).
fn block_meets_source_box(k: u32, lo: vec2<u32>, hi: vec2<u32>) -> bool {
    if (!SOURCE_BOXES) {
        return true;
    }
    let b = source_boxes[k];
    return all(b.xy < hi) && all(lo < b.zw);
}

// Where the loop takes its candidates: a block list from `list_start`, or `cand` (a
// super-tile's list or every visible shape).
struct LoopCandidates {
    cand: Candidates,
    use_list: bool,
    list_start: u32,
}

// Position in `visible` of a block-list entry (NO_SHAPE stays NO_SHAPE).
fn entry_position(e: u32) -> u32 {
    return select(e & ~INSIDE_ENTRY, e, e == NO_SHAPE);
}

// The loop's candidate `i`: its position in `visible` (a block list's entries flagged
// INSIDE_ENTRY where the block lies inside the shape's pyramid), NO_SHAPE when the block
// [lo, hi) misses its source box.
fn loop_candidate(c: LoopCandidates, i: u32, lo: vec2<u32>, hi: vec2<u32>) -> u32 {
    if (c.use_list) {
        if (FUSED_LISTS) {
            return fused_list_entry(i);
        }
        return block_lists[c.list_start + i];
    }
    let k = candidate(c.cand, i);
    if (!block_meets_source_box(k, lo, hi)) {
        return NO_SHAPE;
    }
    return k;
}

// Most candidates subgroup culling sorts (a bit each); beyond, the loop visits them all.
const CULL_CAPACITY: u32 = 128u;

// Subgroup culling's bits, per 32 candidates of the loop: `passes`, a bit for each that may
// reflect some pixel of the subgroup (the conservative box test of tile_test.wgsl against
// the box of the subgroup's positions); `inside`, a bit for each of those whose pyramid
// holds the whole box (box_inside_sides, as a block list's INSIDE_ENTRY: the subgroup's
// pixels then test its plane only).
struct CullMasks {
    passes: vec4<u32>,
    inside: vec4<u32>,
}

// Whether bit `i` is set in `m` (`i` < 128).
fn mask_bit(m: vec4<u32>, i: u32) -> bool {
    return (lane_u32(m, i / 32u) & (1u << (i % 32u))) != 0u;
}

// Call from uniform control flow, `count` <= CULL_CAPACITY.
fn subgroup_cull_masks(q: Quad, c: LoopCandidates, count: u32, lo: vec2<u32>, hi: vec2<u32>) -> CullMasks {
    let valid = q.tolerance > vec4<f32>(0.0);
    let far = vec4<f32>(3.0e38);
    let own_lo = vec3<f32>(
        min4(select(far, q.x, valid)),
        min4(select(far, q.y, valid)),
        min4(select(far, q.z, valid)),
    );
    let own_hi = vec3<f32>(
        max4(select(-far, q.x, valid)),
        max4(select(-far, q.y, valid)),
        max4(select(-far, q.z, valid)),
    );
    let b = subgroup_box(own_lo, own_hi);
    let empty = b.lo.x > b.hi.x;
    let lane = subgroup_lane();
    var masks = CullMasks(vec4<u32>(0u), vec4<u32>(0u));
    for (var w = 0u; w < 4u && w * 32u < count; w++) {
        var m = 0u;
        var m_inside = 0u;
        for (var r = 0u; r < 32u; r += lane.y) {
            let slot = r + lane.x;
            let i = w * 32u + slot;
            var passes = false;
            var inside = false;
            if (!empty && slot < 32u && i < count) {
                let k = entry_position(loop_candidate(c, i, lo, hi));
                if (k != NO_SHAPE) {
                    let t = shape_test(k);
                    passes = box_may_reflect(t, b.lo, b.hi);
                    inside = passes && box_inside_sides(t, b.lo, b.hi);
                }
            }
            m |= subgroup_ballot32(passes) << r;
            m_inside |= subgroup_ballot32(inside) << r;
        }
        masks.passes = select(masks.passes, vec4<u32>(m), lane_mask(w));
        masks.inside = select(masks.inside, vec4<u32>(m_inside), lane_mask(w));
    }
    return masks;
}

fn min4(v: vec4<f32>) -> f32 {
    return min(min(v.x, v.y), min(v.z, v.w));
}

fn max4(v: vec4<f32>) -> f32 {
    return max(max(v.x, v.y), max(v.z, v.w));
}

// The first candidate from `i` on whose bit is set in `masks` (`count` when none).
fn next_culled(masks: vec4<u32>, i: u32, count: u32) -> u32 {
    for (var w = i / 32u; w < 4u; w++) {
        var m = lane_u32(masks, w);
        if (w == i / 32u) {
            m &= 0xffffffffu << (i % 32u);
        }
        if (m != 0u) {
            return min(w * 32u + firstTrailingBit(m), count);
        }
    }
    return count;
}

// ABLATION 2 (bench only): whether the pass stops once it has the positions (kept alive
// by a store no real frame makes).
fn stops_after_positions(q: Quad) -> bool {
    if (ABLATION != 2u) {
        return false;
    }
    if (any(q.x == vec4<f32>(1234.5))) {
        atomicStore(&intermediate[0], 0u);
    }
    return true;
}

@compute @workgroup_size(16, 16)
fn main(
    @builtin(local_invocation_id) local: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
) {
    touch_occupancy_pad(lid);
    let fused = TILE_CULLING && FUSED_LISTS;
    // The ablations stop after the lists where the projection builds them.
    if (ABLATION == 1u && !fused) {
        return;
    }
    let lo = wid.xy * BLOCK_SIZE;
    let hi = lo + vec2<u32>(BLOCK_SIZE);
    let base = quad_base(lo, local.xy);
    let q = load_quad(base);
    if (!fused && stops_after_positions(q)) {
        return;
    }

    // In the tiled variant, the candidates are the block's list (positions in `visible`);
    // otherwise, or when the list overflowed, every candidate (the super-tile's list or
    // every visible shape).
    var cand = Candidates(frame.tested_count, 0u, false);
    var count = frame.tested_count;
    var use_list = false;
    var list_start = 0u;
    if (fused) {
        let listed = block_list_in_workgroup(lid, q, wid, lo, hi);
        if (listed <= BLOCK_LIST_CAPACITY) {
            count = listed;
            use_list = true;
        } else {
            cand = block_candidates(wid);
            count = cand.count;
        }
        if (ABLATION == 1u || stops_after_positions(q)) {
            return;
        }
    } else if (TILE_CULLING) {
        let blocks = block_grid();
        let b = wid.x + wid.y * blocks.x;
        let listed = block_lists[b];
        if (listed <= BLOCK_LIST_CAPACITY) {
            count = listed;
            use_list = true;
            list_start = blocks.y + b * BLOCK_LIST_CAPACITY;
        } else {
            cand = block_candidates(wid);
            count = cand.count;
        }
    }

    // Writes wait one step in `pending` (candidate and distance per pixel), so that the
    // write path has one call site: without the parallel rule a step's passes are written
    // at the next step; with it, a group's best when the next group (or the end) comes.
    var pending_k = vec4<u32>(NO_SHAPE);
    var pending_d = vec4<f32>(0.0);
    // Without the parallel rule every lane's pending shape is the same one: its plane and
    // index, kept from its step.
    var pending_plane = vec4<f32>(0.0);
    var pending_shape = 0u;
    var pending_blocker = NO_BLOCKER;
    var best_k = vec4<u32>(NO_SHAPE);
    var best_d = vec4<f32>(0.0);
    var written = vec4<u32>(0u);
    var tested = vec4<f32>(0.0);
    var group = NO_SHAPE;
    let loop_cand = LoopCandidates(cand, use_list, list_start);
    let culled = SUBGROUP_CULL && count <= CULL_CAPACITY;
    var masks = CullMasks(vec4<u32>(0u), vec4<u32>(0u));
    if (culled) {
        masks = subgroup_cull_masks(q, loop_cand, count, lo, hi);
    }
    for (var i = 0u; i <= count; i++) {
        if (culled && i < count) {
            i = next_culled(masks.passes, i, count);
        }
        var k = NO_SHAPE;
        var inside_block = false;
        if (i < count) {
            let e = loop_candidate(loop_cand, i, lo, hi);
            // Only block lists flag entries: compiled out without tile culling (the
            // untiled loop ran 0.005 ms slower on the H200 with the test in it).
            let listed = TILE_CULLING && use_list;
            inside_block = listed && e != NO_SHAPE && (e & INSIDE_ENTRY) != 0u;
            // Subgroup culling flags them for the subgroup's own (smaller) box: compiled
            // out without it.
            inside_block = inside_block || (culled && mask_bit(masks.inside, i));
            k = select(e, entry_position(e), listed);
        }
        // Loaded unconditionally (the sentinel step reads entry 0): a conditional load
        // into a variable may cost a trip through local memory.
        let t = shape_test(select(k, 0u, k == NO_SHAPE));
        if (PARALLEL_RULE && (i == count || (k != NO_SHAPE && t.group != group))) {
            pending_k = best_k;
            pending_d = best_d;
            best_k = vec4<u32>(NO_SHAPE);
            group = t.group;
        }
        if (any(pending_k != vec4<u32>(NO_SHAPE))) {
            for (var j = 0u; j < 4u; j++) {
                let pk = lane_u32(pending_k, j);
                if (pk != NO_SHAPE) {
                    var plane = pending_plane;
                    var shape = pending_shape;
                    var blocker = pending_blocker;
                    if (PARALLEL_RULE) {
                        let pt = shape_test(pk);
                        plane = pt.plane;
                        shape = pt.shape;
                        blocker = pt.blocker;
                    }
                    let pixel = quad_pixel(base, j);
                    if (reflect_pixel(pixel, quad_position(q, j), lane_f32(pending_d, j), plane, shape, blocker)) {
                        written = select(written, written | vec4<u32>(1u << (pk & 31u)), lane_mask(j));
                    }
                }
            }
            pending_k = vec4<u32>(NO_SHAPE);
        }
        if (k == NO_SHAPE) {
            continue;
        }
        let dist = quad_test(q, t, inside_block);
        if (PARALLEL_TREES && (t.shape & TREE_TEST_FLAG) != 0u) {
            // In front of the family's lowest plane: walk its tree.
            for (var j = 0u; any(dist >= vec4<f32>(0.0)) && j < 4u; j++) {
                if (lane_f32(dist, j) >= 0.0) {
                    tree_pixel(t.shape & ~TREE_TEST_FLAG, quad_pixel(base, j), quad_position(q, j), lane_f32(q.tolerance, j));
                }
            }
            continue;
        }
        let passes = dist >= vec4<f32>(0.0);
        if (ABLATION == 3u) {
            tested += dist;
        } else if (PARALLEL_RULE) {
            let better = passes & (best_k == vec4<u32>(NO_SHAPE) | dist < best_d);
            best_k = select(best_k, vec4<u32>(k), better);
            best_d = select(best_d, dist, better);
        } else {
            pending_k = select(vec4<u32>(NO_SHAPE), vec4<u32>(k), passes);
            pending_d = dist;
            pending_plane = t.plane;
            pending_shape = t.shape;
            pending_blocker = select(NO_BLOCKER, t.blocker, PATH_BLOCKERS);
        }
    }
    if (ABLATION == 3u && dot(tested, vec4<f32>(1.0)) == 1234.5) {
        atomicStore(&intermediate[0], 0u);
    }
    // Layer reflectors (few): their tests follow the visible shapes'. With fused lists the
    // block's box was tested against each layer's pyramid with the list (fused_layer_entry:
    // skip, test, or its plane only); else the block's source box decides.
    for (var l = 0u; LAYERS && l < frame.layer_count; l++) {
        let k = frame.tested_count + l;
        var inside = false;
        if (fused && l < FUSED_LAYER_CAPACITY) {
            let e = fused_layer_entry(l);
            if (e == 0u) {
                continue;
            }
            inside = e == 2u;
        } else if (!block_meets_source_box(k, lo, hi)) {
            continue;
        }
        let dist = quad_test(q, shape_test(k), inside);
        for (var j = 0u; any(dist >= vec4<f32>(0.0)) && j < 4u; j++) {
            let d = lane_f32(dist, j);
            if (d >= 0.0) {
                layer_pixel(quad_pixel(base, j), quad_position(q, j), d, layers[l]);
            }
        }
    }
    if (DEBUG_WRITES) {
        var n = select(0xffffffffu, count, use_list);
        if (culled) {
            // With subgroup culling: the candidates the pixel's subgroup visits.
            n = dot(countOneBits(masks.passes), vec4<u32>(1u));
        }
        for (var j = 0u; j < 4u; j++) {
            let pixel = quad_pixel(base, j);
            if (all(pixel < frame.size)) {
                let index = pixel.x + pixel.y * frame.size.x;
                if (DEBUG_TILE_LISTS) {
                    debug_writes[index] = n;
                } else if (lane_f32(q.tolerance, j) > 0.0) {
                    debug_writes[index] = lane_u32(written, j);
                }
            }
        }
    }
}
