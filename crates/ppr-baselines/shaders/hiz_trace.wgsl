// Hi-Z screen-space reflections (Uludag 2014, seed 004): per reflector pixel, reflect the
// view ray about the reflector's plane and walk it through the min-depth pyramid of
// hiz_build.wgsl. While the ray is in front of the closest surface of its cell it jumps
// to that depth or to the cell's edge and climbs a level; once it is behind, it descends,
// until it is behind a single pixel: the hit. No tracing behind geometry (as in the PPR
// talk's comparison): the first surface the ray passes behind stops it; `thickness` can
// reject hits too far behind the surface (infinite by default).
// Needs common.wgsl and hiz_layout.wgsl.

struct HiZParams {
    // Most cell visits per ray.
    max_iterations: u32,
    // Highest pyramid level the walk climbs to (below the pyramid's level count).
    top_level: u32,
    // A hit further behind the surface than this (metres of view depth) is rejected.
    thickness: f32,
    // Longest reflection ray, metres.
    max_distance: f32,
}

// Workgroup edge (threads per side); set from Rust.
override GROUP_EDGE: u32 = 8u;

@group(0) @binding(1) var<uniform> params: HiZParams;
@group(0) @binding(2) var<storage, read> planes: array<ReflectorPlane>;
@group(0) @binding(3) var hiz: texture_2d<f32>;
@group(0) @binding(8) var<uniform> levels: HiZLevels;
@group(0) @binding(4) var depth_tex: texture_2d<f32>;
@group(0) @binding(5) var reflector_tex: texture_2d<u32>;
@group(0) @binding(6) var color_tex: texture_2d<f32>;
@group(0) @binding(7) var output_tex: texture_storage_2d<rgba16float, write>;

// Pixels a step past a cell edge is nudged along the ray, so that a point on the edge
// belongs to the cell being entered.
const CELL_NUDGE: f32 = 0.01;

// Width and height of pyramid level `level`.
fn level_size(level: i32) -> vec2<u32> {
    return levels.rects[level].zw;
}

// The closest linear depth in `cell` of `level`.
fn cell_depth(cell: vec2<u32>, level: i32) -> f32 {
    return textureLoad(hiz, levels.rects[level].xy + cell, 0).x;
}

// The cell of `level` holding continuous pixel position `p` (moving along `dir`).
fn cell_of(p: vec2<f32>, dir: vec2<f32>, level: i32) -> vec2<u32> {
    let q = p + sign(dir) * CELL_NUDGE;
    let c = floor(q / f32(1u << u32(level)));
    let n = vec2<f32>(level_size(level));
    return vec2<u32>(clamp(c, vec2<f32>(0.0), n - 1.0));
}

// Ray parameter where the segment start + dir * t leaves `cell` of `level`. The last
// cell of a row or column reaches the screen edge (hiz_build folds odd edges into it).
fn cell_exit(start: vec2<f32>, dir: vec2<f32>, cell: vec2<u32>, level: i32) -> f32 {
    let size = f32(1u << u32(level));
    let n = level_size(level);
    let lo = vec2<f32>(cell) * size;
    let hi = select(vec2<f32>(cell + 1u) * size, frame.resolution.xy, cell + 1u >= n);
    var t = 1e30;
    for (var axis = 0; axis < 2; axis = axis + 1) {
        if (dir[axis] > 0.0) {
            t = min(t, (hi[axis] - start[axis]) / dir[axis]);
        } else if (dir[axis] < 0.0) {
            t = min(t, (lo[axis] - start[axis]) / dir[axis]);
        }
    }
    return t;
}

struct TraceResult {
    found: bool,
    pixel: vec2<u32>,
}

fn trace(ray: ScreenRay, plane: ReflectorPlane) -> TraceResult {
    var result: TraceResult;
    result.found = false;
    let dir = ray.end - ray.start;
    let dk = ray.k_end - ray.k_start;
    let top = i32(params.top_level);
    // Start one pixel out along the major axis, off the source pixel.
    var t = 1.0 / ray.length;
    var level = 0;
    var hit_pixel = vec2<u32>(0u);
    for (var i = 0u; i < params.max_iterations; i = i + 1u) {
        if (level < 0 || t > 1.0) {
            break;
        }
        let p = ray.start + dir * t;
        let cell = cell_of(p, dir, level);
        let k_cell = 1.0 / cell_depth(cell, level);
        let k_ray = ray.k_start + dk * t;
        let t_exit = cell_exit(ray.start, dir, cell, level);
        var t_next = t;
        var crossed = false;
        if (k_ray > k_cell) {
            // In front of the closest surface of the cell: advance to its depth if the
            // ray goes away from the camera, else to the cell's edge.
            if (dk < 0.0) {
                t_next = max(t, (k_cell - ray.k_start) / dk);
            } else {
                t_next = t_exit;
            }
            crossed = t_next >= t_exit;
        } else if (level == 0) {
            // Behind the pixel's surface: a hit, unless that surface is the source plane.
            crossed = baseline_on_plane(plane, cell, textureLoad(depth_tex, cell, 0).x);
        }
        if (crossed) {
            t = t_exit;
            level = min(level + 1, top);
        } else {
            t = t_next;
            if (level == 0) {
                hit_pixel = cell;
            }
            level = level - 1;
        }
    }
    if (level < 0 && t <= 1.0) {
        let w_ray = 1.0 / (ray.k_start + dk * t);
        let w_scene = cell_depth(hit_pixel, 0);
        result.found = w_ray - w_scene <= params.thickness;
        result.pixel = hit_pixel;
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
            let hit = trace(ray, plane);
            if (hit.found) {
                out = vec4<f32>(textureLoad(color_tex, hit.pixel, 0).rgb, 1.0);
            }
        }
    }
    textureStore(output_tex, pixel, out);
}
