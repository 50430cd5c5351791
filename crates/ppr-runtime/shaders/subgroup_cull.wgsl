// Subgroup culling, with subgroup operations (the adapter has wgpu::Features::SUBGROUP):
// the box of the positions a subgroup's invocations hold, an invocation's place in its
// subgroup, and a ballot. The projection's SUBGROUP_CULL builds on these
// (subgroup_cull_fallback.wgsl has the same functions without subgroup operations: each
// invocation alone, slower but with the same result). Call from subgroup-uniform control
// flow with every invocation of the subgroup active.

// The box of every invocation's [lo, hi] (lo > hi on an axis for an invocation without
// positions): every invocation gets the subgroup's box.
fn subgroup_box(lo: vec3<f32>, hi: vec3<f32>) -> TileBox {
    return TileBox(subgroupMin(lo), subgroupMax(hi));
}

// (this invocation's index in its subgroup, the subgroup's size).
fn subgroup_lane() -> vec2<u32> {
    return vec2<u32>(subgroupExclusiveAdd(1u), subgroupAdd(1u));
}

// Whether this invocation (local index `lid`) is its subgroup's first active one.
fn subgroup_elected(lid: u32) -> bool {
    return subgroupBroadcastFirst(lid) == lid;
}

// Bit i set when invocation i of the subgroup (i < 32) passes `p`.
fn subgroup_ballot32(p: bool) -> u32 {
    return subgroupBallot(p).x;
}
