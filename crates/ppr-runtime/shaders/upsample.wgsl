// Upsample pass of the reduced-resolution tiers: the reduced reflection to the output at
// full resolution. `frame` is the reduced plan's; the full size is the output's. Each
// output pixel blends the four reduced samples around it, bilinearly, weighted by how
// close each sample's surface is to the pixel's own (camera distance, relative): an edge
// between surfaces does not blend their reflections. With none close, the closest sample
// within 10 % is taken, else the pixel has no reflection (alpha 0).
//
// Variants: INDIRECT (reduced tiles not cleared this frame read as empty), LAYERS (the
// glass and water output: plain bilinear over the layer rectangle, the reflection lies on
// the panel, not on the depth buffer's surface), SHARED (where the four samples come from).
// Without SHARED, the default, each pixel reads its four samples (colour and depth) from
// the reduced textures and computes their camera distances itself, so that each sample is
// read, and its distance computed, by about 4 pixels at the half tier and 16 at the
// quarter tier. With SHARED (bench only, the same image bit for bit) each 16 × 16
// workgroup first reads every sample its pixels can need once, into workgroup memory
// (colour and, unless LAYERS, camera distance: the same `reduced_sample` and
// `reduced_distance` calls), and each pixel reads its four from there; a pixel none of
// whose four holds a reflection writes none without reading its depth.
//
// PROBE (bench only, `UpsampleProbe`: what the pass's time is made of; not the image):
// 1 stores nothing but the empty reflection, 2 reads the pixel's depth and stores, 3 is
// the default with the pixel's own camera distance taken from its four samples' instead
// of its depth (no full-resolution read).

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var full_depth: texture_2d<f32>;
@group(0) @binding(2) var reduced_depth: texture_2d<f32>;
@group(0) @binding(3) var reduced_output: texture_2d<f32>;
@group(0) @binding(4) var output: texture_storage_2d<rgba16float, write>;
@group(0) @binding(5) var<storage, read> tile_flags: array<u32>;

override INDIRECT: bool = false;
override LAYERS: bool = false;
override SHARED: bool = false;
override PROBE: u32 = 0u;

// Output pixels per workgroup edge.
const GROUP_EDGE: i32 = 16;
// Reduced samples per axis a workgroup's pixels can read (SHARED): with a scale of at most
// 1 their base indices lie within 15 of each other, plus the neighbour after the last: at
// most 17, and one more of margin.
const SPAN_EDGE: i32 = 18;
// `span_colour` and `span_distance`, the workgroup arrays, come from upsample_span.wgsl
// (SHARED pipelines) or upsample_span_stub.wgsl (one element each: the per-pixel ones).

// Where reduced sample `q` lies in the workgroup's span of `span` samples from `first`.
fn span_index(q: vec2<i32>, first: vec2<i32>, span: vec2<i32>) -> i32 {
    return (q.y - first.y) * span.x + q.x - first.x;
}

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

// Camera distance of the surface at reduced sample `q`; -1 where its depth is not valid
// (a distance is never negative).
fn reduced_distance(q: vec2<i32>) -> f32 {
    let d = textureLoad(reduced_depth, q, 0).r;
    if (!ppr_is_valid_depth(d)) {
        return -1.0;
    }
    return distance_at(vec2<f32>(q) + 0.5, d, frame.resolution.xy);
}

// The centre of output pixel `p` in reduced pixels, relative to the reduced pixel centres:
// its first sample is the floor, monotone in `p`.
fn reduced_position(p: vec2<i32>, scale: vec2<f32>) -> vec2<f32> {
    return (vec2<f32>(p) + 0.5) * scale - 0.5;
}

@compute @workgroup_size(16, 16)
fn main(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let full = vec2<f32>(textureDimensions(output));
    let scale = frame.resolution.xy / full;
    var lo = vec2<i32>(0);
    var hi = vec2<i32>(frame.size) - 1;
    var origin = vec2<i32>(0);
    if (LAYERS) {
        // The layer rectangle in reduced pixels, and the output pixels it covers.
        lo = vec2<i32>(frame.layer_origin);
        hi = lo + vec2<i32>(frame.layer_extent) - 1;
        origin = vec2<i32>(floor(vec2<f32>(lo) / scale));
    }
    if (any(hi < lo)) {
        return;
    }
    let p = vec2<i32>(gid.xy) + origin;
    // No return before the barrier that depends on the invocation.
    let outside = any(vec2<f32>(p) >= full)
        || (LAYERS && any(vec2<f32>(p) + 0.5 >= (vec2<f32>(hi) + 1.0) / scale + 1.0));

    // SHARED: the samples from the workgroup's first pixel's first to its last pixel's last,
    // clamped as each pixel clamps them, each read once.
    var first = vec2<i32>(0);
    var span = vec2<i32>(0);
    if (SHARED) {
        let p0 = vec2<i32>(wid.xy) * GROUP_EDGE + origin;
        first = clamp(vec2<i32>(floor(reduced_position(p0, scale))), lo, hi);
        let last = clamp(vec2<i32>(floor(reduced_position(p0 + GROUP_EDGE - 1, scale))) + 1, lo, hi);
        span = min(last - first + 1, vec2<i32>(SPAN_EDGE));
        for (var i = i32(lid); i < span.x * span.y; i += GROUP_EDGE * GROUP_EDGE) {
            let q = first + vec2<i32>(i % span.x, i / span.x);
            let colour = reduced_sample(q);
            span_colour[i] = colour;
            // A sample without data is never weighed: its depth is not read.
            if (!LAYERS && colour.a > 0.0) {
                span_distance[i] = reduced_distance(q);
            }
        }
        workgroupBarrier();
    }
    if (outside) {
        return;
    }
    if (PROBE == 1u) {
        textureStore(output, p, vec4<f32>(0.0));
        return;
    }
    if (PROBE == 2u) {
        textureStore(output, p, vec4<f32>(textureLoad(full_depth, p, 0).r * 1e-30));
        return;
    }

    let r = reduced_position(p, scale);
    let base = vec2<i32>(floor(r));
    let f = r - floor(r);

    // SHARED: a pixel whose four samples hold no reflection has none (what the loop below
    // would find), without reading its depth.
    if (SHARED) {
        var data = false;
        for (var k = 0; k < 4; k++) {
            let q = clamp(base + vec2<i32>(k & 1, k >> 1), lo, hi);
            data = data || span_colour[span_index(q, first, span)].a > 0.0;
        }
        if (!data) {
            textureStore(output, p, vec4<f32>(0.0));
            return;
        }
    }
    var own = -1.0;
    // PROBE 3: the four samples and their distances, read once.
    var probe_s: array<vec4<f32>, 4>;
    var probe_d: array<f32, 4>;
    if (PROBE == 3u) {
        // The bilinear mean of the four samples' distances that have data and depth.
        var sum_d = 0.0;
        var sum_w = 0.0;
        for (var k = 0; k < 4; k++) {
            let o = vec2<i32>(k & 1, k >> 1);
            let q = clamp(base + o, lo, hi);
            probe_s[k] = reduced_sample(q);
            probe_d[k] = select(-1.0, reduced_distance(q), probe_s[k].a > 0.0);
            let dq = probe_d[k];
            let w = select(1.0 - f.x, f.x, o.x == 1) * select(1.0 - f.y, f.y, o.y == 1) + 1.0e-6;
            if (dq >= 0.0) {
                sum_d += dq * w;
                sum_w += w;
            }
        }
        if (!(sum_w > 0.0)) {
            textureStore(output, p, vec4<f32>(0.0));
            return;
        }
        own = sum_d / sum_w;
    } else if (!LAYERS) {
        let d = textureLoad(full_depth, p, 0).r;
        if (!ppr_is_valid_depth(d)) {
            textureStore(output, p, vec4<f32>(0.0));
            return;
        }
        own = distance_at(vec2<f32>(p) + 0.5, d, full);
    }
    var sum = vec4<f32>(0.0);
    var weight = 0.0;
    var best = vec4<f32>(0.0);
    var best_rel = 0.1;
    for (var k = 0; k < 4; k++) {
        let o = vec2<i32>(k & 1, k >> 1);
        let q = clamp(base + o, lo, hi);
        // With SHARED, where sample `q` lies in the workgroup's span.
        var at = 0;
        var s: vec4<f32>;
        if (SHARED) {
            at = span_index(q, first, span);
            s = span_colour[at];
        } else if (PROBE == 3u) {
            s = probe_s[k];
        } else {
            s = reduced_sample(q);
        }
        if (!(s.a > 0.0)) {
            continue;
        }
        let w_bilinear = select(1.0 - f.x, f.x, o.x == 1) * select(1.0 - f.y, f.y, o.y == 1);
        var w = w_bilinear + 1.0e-6;
        if (!LAYERS) {
            var dq: f32;
            if (SHARED) {
                dq = span_distance[at];
            } else if (PROBE == 3u) {
                dq = probe_d[k];
            } else {
                dq = reduced_distance(q);
            }
            if (dq < 0.0) {
                continue;
            }
            let rel = abs(dq - own) / own;
            // Full weight within 1 % of the pixel's distance, none beyond 2 %.
            w *= saturate(2.0 - rel * 100.0);
            if (rel < best_rel) {
                best_rel = rel;
                best = s;
            }
        }
        sum += s * w;
        weight += w;
    }
    var result = best;
    if (weight > 1.0e-5) {
        result = sum / weight;
    }
    textureStore(output, p, result);
}
