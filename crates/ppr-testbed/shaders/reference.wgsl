// Exact-reference resolve (testbed): for the main-view pixels on reflectors of one plane,
// copy the colour of the mirrored view rendered for that plane, reconstruct the reflected
// point and classify it: visible in the main view (on screen) or not.
//
// Outputs: the reflected colour (Rgba16Float, alpha 1) and the reflected point (Rgba32Uint:
// xyz = bits of the f32 camera-relative position, w = class). Integer targets are
// renderable everywhere, 32-bit float ones are not (GL without EXT_color_buffer_float).
// Class: 0 = not a reflector pixel (never written here), 1 = reflected point on screen,
// 2 = reflected point off screen or hidden, 3 = reflects the background.

struct Resolve {
    rel_from_mirror_clip: mat4x4<f32>,  // mirrored clip -> real camera-relative position
    main_clip_from_rel: mat4x4<f32>,
    rel_from_main_clip: mat4x4<f32>,
    size: vec4<f32>,                    // width, height, 1/width, 1/height
    plane: vec4<u32>,                   // x: plane index resolved by this pass
    depth: vec4<f32>,                   // x: far depth (cleared value), y: plane tolerance (m),
                                        // z: plane tolerance per metre, w: distance tolerance per metre
    normals: vec4<f32>,                 // x: smallest cosine between the two surfaces' normals
}

@group(0) @binding(0) var<uniform> u: Resolve;
@group(0) @binding(1) var<storage, read> plane_of_reflector: array<u32>;
@group(0) @binding(2) var main_ids: texture_2d<u32>;
@group(0) @binding(3) var main_depth: texture_2d<f32>;  // Depth32Float bound as unfilterable float (GL has no textureLoad on depth)
@group(0) @binding(4) var main_normal: texture_2d<f32>;
@group(0) @binding(5) var mirror_color: texture_2d<f32>;
@group(0) @binding(6) var mirror_depth: texture_2d<f32>;
@group(0) @binding(7) var mirror_normal: texture_2d<f32>;

// `vs_main`: the full-screen triangle of ppr-scene-gpu's fullscreen_triangle.wgsl.

struct ResolveOut {
    @location(0) color: vec4<f32>,
    @location(1) point: vec4<u32>,
}

fn ndc_of(pixel_center: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(pixel_center.x * u.size.z * 2.0 - 1.0, 1.0 - pixel_center.y * u.size.w * 2.0);
}

fn unproject(m: mat4x4<f32>, ndc: vec2<f32>, depth: f32) -> vec3<f32> {
    let h = m * vec4<f32>(ndc, depth, 1.0);
    return h.xyz / h.w;
}

// Whether the camera-relative point x, on a surface of normal nx, is what the main view
// shows (within tolerance): same surface plane, nearby, same facing.
fn on_screen(x: vec3<f32>, nx: vec3<f32>) -> bool {
    let c = u.main_clip_from_rel * vec4<f32>(x, 1.0);
    if (c.w <= 0.0) {
        return false;
    }
    let ndc = c.xy / c.w;
    let q = vec2<f32>((ndc.x + 1.0) * 0.5 * u.size.x, (1.0 - ndc.y) * 0.5 * u.size.y);
    if (q.x < 0.0 || q.y < 0.0 || q.x >= u.size.x || q.y >= u.size.y) {
        return false;
    }
    let qp = vec2<i32>(floor(q));
    let d = textureLoad(main_depth, qp, 0).x;
    if (d == u.depth.x) {
        return false;
    }
    let p = unproject(u.rel_from_main_clip, ndc_of(vec2<f32>(qp) + 0.5), d);
    let n = textureLoad(main_normal, qp, 0).xyz;
    let dist = length(x);
    let off_plane = abs(dot(x - p, n));
    return off_plane <= u.depth.y + u.depth.z * dist
        && length(x - p) <= u.depth.y + u.depth.w * dist
        && dot(n, nx) >= u.normals.x;
}

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> ResolveOut {
    let px = vec2<i32>(frag.xy);
    let id = textureLoad(main_ids, px, 0).x;
    if (id == 0u) {
        discard;
    }
    if (plane_of_reflector[id - 1u] != u.plane.x) {
        discard;
    }
    var out: ResolveOut;
    out.color = vec4<f32>(textureLoad(mirror_color, px, 0).rgb, 1.0);
    let md = textureLoad(mirror_depth, px, 0).x;
    if (md == u.depth.x) {
        out.point = vec4<u32>(0u, 0u, 0u, 3u);
        return out;
    }
    let x = unproject(u.rel_from_mirror_clip, ndc_of(frag.xy), md);
    let nx = textureLoad(mirror_normal, px, 0).xyz;
    out.point = vec4<u32>(bitcast<vec3<u32>>(x), select(2u, 1u, on_screen(x, nx)));
    return out;
}
