// Composite (testbed): scene colour mixed with a reflection over reflector pixels.
// out = mix(scene, reflection.rgb, reflectivity * saturate(reflection.a)) where the
// reflector id is non-zero; the reflection's alpha is how much to trust it (PPR: a
// confidence in [0, 1]; the baselines: 0 or 1), the scene colour the fallback.

struct Composite {
    params: vec4<f32>,  // x: reflectivity in [0, 1]
}

@group(0) @binding(0) var<uniform> u: Composite;
@group(0) @binding(1) var scene_color: texture_2d<f32>;
@group(0) @binding(2) var reflection: texture_2d<f32>;
@group(0) @binding(3) var reflector_id: texture_2d<u32>;

// `vs_main`: the full-screen triangle of ppr-scene-gpu's fullscreen_triangle.wgsl.

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let px = vec2<i32>(frag.xy);
    let scene = textureLoad(scene_color, px, 0);
    if (textureLoad(reflector_id, px, 0).x == 0u) {
        return scene;
    }
    let r = textureLoad(reflection, px, 0);
    let weight = u.params.x * clamp(r.a, 0.0, 1.0);
    return vec4<f32>(mix(scene.rgb, r.rgb, weight), scene.a);
}
