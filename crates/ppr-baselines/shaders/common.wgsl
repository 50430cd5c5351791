// Declarations shared by the baseline passes (prepended to each pass by
// crates/ppr-baselines/src/shader.rs): the frame uniform, reflector planes, position
// reconstruction, projection and the screen-space reflection ray.
// Mirrors crates/ppr-baselines/src/gpu_types.rs byte for byte (sizes asserted there).

// Linear view depth given to pixels where nothing was drawn (the sky).
const BASELINE_SKY_DEPTH: f32 = 1e30;
// A surface point closer to the source reflector's plane than this times its camera
// distance lies on that plane: a planar mirror never reflects itself, so a ray-march hit
// there is a self-intersection and is skipped.
const BASELINE_SELF_HIT_EPSILON: f32 = 1e-3;
// Layer of a reflector whose plane has no SSPR hash layer this frame.
const BASELINE_NO_LAYER: u32 = 0xffffffffu;

struct BaselineFrame {
    clip_from_rel: mat4x4<f32>,
    rel_from_clip: mat4x4<f32>,
    // width, height, 1 / width, 1 / height
    resolution: vec4<f32>,
    // xyz: the camera's forward direction; w: near-plane distance (metres).
    forward_near: vec4<f32>,
    size: vec2<u32>,
    // Device depth of a pixel where nothing was drawn.
    far_depth: f32,
    // Device depth d and linear view depth w are tied by d = depth_a + depth_b / w.
    depth_a: f32,
    depth_b: f32,
    // Points closer to a reflector's plane than this times their distance from the camera
    // lie on it.
    plane_epsilon: f32,
    reflector_count: u32,
    layer_count: u32,
}

// Every pass binds the frame at group 0, binding 0.
@group(0) @binding(0) var<uniform> frame: BaselineFrame;

// The plane of one reflector, camera-relative: points p with dot(normal, p) == offset.
struct ReflectorPlane {
    normal: vec3<f32>,
    // dot(normal, point on the plane), computed in f64 on the CPU.
    offset: f32,
    // SSPR hash layer of the plane (BASELINE_NO_LAYER when it has none this frame).
    layer: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// Linear view depth (clip w) of a device depth value; BASELINE_SKY_DEPTH where nothing
// was drawn.
fn baseline_view_depth(d: f32) -> f32 {
    if (d == frame.far_depth) {
        return BASELINE_SKY_DEPTH;
    }
    let w = frame.depth_b / (d - frame.depth_a);
    return select(BASELINE_SKY_DEPTH, w, w > 0.0 && w < BASELINE_SKY_DEPTH);
}

// Camera-relative position of the centre of `pixel` at device depth `d`.
fn baseline_rel_position(pixel: vec2<u32>, d: f32) -> vec3<f32> {
    let uv = (vec2<f32>(pixel) + 0.5) * frame.resolution.zw;
    let ndc = vec2<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0);
    let h = frame.rel_from_clip * vec4<f32>(ndc, d, 1.0);
    return h.xyz / h.w;
}

// Whether the surface at `pixel` (device depth `d`) lies on `plane` (a self-intersection
// of a ray leaving that plane).
fn baseline_on_plane(plane: ReflectorPlane, pixel: vec2<u32>, d: f32) -> bool {
    let p = baseline_rel_position(pixel, d);
    return abs(baseline_plane_distance(plane, p)) <= BASELINE_SELF_HIT_EPSILON * length(p);
}

// Continuous pixel coordinates (x right, y down, pixel centres at +0.5) of clip-space `clip`.
fn baseline_clip_to_pixel(clip: vec4<f32>) -> vec2<f32> {
    let ndc = clip.xy / clip.w;
    return vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * frame.resolution.xy;
}

// Signed distance of camera-relative `p` from `plane`.
fn baseline_plane_distance(plane: ReflectorPlane, p: vec3<f32>) -> f32 {
    return dot(plane.normal, p) - plane.offset;
}

// The reflection ray of one pixel as a screen-space segment: pixel coordinates and inverse
// linear depth k = 1 / w at both ends (k is linear in screen space, so the ray's depth at
// any point of the segment interpolates exactly). The segment starts at the pixel centre
// and is clipped to the near plane and to the viewport.
struct ScreenRay {
    start: vec2<f32>,
    end: vec2<f32>,
    k_start: f32,
    k_end: f32,
    // Pixels along the major axis from start to end (< 1: nothing to march).
    length: f32,
    valid: bool,
}

fn baseline_screen_ray(p: vec3<f32>, normal: vec3<f32>, max_distance: f32) -> ScreenRay {
    var ray: ScreenRay;
    ray.valid = false;
    let incident = normalize(p);
    let r = reflect(incident, normal);
    if (dot(r, normal) <= 0.0) {
        // Seen from behind the reflector: nothing to reflect.
        return ray;
    }
    let c0 = frame.clip_from_rel * vec4<f32>(p, 1.0);
    let cr = frame.clip_from_rel * vec4<f32>(r, 0.0);
    // Clip the ray where it would cross the near plane (w = near).
    var distance = max_distance;
    let near = frame.forward_near.w;
    if (c0.w + distance * cr.w < near) {
        distance = (near - c0.w) / cr.w * 0.999;
    }
    let c1 = c0 + distance * cr;
    let s0 = baseline_clip_to_pixel(c0);
    var s1 = baseline_clip_to_pixel(c1);
    let k0 = 1.0 / c0.w;
    var k1 = 1.0 / c1.w;
    // Clip the far end to the viewport (the start is inside).
    let d = s1 - s0;
    var t = 1.0;
    let lo = vec2<f32>(0.0);
    let hi = frame.resolution.xy;
    for (var axis = 0; axis < 2; axis = axis + 1) {
        if (d[axis] > 0.0 && s1[axis] > hi[axis]) {
            t = min(t, (hi[axis] - s0[axis]) / d[axis]);
        } else if (d[axis] < 0.0 && s1[axis] < lo[axis]) {
            t = min(t, (lo[axis] - s0[axis]) / d[axis]);
        }
    }
    t = max(t, 0.0);
    s1 = s0 + d * t;
    k1 = k0 + (k1 - k0) * t;
    ray.start = s0;
    ray.end = s1;
    ray.k_start = k0;
    ray.k_end = k1;
    ray.length = max(abs(s1.x - s0.x), abs(s1.y - s0.y));
    ray.valid = ray.length >= 1.0;
    return ray;
}

// The integer pixel containing continuous pixel position `s`, clamped to the viewport.
fn baseline_pixel_at(s: vec2<f32>) -> vec2<u32> {
    let p = clamp(floor(s), vec2<f32>(0.0), frame.resolution.xy - 1.0);
    return vec2<u32>(p);
}
