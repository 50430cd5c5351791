// Composite (bevy_ppr): the reflection over the camera's colour by its confidence. The
// pipeline's blend does the mix: out = mix(scene, reflection.rgb, weight) with
// weight = reflectivity * saturate(reflection.a); off reflectors the runtime's alpha is 0.

#import bevy_core_pipeline::fullscreen_vertex_shader::FullscreenVertexOutput

// x: reflectivity in [0, 1]
@group(0) @binding(0) var<uniform> params: vec4<f32>;
@group(0) @binding(1) var reflection: texture_2d<f32>;

@fragment
fn fragment(in: FullscreenVertexOutput) -> @location(0) vec4<f32> {
    let r = textureLoad(reflection, vec2<i32>(in.position.xy), 0);
    return vec4<f32>(r.rgb, params.x * clamp(r.a, 0.0, 1.0));
}
