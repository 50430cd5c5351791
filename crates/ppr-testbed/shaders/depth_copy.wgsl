// Depth copy (testbed): writes the bits of a Depth32Float texture into an R32Uint target,
// so depth can be read back where depth-to-buffer copies are missing (GL).

@group(0) @binding(0) var depth: texture_2d<f32>;  // Depth32Float bound as unfilterable float

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) u32 {
    return bitcast<u32>(textureLoad(depth, vec2<i32>(frag.xy), 0).x);
}
