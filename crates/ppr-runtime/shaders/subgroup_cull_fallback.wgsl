// Subgroup culling without subgroup operations (adapters without wgpu::Features::SUBGROUP,
// such as wgpu's GL backend): the functions of subgroup_cull.wgsl for a subgroup of one
// invocation. The projection never enables SUBGROUP_CULL with these by choice (each
// invocation would test every candidate against its own box), but the result is the same:
// the tests use it to check the culling's bookkeeping on any adapter.

fn subgroup_box(lo: vec3<f32>, hi: vec3<f32>) -> TileBox {
    return TileBox(lo, hi);
}

fn subgroup_lane() -> vec2<u32> {
    return vec2<u32>(0u, 1u);
}

fn subgroup_elected(lid: u32) -> bool {
    return true;
}

fn subgroup_ballot32(p: bool) -> u32 {
    return select(0u, 1u, p);
}
