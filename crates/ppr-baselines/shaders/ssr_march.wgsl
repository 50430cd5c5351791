// Ray-marched screen-space reflections (brute force and low quality): per reflector pixel,
// reflect the view ray about the reflector's plane and march it in screen space with
// steps of `stride` pixels along its major axis (perspective-correct depth, McGuire and
// Mara 2014), test each sample's depth footprint against the depth buffer with a
// thickness, then refine a hit by bisection (seeds 003 and 004).
// Needs common.wgsl.

struct SsrParams {
    // Pixels per step along the ray's major screen axis.
    stride: f32,
    // Most steps per ray (0: until the ray leaves the screen).
    max_steps: u32,
    // Bisection steps after a coarse hit.
    refine_steps: u32,
    // Thickness assumed behind each depth sample, metres of view depth.
    thickness: f32,
    // Longest reflection ray, metres.
    max_distance: f32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// Workgroup edge (threads per side); set from Rust.
override GROUP_EDGE: u32 = 8u;
// Alpha of a found reflection: 1 (a technique's output), or the distance from the
// reflector to the hit in metres (ssr-glossy's blur reads it); set from Rust.
override OUTPUT_HIT_DISTANCE: bool = false;

@group(0) @binding(1) var<uniform> params: SsrParams;
@group(0) @binding(2) var<storage, read> planes: array<ReflectorPlane>;
@group(0) @binding(3) var depth_tex: texture_2d<f32>;
@group(0) @binding(4) var reflector_tex: texture_2d<u32>;
@group(0) @binding(5) var color_tex: texture_2d<f32>;
@group(0) @binding(6) var output_tex: texture_storage_2d<rgba16float, write>;

struct MarchSample {
    pixel: vec2<u32>,
    // The ray's linear depth over the sampled pixel's footprint.
    ray_near: f32,
    ray_far: f32,
    // Device and linear depth of the sampled pixel.
    depth: f32,
    scene: f32,
}

// The ray at `t` pixels along its major axis.
fn sample_ray(ray: ScreenRay, t: f32) -> MarchSample {
    var s: MarchSample;
    let dir = (ray.end - ray.start) / ray.length;
    let dk = (ray.k_end - ray.k_start) / ray.length;
    s.pixel = baseline_pixel_at(ray.start + dir * t);
    // Depth of the ray half a pixel before and after the sample (its footprint).
    let k_a = ray.k_start + dk * max(t - 0.5, 0.0);
    let k_b = ray.k_start + dk * min(t + 0.5, ray.length);
    let w_a = 1.0 / k_a;
    let w_b = 1.0 / k_b;
    s.ray_near = min(w_a, w_b);
    s.ray_far = max(w_a, w_b);
    s.depth = textureLoad(depth_tex, s.pixel, 0).x;
    s.scene = baseline_view_depth(s.depth);
    return s;
}

// The ray reaches behind the sampled surface, which is not the source plane.
fn is_behind(s: MarchSample, plane: ReflectorPlane) -> bool {
    return s.ray_far >= s.scene && !baseline_on_plane(plane, s.pixel, s.depth);
}

// ... and not further behind it than the thickness.
fn is_hit(s: MarchSample, plane: ReflectorPlane) -> bool {
    return is_behind(s, plane) && s.ray_near <= s.scene + params.thickness;
}

struct MarchResult {
    found: bool,
    pixel: vec2<u32>,
}

fn march(ray: ScreenRay, plane: ReflectorPlane) -> MarchResult {
    var result: MarchResult;
    result.found = false;
    let stride = max(params.stride, 1.0);
    var steps = u32(ceil(ray.length / stride));
    if (params.max_steps > 0u) {
        steps = min(steps, params.max_steps);
    }
    var t_prev = 0.0;
    for (var i = 1u; i <= steps; i = i + 1u) {
        let t = min(f32(i) * stride, ray.length);
        let s = sample_ray(ray, t);
        if (is_behind(s, plane)) {
            // Bisect (t_prev, t] for the first sample behind the surface.
            var lo = t_prev;
            var hi = t;
            var best = s;
            for (var j = 0u; j < params.refine_steps && hi - lo > 0.5; j = j + 1u) {
                let mid = 0.5 * (lo + hi);
                let m = sample_ray(ray, mid);
                if (is_behind(m, plane)) {
                    hi = mid;
                    best = m;
                } else {
                    lo = mid;
                }
            }
            if (is_hit(best, plane)) {
                result.found = true;
                result.pixel = best.pixel;
                return result;
            }
        }
        t_prev = t;
    }
    return result;
}

@compute @workgroup_size(GROUP_EDGE, GROUP_EDGE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let pixel = gid.xy;
    if (any(pixel >= frame.size)) {
        return;
    }
    var out = vec4<f32>(0.0);
    let id = textureLoad(reflector_tex, pixel, 0).x;
    let d = textureLoad(depth_tex, pixel, 0).x;
    if (id != 0u && id <= frame.reflector_count && d != frame.far_depth) {
        let p = baseline_rel_position(pixel, d);
        let plane = planes[id - 1u];
        let ray = baseline_screen_ray(p, plane.normal, params.max_distance);
        if (ray.valid) {
            let hit = march(ray, plane);
            if (hit.found) {
                var alpha = 1.0;
                if (OUTPUT_HIT_DISTANCE) {
                    let q = baseline_rel_position(hit.pixel, textureLoad(depth_tex, hit.pixel, 0).x);
                    alpha = max(distance(q, p), 1e-3);
                }
                out = vec4<f32>(textureLoad(color_tex, hit.pixel, 0).rgb, alpha);
            }
        }
    }
    textureStore(output_tex, pixel, out);
}
