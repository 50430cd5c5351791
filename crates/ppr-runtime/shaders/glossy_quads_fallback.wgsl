// glossy_quads.wgsl's functions without subgroup operations: each invocation its own quad
// (its own value back, so that no neighbour's pixel matches and nothing is shared). The
// reflection pass runs GLOSSY_SHARED only with glossy_quads.wgsl.

fn glossy_quad_xor_i3(v: vec3<i32>, mask: u32) -> vec3<i32> {
    return v;
}

fn glossy_quad_xor_f4(v: vec4<f32>, mask: u32) -> vec4<f32> {
    return v;
}
