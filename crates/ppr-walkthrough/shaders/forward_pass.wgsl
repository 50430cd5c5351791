// Forward pass of the walkthrough (a game's own renderer, not the testbed's): lit linear
// HDR colour, the reflection weight the composite pass uses, and depth.
//
// Positions are camera-relative (see scene_raster.wgsl).
// Lighting: one directional light plus ambient, no shadows (the testbed's, so headless
// frames can be compared with its frames).

struct View {
    clip_from_rel: mat4x4<f32>,
    light: vec4<f32>,    // xyz: unit direction towards the light, w: intensity
    ambient: vec4<f32>,  // rgb: ambient colour
}

@group(0) @binding(0) var<uniform> view: View;

// Material (group 1: params.x = metallic, params.y = 1 when alpha blended), Draw (group 2:
// params.x = the bits of the draw's reflectivity in [0, 1], 0 where it takes no
// reflection), `vs_main`, `surface_normal`, `base_colour` and `lit_colour` are in
// ppr-scene-gpu's scene_raster.wgsl, put in front of this file.

struct ForwardOut {
    @location(0) color: vec4<f32>,
    // How much of the reflection the composite takes here (before the reflection's own
    // validity): the material's reflectivity times a Schlick Fresnel term.
    @location(1) reflection_weight: vec4<f32>,
}

fn fresnel_schlick(f0: f32, cos_theta: f32) -> f32 {
    let m = 1.0 - clamp(cos_theta, 0.0, 1.0);
    return f0 + (1.0 - f0) * m * m * m * m * m;
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> ForwardOut {
    let n = surface_normal(in, front);
    let base = base_colour(in.uv);
    let rgb = lit_colour(base.rgb, n);
    // Dielectrics reflect 4% head-on, metals their base colour.
    let f0 = mix(0.04, max(base.r, max(base.g, base.b)), material.params.x);
    let to_eye = -normalize(in.rel);
    let weight = bitcast<f32>(draw.params.x) * fresnel_schlick(f0, dot(n, to_eye));
    var out: ForwardOut;
    // Alpha: 1 for opaque surfaces; blended ones multiply it by (1 - their alpha) (see the
    // pipeline's blend state), so it ends as the share of the opaque surface still seen.
    out.color = vec4<f32>(rgb, select(1.0, base.a, material.params.y > 0.5));
    out.reflection_weight = vec4<f32>(weight, 0.0, 0.0, base.a);
    return out;
}
