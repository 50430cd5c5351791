// The glossy blur's quad exchange with subgroup operations (the adapter has
// wgpu::Features::SUBGROUP): the value of the invocation whose subgroup index differs from
// this one's by `mask` (1 or 2: the other pixel of the quad's row or column, when the
// reflection pass puts 2 x 2 pixels on four consecutive invocations). Call from
// subgroup-uniform control flow with every invocation of the subgroup active.
// glossy_quads_fallback.wgsl has the same functions for a subgroup of one invocation.

fn glossy_quad_xor_i3(v: vec3<i32>, mask: u32) -> vec3<i32> {
    return subgroupShuffleXor(v, mask);
}

fn glossy_quad_xor_f4(v: vec4<f32>, mask: u32) -> vec4<f32> {
    return subgroupShuffleXor(v, mask);
}
