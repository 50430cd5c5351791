// Projection pass: for every pixel, mirror its position against each visible reflector,
// test the reflection point against the rectangle and its occluders, and atomicMin the
// encoded screen offset into the intermediate buffer where the pixel is reflected.
// Seed: PPR_ProjectionPassWrite.

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
@group(0) @binding(1) var depth_tex: texture_2d<f32>;
@group(0) @binding(2) var<storage, read> shapes: array<Shape>;
@group(0) @binding(3) var<storage, read> visible: array<u32>;
@group(0) @binding(4) var<storage, read> occluders: array<u32>;
@group(0) @binding(5) var<storage, read_write> intermediate: array<atomic<u32>>;

fn is_occluded(hit: vec3<f32>, s: Shape) -> bool {
    for (var k = 0u; k < s.occluder_count; k++) {
        let o = shapes[occluders[s.occluder_start + k]];
        if ((o.flags & PPR_SHAPE_OCCLUDES) != 0u && ppr_segment_hits_shape(hit, o)) {
            return true;
        }
    }
    return false;
}

// Writes the reflection of `pixel` (camera-relative position `mirrored` once mirrored).
fn write_projection(pixel: vec2<u32>, mirrored: vec3<f32>) {
    let clip = frame.clip_from_rel * vec4<f32>(mirrored, 1.0);
    if (!(clip.w > 0.0)) {
        return;
    }
    let ndc = clip.xy / clip.w;
    if (!all(abs(ndc) < vec2<f32>(1.0))) {
        return;
    }
    let target_crd = (ndc * vec2<f32>(0.5, -0.5) + 0.5) * frame.resolution.xy;
    let offset = target_crd - (vec2<f32>(pixel) + 0.5);
    let value = ppr_encode(offset, frame.encoding);
    if (value == PPR_CLEAR_VALUE) {
        return;
    }
    let t = min(vec2<u32>(target_crd), frame.size - 1u);
    let index = t.x + t.y * frame.size.x;
    if ((frame.flags & (PPR_FLAG_WRITE_LAST | PPR_FLAG_WRITE_MAX)) == 0u) {
        atomicMin(&intermediate[index], value);
    } else if ((frame.flags & PPR_FLAG_WRITE_LAST) != 0u) {
        atomicStore(&intermediate[index], value);
    } else {
        // The largest offset wins; the clear value counts as empty, so plain atomicMax
        // would never write: a compare-exchange loop instead (debug path only).
        var old = atomicLoad(&intermediate[index]);
        loop {
            if (old != PPR_CLEAR_VALUE && old >= value) {
                break;
            }
            let r = atomicCompareExchangeWeak(&intermediate[index], old, value);
            if (r.exchanged) {
                break;
            }
            old = r.old_value;
        }
    }
}

@compute @workgroup_size(16, 16)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if (any(gid.xy >= frame.size)) {
        return;
    }
    let depth = textureLoad(depth_tex, vec2<i32>(gid.xy), 0).r;
    // Nothing rendered here (far plane), or a depth that is not a number.
    if (!(depth >= 0.0 && depth <= 1.0) || depth == frame.far_depth) {
        return;
    }
    let uv = (vec2<f32>(gid.xy) + 0.5) * frame.resolution.zw;
    let ndc = vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, depth, 1.0);
    let h = frame.rel_from_clip * ndc;
    let p = h.xyz / h.w;
    if (!all(abs(p) < vec3<f32>(1e30))) {
        return;
    }
    let occluder_tests = (frame.flags & PPR_FLAG_OCCLUDER_TESTS) != 0u;
    let min_dist = frame.plane_epsilon * length(p);
    for (var i = 0u; i < frame.visible_count; i++) {
        let s = shapes[visible[i]];
        let dist = dot(p, s.normal) - s.plane_dist;
        if (!(dist > min_dist)) {
            continue;
        }
        // Mirror against the plane; cast from the camera (origin) to the mirrored point.
        let mirrored = p - 2.0 * dist * s.normal;
        let hit = mirrored * (s.plane_dist / dot(mirrored, s.normal));
        let l = hit - s.center;
        if (abs(dot(l, s.axis_u)) > s.half_u || abs(dot(l, s.axis_v)) > s.half_v) {
            continue;
        }
        if (occluder_tests && is_occluded(hit, s)) {
            continue;
        }
        write_projection(gid.xy, mirrored);
    }
}
