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
    // The output pixel's centre in reduced pixels, relative to the reduced pixel centres.
    let r = (vec2<f32>(p) + 0.5) * scale - 0.5;
    let base = vec2<i32>(floor(r));
    let f = r - floor(r);

    var own = -1.0;
    if (!LAYERS) {
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
        let s = reduced_sample(q);
        if (!(s.a > 0.0)) {
            continue;
        }
        let w_bilinear = select(1.0 - f.x, f.x, o.x == 1) * select(1.0 - f.y, f.y, o.y == 1);
        var w = w_bilinear + 1.0e-6;
        if (!LAYERS) {
            let dq = textureLoad(reduced_depth, q, 0).r;
            if (!ppr_is_valid_depth(dq)) {
                continue;
            }
            let rel = abs(distance_at(vec2<f32>(q) + 0.5, dq, frame.resolution.xy) - own) / own;
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
