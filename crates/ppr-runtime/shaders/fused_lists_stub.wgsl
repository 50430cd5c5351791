// The functions of fused_lists.wgsl for the projection's module without fused lists
// (FUSED_LISTS is false there, so neither is called): no workgroup memory.

fn fused_list_entry(i: u32) -> u32 {
    return NO_SHAPE;
}

// As fused_lists.wgsl's (never read here).
const FUSED_LAYER_CAPACITY: u32 = 64u;

fn fused_layer_entry(l: u32) -> u32 {
    return 1u;
}

fn block_list_in_workgroup(lid: u32, q: Quad, wid: vec3<u32>, lo: vec2<u32>, hi: vec2<u32>) -> u32 {
    return BLOCK_LIST_CAPACITY + 1u;
}
