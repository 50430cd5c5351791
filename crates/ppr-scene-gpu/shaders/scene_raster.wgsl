// Shared by the scene raster passes (the testbed's G-buffer, the walkthrough's forward
// pass), put in front of each pass's own WGSL by `scene_raster.rs`.
//
// Groups 1 and 2 are declared here: what `LevelMeshes` binds. The pass declares group 0,
// `view`, with at least `clip_from_rel: mat4x4<f32>`, `light: vec4<f32>` (xyz: unit
// direction towards the light, w: intensity) and `ambient: vec4<f32>` (rgb).
//
// Positions are camera-relative: each draw's model matrix already has the camera position
// subtracted (in f64 on the CPU), so nothing here sees large coordinates.

struct Material {
    base_color: vec4<f32>,
    emissive: vec4<f32>,  // w: 1 = unlit
    params: vec4<f32>,    // the pass's own (`SurfaceRules::material_params`)
}

struct Draw {
    model: mat4x4<f32>,          // relative-from-object
    normal_matrix: mat4x4<f32>,  // inverse transpose of the model's upper 3 × 3
    params: vec4<u32>,           // the pass's own (`SurfaceRules::draw_params`)
}

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

// The unit normal of the surface, turned around on back faces.
fn surface_normal(in: VertexOut, front: bool) -> vec3<f32> {
    let n = normalize(in.normal);
    return select(-n, n, front);
}

// The material's base colour factor times its texture.
fn base_colour(uv: vec2<f32>) -> vec4<f32> {
    return material.base_color * textureSample(base_texture, base_sampler, uv);
}

// Linear colour of `base` lit by one sun plus ambient (no shadows), plus emission; an
// unlit material shows its base colour.
fn lit_colour(base: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    if (material.emissive.w >= 0.5) {
        return base;
    }
    let lambert = max(dot(n, view.light.xyz), 0.0) * view.light.w;
    return base * (view.ambient.rgb + vec3<f32>(lambert)) + material.emissive.rgb;
}
