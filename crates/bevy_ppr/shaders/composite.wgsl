// Composite (bevy_ppr): the reflection blended over the camera's colour by its confidence.
// The blend state does the mix: out = mix(scene, reflection.rgb, weight), with
// weight = reflectivity * saturate(reflection.a). Off reflectors the runtime's alpha is 0.

struct Composite {
    params: vec4<f32>,  // x: reflectivity in [0, 1]
}

@group(0) @binding(0) var<uniform> u: Composite;
@group(0) @binding(1) var reflection: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let r = textureLoad(reflection, vec2<i32>(frag.xy), 0);
    return vec4<f32>(r.rgb, u.params.x * clamp(r.a, 0.0, 1.0));
}
