// Hidden-shape culling: finds the projection's tests whose reflector no pixel shows, so that
// the projection skips them (many reflectors behind walls: mazes, real levels).
//
// With depth occlusion, a write of the projection lands at a pixel of its reflector's
// screen rectangle, and only where the surface seen there does not lie in front of the
// reflector's plane by more than its on-plane tolerance (projection.wgsl's occluded_at; a
// pixel on a glass layer or without a surface never hides). A test for which every pixel of
// its rectangle, widened by a pixel for rounding, shows a surface in front of its plane
// takes no write at all: skipping it leaves the intermediate buffer the same, bit for bit.
//
// `mark` (one workgroup per 32x32 block, four pixels per thread) sets `seen` for each test
// whose rectangle meets the block and that some pixel of the block does not hide: first
// the box of the block's positions against the test's plane (a block wholly in front of
// it by more than its largest tolerance hides it), then per pixel. `apply` (per test)
// empties the source box of each test left unseen; every reader of source boxes (the
// super-tile and block lists, the projection's loop and its subgroup culling) then skips it.
//
// Layout: `hidden_rects`, per test, its screen rectangle (min.xy, max.xy exclusive), or
// x = KEEP for a test never skipped (a parallel tree: its members' planes differ).

override LAYERS: bool = false;

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var depth_tex: texture_2d<f32>;
@group(0) @binding(2) var<storage, read> shapes: array<Shape>;
@group(0) @binding(3) var<storage, read> tests: array<ShapeTest>;
@group(0) @binding(4) var<storage, read> layers: array<Layer>;
@group(0) @binding(5) var<storage, read> hidden_rects: array<vec4<u32>>;
// Per test: 1 once some pixel may show it (cleared to 0 before `mark`).
@group(0) @binding(6) var<storage, read_write> seen: array<atomic<u32>>;
@group(0) @binding(7) var<storage, read_write> source_boxes: array<vec4<u32>>;

const KEEP: u32 = 0xffffffffu;

// The block's candidates of one chunk that its box does not settle, and which of them
// some pixel shows.
var<workgroup> list: array<u32, TILE_GROUP_THREADS>;
var<workgroup> list_len: atomic<u32>;
var<workgroup> hits: array<atomic<u32>, 8>;
// Whether some pixel of the block never hides (no surface, or glass), and the largest
// on-plane tolerance of the others (positive floats order as their bits).
var<workgroup> block_open: atomic<u32>;
var<workgroup> block_tolerance: atomic<u32>;

// Whether pixel `p` lies in rectangle `r` widened by a pixel on every side.
fn in_rect(r: vec4<u32>, p: vec2<u32>) -> bool {
    return all(p + 1u >= r.xy) && all(p < r.zw + 1u);
}

// Whether the block [lo, hi) meets rectangle `r` widened by a pixel.
fn rect_meets(r: vec4<u32>, lo: vec2<u32>, hi: vec2<u32>) -> bool {
    return all(r.xy < hi + 1u) && all(lo < r.zw + 1u);
}

// Whether the surface at `q` (tolerance in w > 0, not on glass) may let a write of the
// plane `pl` land: it does not lie in front of the plane by more than its tolerance. With a
// margin for the rounding of the projection's own evaluation (conservative: it may only
// call more pixels showing).
fn shows(q: vec4<f32>, pl: vec4<f32>) -> bool {
    let reach = abs(q.x) + abs(q.y) + abs(q.z) + abs(pl.w);
    return dot(q.xyz, pl.xyz) + pl.w <= q.w + 1e-5 * reach;
}

// Whether the whole box of positions lies in front of plane `pl` by more than `tolerance`
// plus `shows`'s margin for any position of the box: then no pixel of the block shows a
// test of that plane.
fn box_hides(pl: vec4<f32>, b: TileBox, tolerance: f32) -> bool {
    let c = 0.5 * (b.lo + b.hi);
    let h = 0.5 * (b.hi - b.lo);
    let reach = dot(abs(c) + h, vec3<f32>(1.0)) + abs(pl.w);
    return -ppr_box_plane_max(-pl, c, h) > tolerance + 1e-5 * reach;
}

// Whether the position `q` lies on a glass panel given a layer this frame (what lies
// behind it is still seen through it).
fn on_glass(q: vec4<f32>) -> bool {
    for (var l = 0u; LAYERS && l < frame.layer_count; l++) {
        if (layers[l].kind == PPR_KIND_TRANSPARENT && ppr_on_shape(q, shapes[layers[l].shape])) {
            return true;
        }
    }
    return false;
}

// A thread's pixel that may hide tests: its position (w = 0 when it hides nothing here:
// outside the viewport, or open, which the block records).
fn hiding_position(p: vec2<u32>) -> vec4<f32> {
    if (!all(p < frame.size)) {
        return vec4<f32>(0.0);
    }
    let q = tile_pixel_position(p);
    if (!(q.w > 0.0) || on_glass(q)) {
        atomicOr(&block_open, 1u);
        return vec4<f32>(0.0);
    }
    atomicMax(&block_tolerance, bitcast<u32>(q.w));
    return q;
}

// Whether pixel `p` at `q` (hiding_position) shows the test with rectangle `r`, plane `pl`.
fn pixel_shows(p: vec2<u32>, q: vec4<f32>, r: vec4<u32>, pl: vec4<f32>) -> bool {
    return q.w > 0.0 && in_rect(r, p) && shows(q, pl);
}

@compute @workgroup_size(16, 16)
fn mark(
    @builtin(local_invocation_id) local: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
) {
    let lo = wid.xy * BLOCK_SIZE;
    let hi = lo + vec2<u32>(BLOCK_SIZE);
    if (lid == 0u) {
        atomicStore(&block_open, 0u);
        atomicStore(&block_tolerance, 0u);
        atomicStore(&list_len, 0u);
    }
    if (lid < 8u) {
        atomicStore(&hits[lid], 0u);
    }
    workgroupBarrier();
    let base = quad_base(lo, local.xy);
    let p0 = quad_pixel(base, 0u);
    let p1 = quad_pixel(base, 1u);
    let p2 = quad_pixel(base, 2u);
    let p3 = quad_pixel(base, 3u);
    let q0 = hiding_position(p0);
    let q1 = hiding_position(p1);
    let q2 = hiding_position(p2);
    let q3 = hiding_position(p3);
    var own = TileBox(vec3<f32>(3.0e38), vec3<f32>(-3.0e38));
    for (var j = 0u; j < 4u; j++) {
        let q = select(select(q0, q1, j == 1u), select(q2, q3, j == 3u), j > 1u);
        if (q.w > 0.0) {
            own = TileBox(min(own.lo, q.xyz), max(own.hi, q.xyz));
        }
    }
    // The box's barriers also publish block_open and block_tolerance.
    let box = workgroup_box(lid, own.lo, own.hi);
    let open = atomicLoad(&block_open) != 0u;
    let tolerance = bitcast<f32>(atomicLoad(&block_tolerance));
    let count = frame.tested_count;
    for (var first = 0u; first < count; first += TILE_GROUP_THREADS) {
        let k = first + lid;
        if (k < count) {
            let r = hidden_rects[k];
            if (r.x != KEEP && rect_meets(r, lo, hi) && atomicLoad(&seen[k]) == 0u) {
                let pl = tests[k].plane;
                if (open) {
                    // A pixel without a surface or on glass never hides (conservative:
                    // the block may show the test anywhere).
                    atomicStore(&seen[k], 1u);
                } else if (!box_hides(pl, box, tolerance)) {
                    list[atomicAdd(&list_len, 1u)] = k;
                }
            }
        }
        workgroupBarrier();
        let n = atomicLoad(&list_len);
        for (var i = 0u; i < n; i++) {
            let t = list[i];
            let r = hidden_rects[t];
            let pl = tests[t].plane;
            if (pixel_shows(p0, q0, r, pl) || pixel_shows(p1, q1, r, pl) || pixel_shows(p2, q2, r, pl)
                || pixel_shows(p3, q3, r, pl)) {
                atomicOr(&hits[i / 32u], 1u << (i % 32u));
            }
        }
        workgroupBarrier();
        if (lid < n && (atomicLoad(&hits[lid / 32u]) & (1u << (lid % 32u))) != 0u) {
            atomicStore(&seen[list[lid]], 1u);
        }
        workgroupBarrier();
        if (lid == 0u) {
            atomicStore(&list_len, 0u);
        }
        if (lid < 8u) {
            atomicStore(&hits[lid], 0u);
        }
        workgroupBarrier();
    }
}

@compute @workgroup_size(64)
fn apply(@builtin(global_invocation_id) gid: vec3<u32>) {
    let k = gid.x;
    if (k < frame.tested_count && hidden_rects[k].x != KEEP && atomicLoad(&seen[k]) == 0u) {
        source_boxes[k] = vec4<u32>(0u);
    }
}
