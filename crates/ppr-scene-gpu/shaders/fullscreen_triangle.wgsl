// The vertex shader of the tools' screen passes (composites, resolves, debug views): one
// triangle covering the screen, drawn as `draw(0..3)` without vertex buffers. Put in front
// of a pass's WGSL by `screen_pass.rs`.

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}
