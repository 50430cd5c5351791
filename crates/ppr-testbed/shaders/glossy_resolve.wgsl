// Exact glossy reference, resolve (testbed): colour = Σ w L / Σ w on the pixels that
// glossy_accumulate.wgsl accumulated (Σ w > 0); other pixels keep the mirror reference.

struct Accum {
    sum: vec4<f32>,      // rgb: Σ w L, a: Σ w
    moments: vec4<f32>,  // x: Σ w², y: views with w > 0
}

@group(0) @binding(0) var<storage, read> resolved: array<Accum>;
@group(0) @binding(1) var resolve_ids: texture_2d<u32>;

// `vs_main`: the full-screen triangle of ppr-scene-gpu's fullscreen_triangle.wgsl.

@fragment
fn fs_resolve(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let size = textureDimensions(resolve_ids);
    let p = vec2<u32>(frag.xy);
    let a = resolved[p.y * size.x + p.x];
    if (!(a.sum.a > 0.0)) {
        discard;
    }
    return vec4<f32>(a.sum.rgb / a.sum.a, 1.0);
}
