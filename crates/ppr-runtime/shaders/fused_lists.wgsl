// The projection's own block lists (FUSED_LISTS in projection.wgsl): the list in workgroup
// memory and the function that builds it. Only in the projection's fused module (the other
// module takes fused_lists_stub.wgsl: no workgroup memory). Needs tile_test.wgsl and the
// projection's Quad, candidates and shape tests.

// The block's list (positions in `visible`, as block_lists.wgsl's).
var<workgroup> fused_list: array<u32, BLOCK_LIST_CAPACITY>;

fn fused_list_entry(i: u32) -> u32 {
    return fused_list[i];
}

// Layers a block tests at most (MAX_LAYERS in plan.rs).
const FUSED_LAYER_CAPACITY: u32 = 64u;
// Per layer (LAYERS), what the block's box says of its test: 0 the block cannot reflect
// into it (its source box or its pyramid missed), 1 test it, 2 test its plane only (the
// box lies inside its pyramid's sides, as a list entry's INSIDE_ENTRY).
var<workgroup> fused_layers: array<u32, FUSED_LAYER_CAPACITY>;

fn fused_layer_entry(l: u32) -> u32 {
    return fused_layers[l];
}

// FUSED_LISTS: the block's list of candidates, built into `fused_list` from the box of the
// block's positions (`q`, every thread's), exactly as block_lists.wgsl builds it: the
// candidates are the super-tile's list (SUPER_TILES, when it did not overflow) or every
// visible shape, in that order, each kept when the block meets its source box and the box
// test passes. Returns the list's length (over BLOCK_LIST_CAPACITY when it overflowed:
// the entries past it are not kept). Call from uniform control flow.
fn block_list_in_workgroup(lid: u32, q: Quad, wid: vec3<u32>, lo: vec2<u32>, hi: vec2<u32>) -> u32 {
    let c = block_candidates(wid);
    // LIST_PREFETCH: the first chunk's candidate, source-box test and shape test loaded
    // before the box (whose barriers they then overlap), unconditionally (entry 0 where
    // there is none: a conditional load into a variable may cost a trip through local
    // memory).
    var pre_k = 0u;
    var pre_meets = false;
    var pre_t: ShapeTest;
    if (LIST_PREFETCH) {
        let has = lid < c.count;
        pre_k = select(0u, candidate(c, min(lid, max(c.count, 1u) - 1u)), has);
        pre_meets = has && block_meets_source_box(pre_k, lo, hi);
        pre_t = shape_test(pre_k);
    }
    var own = TileBox(vec3<f32>(3.0e38), vec3<f32>(-3.0e38));
    for (var j = 0u; j < 4u; j++) {
        if (lane_f32(q.tolerance, j) > 0.0) {
            let p = quad_position(q, j);
            own = TileBox(min(own.lo, p), max(own.hi, p));
        }
    }
    var box: TileBox;
    if (SUBGROUP_BOX == 2u) {
        box = box_by_subgroup_slots(lid, own);
    } else {
        // SUBGROUP_BOX 1: each subgroup's box first, then one invocation a subgroup takes
        // part in the workgroup's atomics (8 sets of atomics on a 32-wide device instead of
        // 256). Without subgroup operations the subgroups are of one invocation: the same
        // box.
        var part = own;
        var takes_part = true;
        if (SUBGROUP_BOX == 1u) {
            part = subgroup_box(own.lo, own.hi);
            takes_part = subgroup_elected(lid);
        }
        box = workgroup_box_of(lid, part.lo, part.hi, takes_part);
    }
    let empty = box.lo.x > box.hi.x;
    var written = 0u;
    for (var first = 0u; first < c.count; first += TILE_GROUP_THREADS) {
        let i = first + lid;
        var entry = 0u;
        var passes = false;
        if (!empty && i < c.count) {
            let prefetched = LIST_PREFETCH && first == 0u;
            var k = pre_k;
            var meets = pre_meets;
            if (!prefetched) {
                k = candidate(c, i);
                meets = block_meets_source_box(k, lo, hi);
            }
            if (meets) {
                var t = pre_t;
                if (!prefetched) {
                    t = shape_test(k);
                }
                passes = box_may_reflect(t, box.lo, box.hi);
                // The inside test only for the entries that are listed.
                if (passes) {
                    entry = list_entry(k, t, box.lo, box.hi);
                }
            }
        }
        let r = chunk_rank(lid, first / TILE_GROUP_THREADS, passes);
        if (passes && written + r.x < BLOCK_LIST_CAPACITY) {
            fused_list[written + r.x] = entry;
        }
        written += r.y;
    }
    // The layers' tests (after the visible shapes'), one invocation each, against the same
    // box: a layer's test then runs only in the blocks that may reflect into it, as a
    // listed shape's (the layer loop tested every block its source box met).
    if (LAYERS && lid < min(frame.layer_count, FUSED_LAYER_CAPACITY)) {
        let k = frame.tested_count + lid;
        var e = 0u;
        if (!empty && block_meets_source_box(k, lo, hi)) {
            let t = shape_test(k);
            if (box_may_reflect(t, box.lo, box.hi)) {
                e = select(1u, 2u, box_inside_sides(t, box.lo, box.hi));
            }
        }
        fused_layers[lid] = e;
    }
    // The list (and the layers' entries) complete before any thread reads them.
    workgroupBarrier();
    return written;
}

// SUBGROUP_BOX 2: the box of the workgroup's positions (as workgroup_box_of) with one barrier
// and no atomics. Each subgroup's first invocation stores the subgroup's box in the
// subgroup's slot of six words at the start of `fused_list` (free until the list is
// built: every thread has read the slots before the first chunk's ranks, whose barriers
// come before any entry is written); then every subgroup reduces all the slots itself.
// Min and max of floats give the atomics' box of ordered bits (only a zero's sign may
// differ, which no plane test sees). Needs subgroups of consecutive local indices (as on
// every Vulkan driver we know) at least 8 wide, so that the slots fit in the list: the
// renderer picks it only on such adapters (wgpu::AdapterInfo::subgroup_min_size). Also
// zeroes the first chunk's pass bits, as workgroup_box_of does. Call from uniform control
// flow.
fn box_by_subgroup_slots(lid: u32, own: TileBox) -> TileBox {
    let part = subgroup_box(own.lo, own.hi);
    let lane = subgroup_lane();
    if (lane.x == 0u) {
        let s = 6u * (lid / lane.y);
        fused_list[s] = bitcast<u32>(part.lo.x);
        fused_list[s + 1u] = bitcast<u32>(part.lo.y);
        fused_list[s + 2u] = bitcast<u32>(part.lo.z);
        fused_list[s + 3u] = bitcast<u32>(part.hi.x);
        fused_list[s + 4u] = bitcast<u32>(part.hi.y);
        fused_list[s + 5u] = bitcast<u32>(part.hi.z);
    }
    if (lid < PASS_WORDS) {
        atomicStore(&pass_bits[0][lid], 0u);
    }
    workgroupBarrier();
    var lo = vec3<f32>(3.0e38);
    var hi = vec3<f32>(-3.0e38);
    for (var s = lane.x; s < TILE_GROUP_THREADS / lane.y; s += lane.y) {
        let w = 6u * s;
        lo = min(lo, bitcast<vec3<f32>>(vec3<u32>(fused_list[w], fused_list[w + 1u], fused_list[w + 2u])));
        hi = max(hi, bitcast<vec3<f32>>(vec3<u32>(fused_list[w + 3u], fused_list[w + 4u], fused_list[w + 5u])));
    }
    let b = subgroup_box(lo, hi);
    if (b.lo.x <= b.hi.x) {
        return b;
    }
    return TileBox(vec3<f32>(1.0), vec3<f32>(-1.0));
}
