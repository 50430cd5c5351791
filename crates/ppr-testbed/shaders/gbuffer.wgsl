// G-buffer raster of a level (testbed): linear HDR colour, world normal and reflector id.
//
// Positions are camera-relative: the per-draw model matrix already has the camera position
// subtracted (in f64 on the CPU), so nothing here sees large coordinates.
// Also used for the mirrored views of the exact reference (mask disabled there).

struct View {
    clip_from_rel: mat4x4<f32>,
    light: vec4<f32>,      // xyz: direction towards the light, w: intensity
    ambient: vec4<f32>,    // rgb: ambient colour
    mask: vec4<u32>,       // x: shape count (0 = no mask), y: 1 = draw must be reflective
    tolerance: vec4<f32>,  // x: plane distance (m), y: growth per metre, z: min normal cosine
}

struct Shape {
    center: vec4<f32>,  // xyz: camera-relative centre, w: 1 = enabled
    axis_u: vec4<f32>,  // xyz: axis, w: half extent
    axis_v: vec4<f32>,
    normal: vec4<f32>,
}

struct MaterialParams {
    base_color: vec4<f32>,
    emissive: vec4<f32>,  // w: 1 = unlit
    params: vec4<f32>,    // roughness, metallic, transmission, textured
}

struct Draw {
    model: mat4x4<f32>,
    normal_matrix: mat4x4<f32>,
    flags: vec4<u32>,  // x: 1 = reflective surface
}

@group(0) @binding(0) var<uniform> view: View;
@group(0) @binding(1) var<storage, read> shapes: array<Shape>;
@group(1) @binding(0) var<uniform> material: MaterialParams;
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

struct GBufferOut {
    @location(0) color: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @location(2) reflector: u32,
}

// 0 = not on a reflector; i + 1 = on shape i (the first that matches).
fn reflector_at(rel: vec3<f32>, n: vec3<f32>) -> u32 {
    let count = view.mask.x;
    if (count == 0u || (view.mask.y == 1u && draw.flags.x == 0u)) {
        return 0u;
    }
    let tolerance = view.tolerance.x + view.tolerance.y * length(rel);
    for (var i = 0u; i < count; i = i + 1u) {
        let s = shapes[i];
        if (s.center.w < 0.5) {
            continue;
        }
        let d = rel - s.center.xyz;
        if (abs(dot(d, s.normal.xyz)) > tolerance || dot(n, s.normal.xyz) < view.tolerance.z) {
            continue;
        }
        if (abs(dot(d, s.axis_u.xyz)) <= s.axis_u.w + tolerance && abs(dot(d, s.axis_v.xyz)) <= s.axis_v.w + tolerance) {
            return i + 1u;
        }
    }
    return 0u;
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> GBufferOut {
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
    var out: GBufferOut;
    out.color = vec4<f32>(rgb, 1.0);
    out.normal = vec4<f32>(n, 1.0);
    out.reflector = reflector_at(in.rel, n);
    return out;
}
