// Depth copy (testbed): writes the bits of a Depth32Float texture into an R32Uint target,
// so depth can be read back where depth-to-buffer copies are missing (GL).

@group(0) @binding(0) var depth: texture_2d<f32>;  // Depth32Float bound as unfilterable float

// `vs_main`: the full-screen triangle of ppr-scene-gpu's fullscreen_triangle.wgsl.

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) u32 {
    return bitcast<u32>(textureLoad(depth, vec2<i32>(frag.xy), 0).x);
}
