// Downsample pass of the reduced-resolution tiers: the scene's depth at the plan's reduced
// size, so that clear, projection and reflection run unchanged on a quarter (half tier) or
// a sixteenth (quarter tier) of the pixels (the reflection reads the full-size colour).
// `frame` is the reduced plan's. Each reduced pixel takes the four full-resolution depths
// around its centre: bilinearly where they lie on one plane (NDC depth is affine in screen space over a plane, so a
// reflector's pixels stay exactly on it), else the nearest of the four to the camera (a
// silhouette keeps its foreground instead of a point floating between two surfaces).

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var full_depth: texture_2d<f32>;
@group(0) @binding(2) var reduced_depth: texture_storage_2d<r32float, write>;

// Camera distance of a full-resolution pixel's depth (the same camera: rel_from_clip does
// not depend on the resolution).
fn full_distance(p: vec2<i32>, depth: f32, full: vec2<f32>) -> f32 {
    let uv = (vec2<f32>(p) + 0.5) / full;
    let h = frame.rel_from_clip * vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, depth, 1.0);
    return length(h.xyz / h.w);
}

@compute @workgroup_size(16, 16)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if (any(gid.xy >= frame.size)) {
        return;
    }
    let dims = vec2<i32>(textureDimensions(full_depth));
    let full = vec2<f32>(dims);
    // The reduced pixel's centre in full-resolution pixels, and the four pixel centres
    // around it.
    let c = (vec2<f32>(gid.xy) + 0.5) * full / frame.resolution.xy - 0.5;
    let base = vec2<i32>(floor(c));
    let f = c - floor(c);
    let hi = dims - 1;
    let p00 = clamp(base, vec2<i32>(0), hi);
    let p10 = clamp(base + vec2<i32>(1, 0), vec2<i32>(0), hi);
    let p01 = clamp(base + vec2<i32>(0, 1), vec2<i32>(0), hi);
    let p11 = clamp(base + vec2<i32>(1, 1), vec2<i32>(0), hi);

    let d = vec4<f32>(
        textureLoad(full_depth, p00, 0).r,
        textureLoad(full_depth, p10, 0).r,
        textureLoad(full_depth, p01, 0).r,
        textureLoad(full_depth, p11, 0).r,
    );
    let valid = vec4<bool>(
        ppr_is_valid_depth(d.x),
        ppr_is_valid_depth(d.y),
        ppr_is_valid_depth(d.z),
        ppr_is_valid_depth(d.w),
    );
    var out_depth = frame.far_depth;
    if (any(valid)) {
        let far = 3.0e38;
        let dist = vec4<f32>(
            select(far, full_distance(p00, d.x, full), valid.x),
            select(far, full_distance(p10, d.y, full), valid.y),
            select(far, full_distance(p01, d.z, full), valid.z),
            select(far, full_distance(p11, d.w, full), valid.w),
        );
        let nearest = min(min(dist.x, dist.y), min(dist.z, dist.w));
        let farthest = max(max(dist.x, dist.y), max(dist.z, dist.w));
        // Four samples of one plane: an affine function has d00 + d11 == d10 + d01 (up to
        // rounding), and a step between surfaces shows as a large spread of distances.
        let residual = abs(d.x + d.w - d.y - d.z);
        let spread = max(max(d.x, d.y), max(d.z, d.w)) - min(min(d.x, d.y), min(d.z, d.w));
        let ulps = 8.0 * 1.1920929e-7 * max(max(abs(d.x), abs(d.w)), 1.0e-30);
        let planar = all(valid) && farthest <= nearest * 1.1 && residual <= 0.25 * spread + ulps;
        if (planar) {
            out_depth = mix(mix(d.x, d.y, f.x), mix(d.z, d.w, f.x), f.y);
        } else if (dist.x == nearest) {
            out_depth = d.x;
        } else if (dist.y == nearest) {
            out_depth = d.y;
        } else if (dist.z == nearest) {
            out_depth = d.z;
        } else {
            out_depth = d.w;
        }
    }
    textureStore(reduced_depth, vec2<i32>(gid.xy), vec4<f32>(out_depth, 0.0, 0.0, 0.0));
}
