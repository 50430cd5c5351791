// Upsample pass of the reduced-resolution tiers: the reduced reflection to the output at
// full resolution. `frame` is the reduced plan's; the full size is the output's. Each
// output pixel blends the four reduced samples around it, bilinearly, weighted by how
// close each sample's surface is to the pixel's own (camera distance, relative): an edge
// between surfaces does not blend their reflections. With none close, the closest sample
// within 10 % is taken, else the pixel has no reflection (alpha 0).
//
// Variants: INDIRECT (reduced tiles not cleared this frame read as empty), LAYERS (the
// glass and water output: plain bilinear over the layer rectangle, the reflection lies on
// the panel, not on the depth buffer's surface).
//
// Entry points: `main_quads` (the main output) takes two by two output pixels per
// invocation: their samples lie in a 3 x 3 window of reduced pixels (2 x 2 at the quarter
// tier), each loaded, and its distance computed, once instead of four times. `main` (the
// layer output, and the bench's one-pixel layout) one pixel per invocation. Both blend
// with the same code, so they store the same values.

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var full_depth: texture_2d<f32>;
@group(0) @binding(2) var reduced_depth: texture_2d<f32>;
@group(0) @binding(3) var reduced_output: texture_2d<f32>;
@group(0) @binding(4) var output: texture_storage_2d<rgba16float, write>;
@group(0) @binding(5) var<storage, read> tile_flags: array<u32>;

override INDIRECT: bool = false;
override LAYERS: bool = false;

// Camera distance of a pixel centre at a depth, for a viewport of `size` pixels.
fn distance_at(pixel: vec2<f32>, depth: f32, size: vec2<f32>) -> f32 {
    let uv = pixel / size;
    let h = frame.rel_from_clip * vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, depth, 1.0);
    return length(h.xyz / h.w);
}

fn reduced_sample(q: vec2<i32>) -> vec4<f32> {
    if (INDIRECT) {
        let tiles_x = (frame.size.x + 15u) / 16u;
        if (tile_flags[u32(q.x) / 16u + u32(q.y) / 16u * tiles_x] == 0u) {
            return vec4<f32>(0.0);
        }
    }
    return textureLoad(reduced_output, q, 0);
}

// A reduced sample: its reflection and its surface's camera distance; `dist` < 0 when the
// sample has no reflection or (main output) no rendered surface: it takes no part.
struct Sample {
    colour: vec4<f32>,
    dist: f32,
}

fn load_sample(q: vec2<i32>) -> Sample {
    let s = reduced_sample(q);
    if (!(s.a > 0.0)) {
        return Sample(s, -1.0);
    }
    if (LAYERS) {
        return Sample(s, 0.0);
    }
    let dq = textureLoad(reduced_depth, q, 0).r;
    if (!ppr_is_valid_depth(dq)) {
        return Sample(s, -1.0);
    }
    return Sample(s, distance_at(vec2<f32>(q) + 0.5, dq, frame.resolution.xy));
}

// The running blend of one output pixel.
struct Blend {
    sum: vec4<f32>,
    weight: f32,
    best: vec4<f32>,
    best_rel: f32,
}

// Adds sample `s` with bilinear weight `w_bilinear` to the blend of a pixel at camera
// distance `own`.
fn add_sample(acc: ptr<function, Blend>, s: Sample, w_bilinear: f32, own: f32) {
    if (s.dist < 0.0) {
        return;
    }
    var w = w_bilinear + 1.0e-6;
    if (!LAYERS) {
        let rel = abs(s.dist - own) / own;
        // Full weight within 1 % of the pixel's distance, none beyond 2 %.
        w *= saturate(2.0 - rel * 100.0);
        if (rel < (*acc).best_rel) {
            (*acc).best_rel = rel;
            (*acc).best = s.colour;
        }
    }
    (*acc).sum += s.colour * w;
    (*acc).weight += w;
}

// The output value of a pixel at camera distance `own` (main output) whose bilinear
// fraction is `f`, from the four reduced samples around it (a at the base, b right of it,
// c below, d diagonal).
fn blend(f: vec2<f32>, own: f32, a: Sample, b: Sample, c: Sample, d: Sample) -> vec4<f32> {
    var acc = Blend(vec4<f32>(0.0), 0.0, vec4<f32>(0.0), 0.1);
    add_sample(&acc, a, (1.0 - f.x) * (1.0 - f.y), own);
    add_sample(&acc, b, f.x * (1.0 - f.y), own);
    add_sample(&acc, c, (1.0 - f.x) * f.y, own);
    add_sample(&acc, d, f.x * f.y, own);
    var result = acc.best;
    if (acc.weight > 1.0e-5) {
        result = acc.sum / acc.weight;
    }
    return result;
}

// The output pixel's centre in reduced pixels, relative to the reduced pixel centres.
fn reduced_position(p: vec2<i32>, scale: vec2<f32>) -> vec2<f32> {
    return (vec2<f32>(p) + 0.5) * scale - 0.5;
}

// The camera distance of output pixel `p`'s surface, or < 0 where it has none.
fn own_distance(p: vec2<i32>, full: vec2<f32>) -> f32 {
    let d = textureLoad(full_depth, p, 0).r;
    if (!ppr_is_valid_depth(d)) {
        return -1.0;
    }
    return distance_at(vec2<f32>(p) + 0.5, d, full);
}

@compute @workgroup_size(16, 16)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let full = vec2<f32>(textureDimensions(output));
    let scale = frame.resolution.xy / full;
    var lo = vec2<i32>(0);
    var hi = vec2<i32>(frame.size) - 1;
    var p = vec2<i32>(gid.xy);
    if (LAYERS) {
        // The layer rectangle in reduced pixels, and the output pixels it covers.
        lo = vec2<i32>(frame.layer_origin);
        hi = lo + vec2<i32>(frame.layer_extent) - 1;
        p += vec2<i32>(floor(vec2<f32>(lo) / scale));
    }
    if (any(vec2<f32>(p) >= full) || any(hi < lo)) {
        return;
    }
    if (LAYERS && any(vec2<f32>(p) + 0.5 >= (vec2<f32>(hi) + 1.0) / scale + 1.0)) {
        return;
    }
    let r = reduced_position(p, scale);
    let base = vec2<i32>(floor(r));
    var own = -1.0;
    if (!LAYERS) {
        own = own_distance(p, full);
        if (own < 0.0) {
            textureStore(output, p, vec4<f32>(0.0));
            return;
        }
    }
    let a = load_sample(clamp(base, lo, hi));
    let b = load_sample(clamp(base + vec2<i32>(1, 0), lo, hi));
    let c = load_sample(clamp(base + vec2<i32>(0, 1), lo, hi));
    let d = load_sample(clamp(base + vec2<i32>(1, 1), lo, hi));
    textureStore(output, p, blend(r - floor(r), own, a, b, c, d));
}

fn pick(x: Sample, y: Sample, second: bool) -> Sample {
    return Sample(select(x.colour, y.colour, second), select(x.dist, y.dist, second));
}

// Output pixel `p` of a quad whose samples start at window column `cx` and row `cy` of
// the 3 x 3 window (s_ij: column i, row j).
fn quad_pixel_out(p: vec2<i32>, full: vec2<f32>, scale: vec2<f32>, a: Sample, b: Sample, c: Sample, d: Sample) {
    if (any(vec2<f32>(p) >= full)) {
        return;
    }
    let own = own_distance(p, full);
    if (own < 0.0) {
        textureStore(output, p, vec4<f32>(0.0));
        return;
    }
    let r = reduced_position(p, scale);
    textureStore(output, p, blend(r - floor(r), own, a, b, c, d));
}

// Two by two output pixels per invocation (main output only). Along each axis the
// second pixel's base is the first's or the next reduced pixel (`ext`), never further:
// adjacent output pixels lie at most one reduced pixel apart.
@compute @workgroup_size(16, 16)
fn main_quads(@builtin(global_invocation_id) gid: vec3<u32>) {
    let full = vec2<f32>(textureDimensions(output));
    let scale = frame.resolution.xy / full;
    let hi = vec2<i32>(frame.size) - 1;
    let p0 = vec2<i32>(gid.xy) * 2;
    if (any(vec2<f32>(p0) >= full) || any(hi < vec2<i32>(0))) {
        return;
    }
    let wb = vec2<i32>(floor(reduced_position(p0, scale)));
    let ext = vec2<i32>(floor(reduced_position(p0 + 1, scale))) - wb;
    let s00 = load_sample(clamp(wb, vec2<i32>(0), hi));
    let s10 = load_sample(clamp(wb + vec2<i32>(1, 0), vec2<i32>(0), hi));
    let s01 = load_sample(clamp(wb + vec2<i32>(0, 1), vec2<i32>(0), hi));
    let s11 = load_sample(clamp(wb + vec2<i32>(1, 1), vec2<i32>(0), hi));
    var s20 = s10;
    var s21 = s11;
    var s02 = s01;
    var s12 = s11;
    var s22 = s11;
    if (ext.x == 1) {
        s20 = load_sample(clamp(wb + vec2<i32>(2, 0), vec2<i32>(0), hi));
        s21 = load_sample(clamp(wb + vec2<i32>(2, 1), vec2<i32>(0), hi));
    }
    if (ext.y == 1) {
        s02 = load_sample(clamp(wb + vec2<i32>(0, 2), vec2<i32>(0), hi));
        s12 = load_sample(clamp(wb + vec2<i32>(1, 2), vec2<i32>(0), hi));
    }
    if (ext.x == 1 && ext.y == 1) {
        s22 = load_sample(clamp(wb + vec2<i32>(2, 2), vec2<i32>(0), hi));
    }
    let nx = ext.x == 1;
    let ny = ext.y == 1;
    // Pixel (0, 0): the window's first 2 x 2.
    quad_pixel_out(p0, full, scale, s00, s10, s01, s11);
    // Pixel (1, 0): columns ext.x and ext.x + 1.
    quad_pixel_out(p0 + vec2<i32>(1, 0), full, scale, pick(s00, s10, nx), pick(s10, s20, nx), pick(s01, s11, nx), pick(s11, s21, nx));
    // Pixel (0, 1): rows ext.y and ext.y + 1.
    quad_pixel_out(p0 + vec2<i32>(0, 1), full, scale, pick(s00, s01, ny), pick(s10, s11, ny), pick(s01, s02, ny), pick(s11, s12, ny));
    // Pixel (1, 1): both.
    let a = pick(pick(s00, s10, nx), pick(s01, s11, nx), ny);
    let b = pick(pick(s10, s20, nx), pick(s11, s21, nx), ny);
    let c = pick(pick(s01, s11, nx), pick(s02, s12, nx), ny);
    let d = pick(pick(s11, s21, nx), pick(s12, s22, nx), ny);
    quad_pixel_out(p0 + vec2<i32>(1, 1), full, scale, a, b, c, d);
}
