// Tile culling shared by the projection pass (16x16 tiles) and the super-tile list pass
// (64x64 super-tiles): the conservative test of a box of camera-relative positions
// against a shape, the box built from the pixels' positions, and the ordered compaction
// that turns per-thread pass flags into a list. Needs `frame`, `depth_tex` and the view
// module; uses the workgroup arrays below.

const TILE_GROUP_THREADS: u32 = 256u;
// Edge of a super-tile in pixels (4x4 projection tiles).
const SUPER_TILE_SIZE: u32 = 64u;
// Capacity of a super-tile's list; a super-tile with more candidates lists nothing and its
// tiles test every visible shape.
const SUPER_LIST_CAPACITY: u32 = 1024u;

// The box of a tile's pixel positions (ordered float bits per axis).
var<workgroup> tile_box_min: array<atomic<u32>, 3>;
var<workgroup> tile_box_max: array<atomic<u32>, 3>;
// Per thread of a chunk: whether its shape passed; packed into words for the ranks.
var<workgroup> pass_flags: array<u32, TILE_GROUP_THREADS>;
var<workgroup> pass_words: array<u32, 8>;

// The camera-relative position of a pixel, when its depth is a rendered surface and the
// position is finite (w = 1), else w = 0. The one rule both culling levels and the
// per-pixel projection use, so that a tile's box holds every position its pixels test.
fn tile_pixel_position(pixel: vec2<u32>) -> vec4<f32> {
    if (!all(pixel < frame.size)) {
        return vec4<f32>(0.0);
    }
    let depth = textureLoad(depth_tex, vec2<i32>(pixel), 0).r;
    if (!ppr_is_valid_depth(depth)) {
        return vec4<f32>(0.0);
    }
    let p = ppr_unproject(vec2<f32>(pixel) + 0.5, depth);
    if (!(ppr_is_finite2(p.xy) && ppr_is_finite(p.z) && all(abs(p) < vec3<f32>(1e30)))) {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(p, 1.0);
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
// thread without any). Every thread gets the box; `lo.x > hi.x` when it is empty.
struct TileBox {
    lo: vec3<f32>,
    hi: vec3<f32>,
}

fn workgroup_box(lid: u32, lo: vec3<f32>, hi: vec3<f32>) -> TileBox {
    if (lid < 3u) {
        atomicStore(&tile_box_min[lid], 0xffffffffu);
        atomicStore(&tile_box_max[lid], 0u);
    }
    workgroupBarrier();
    if (lo.x <= hi.x) {
        for (var c = 0u; c < 3u; c++) {
            atomicMin(&tile_box_min[c], ordered_bits(lo[c]));
            atomicMax(&tile_box_max[c], ordered_bits(hi[c]));
        }
    }
    workgroupBarrier();
    var b = TileBox(vec3<f32>(0.0), vec3<f32>(0.0));
    for (var c = 0u; c < 3u; c++) {
        b.lo[c] = from_ordered_bits(atomicLoad(&tile_box_min[c]));
        b.hi[c] = from_ordered_bits(atomicLoad(&tile_box_max[c]));
    }
    if (atomicLoad(&tile_box_min[0]) > atomicLoad(&tile_box_max[0])) {
        b.lo.x = 1.0;
        b.hi.x = -1.0;
    }
    return b;
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
// Monotone in the box: a box holding another passes whenever the smaller one does (its
// front part holds the smaller one's, and the margin only grows), so a super-tile's list
// holds every shape the lists of its tiles would.
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
    // Margin for the f32 error of per-pixel positions against the box's; the reach is
    // that of the box's farthest corner (monotone in the box).
    let reach = length(max(abs(lo), abs(hi)));
    let margin = 1e-4 * reach + 1e-6 * max(s.half_u, s.half_v);
    let half = vec2<f32>(s.half_u, s.half_v) + margin;
    return all(b.hi >= -half) && all(b.lo <= half);
}

// Ordered compaction of one chunk of TILE_GROUP_THREADS candidates: (rank, total), where
// rank is the number of passing threads before this one and total the chunk's passing
// count. Eight threads pack the flags into words; the ranks are popcounts. Call from
// uniform control flow (it has barriers).
fn chunk_rank(lid: u32, passes: bool) -> vec2<u32> {
    pass_flags[lid] = select(0u, 1u, passes);
    workgroupBarrier();
    if (lid < 8u) {
        var bits = 0u;
        for (var t = 0u; t < 32u; t++) {
            bits |= pass_flags[lid * 32u + t] << t;
        }
        pass_words[lid] = bits;
    }
    workgroupBarrier();
    let word = lid / 32u;
    var rank = countOneBits(pass_words[word] & ((1u << (lid % 32u)) - 1u));
    var total = 0u;
    for (var w = 0u; w < 8u; w++) {
        let n = countOneBits(pass_words[w]);
        total += n;
        if (w < word) {
            rank += n;
        }
    }
    workgroupBarrier();
    return vec2<u32>(rank, total);
}

// Super-tiles of the viewport: (columns, count).
fn super_tile_grid() -> vec2<u32> {
    let cols = (frame.size.x + SUPER_TILE_SIZE - 1u) / SUPER_TILE_SIZE;
    let rows = (frame.size.y + SUPER_TILE_SIZE - 1u) / SUPER_TILE_SIZE;
    return vec2<u32>(cols, cols * rows);
}
