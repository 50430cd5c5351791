// G-buffer raster of a level (testbed): linear HDR colour, world normal and reflector id.
//
// Positions are camera-relative (see scene_raster.wgsl).
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

@group(0) @binding(0) var<uniform> view: View;
@group(0) @binding(1) var<storage, read> shapes: array<Shape>;

// Material (group 1: params = roughness, metallic, transmission, textured), Draw (group 2:
// params.x = 1 for a reflective surface), `vs_main`, `surface_normal`, `base_colour` and
// `lit_colour` are in ppr-scene-gpu's scene_raster.wgsl, put in front of this file.

struct GBufferOut {
    @location(0) color: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @location(2) reflector: u32,
}

// 0 = not on a reflector; i + 1 = on shape i (the first that matches).
fn reflector_at(rel: vec3<f32>, n: vec3<f32>) -> u32 {
    let count = view.mask.x;
    if (count == 0u || (view.mask.y == 1u && draw.params.x == 0u)) {
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
    let n = surface_normal(in, front);
    let base = base_colour(in.uv);
    var out: GBufferOut;
    out.color = vec4<f32>(lit_colour(base.rgb, n), 1.0);
    out.normal = vec4<f32>(n, 1.0);
    out.reflector = reflector_at(in.rel, n);
    return out;
}
