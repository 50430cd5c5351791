// Forward pass of the walkthrough (a game's own renderer, not the testbed's): lit linear
// HDR colour, the reflection weight the composite pass uses, and depth.
//
// Positions are camera-relative: each draw's model matrix already has the camera position
// subtracted (in f64 on the CPU), so nothing here sees large coordinates.
// Lighting: one directional light plus ambient, no shadows (the testbed's, so headless
// frames can be compared with its frames).

struct View {
    clip_from_rel: mat4x4<f32>,
    light: vec4<f32>,    // xyz: unit direction towards the light, w: intensity
    ambient: vec4<f32>,  // rgb: ambient colour
}

struct Material {
    base_color: vec4<f32>,
    emissive: vec4<f32>,  // w: 1 = unlit
    params: vec4<f32>,    // x: metallic, y: 1 = alpha blended, zw: unused
}

struct Draw {
    model: mat4x4<f32>,          // relative-from-object
    normal_matrix: mat4x4<f32>,  // inverse transpose of the model's upper 3 × 3
    // x: reflectivity of this draw in [0, 1] (0: it takes no reflection), yzw: unused
    params: vec4<f32>,
}

@group(0) @binding(0) var<uniform> view: View;
@group(1) @binding(0) var<uniform> material: Material;
@group(1) @binding(1) var base_texture: texture_2d<f32>;
@group(1) @binding(2) var base_sampler: sampler;
@group(2) @binding(0) var<uniform> draw: Draw;

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) rel: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
}

@vertex
fn vs_main(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>, @location(2) uv: vec2<f32>) -> VertexOut {
    var out: VertexOut;
    let rel = draw.model * vec4<f32>(position, 1.0);
    out.clip = view.clip_from_rel * rel;
    out.rel = rel.xyz;
    out.normal = (draw.normal_matrix * vec4<f32>(normal, 0.0)).xyz;
    out.uv = uv;
    return out;
}

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
    var n = normalize(in.normal);
    if (!front) {
        n = -n;
    }
    let base = material.base_color * textureSample(base_texture, base_sampler, in.uv);
    var rgb = base.rgb;
    if (material.emissive.w < 0.5) {
        let lambert = max(dot(n, view.light.xyz), 0.0) * view.light.w;
        rgb = base.rgb * (view.ambient.rgb + vec3<f32>(lambert)) + material.emissive.rgb;
    }
    // Dielectrics reflect 4% head-on, metals their base colour.
    let f0 = mix(0.04, max(base.r, max(base.g, base.b)), material.params.x);
    let to_eye = -normalize(in.rel);
    let weight = draw.params.x * fresnel_schlick(f0, dot(n, to_eye));
    var out: ForwardOut;
    // Alpha: 1 for opaque surfaces; blended ones multiply it by (1 - their alpha) (see the
    // pipeline's blend state), so it ends as the share of the opaque surface still seen.
    out.color = vec4<f32>(rgb, select(1.0, base.a, material.params.y > 0.5));
    out.reflection_weight = vec4<f32>(weight, 0.0, 0.0, base.a);
    return out;
}
