// SSPR projection (Ghost Recon Wildlands, seed 002): every pixel of the main view above a
// reflector plane is mirrored through the plane, projected back to the screen, and its
// own position written there as the projection hash `y << 16 | x` with `atomicMax`: of
// the pixels landing on the same spot, the lowest on screen wins, which for an upward
// plane is the one closest to the plane (and to the mirrored camera). Pixels below or on
// the plane are skipped (the seed's stencil optimisation). One hash layer per visible
// plane; the optional edge stretch widens the projection towards the left and right edges
// in proportion to the pixel's height above the plane, to fill the border columns that
// need pixels from outside the screen.
// Needs common.wgsl.

struct SsprParams {
    // 1: apply the edge stretch.
    stretch: u32,
    // |ndc x| above which the stretch starts.
    stretch_threshold: f32,
    // Stretch per metre of height above the plane.
    stretch_intensity: f32,
    _pad: u32,
}

// Workgroup edge (threads per side); set from Rust.
override GROUP_EDGE: u32 = 8u;

@group(0) @binding(1) var<uniform> params: SsprParams;
// One plane per hash layer.
@group(0) @binding(2) var<storage, read> layers: array<ReflectorPlane>;
@group(0) @binding(3) var depth_tex: texture_2d<f32>;
@group(0) @binding(4) var<storage, read_write> hash: array<atomic<u32>>;

@compute @workgroup_size(GROUP_EDGE, GROUP_EDGE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let pixel = gid.xy;
    if (any(pixel >= frame.size)) {
        return;
    }
    let d = textureLoad(depth_tex, pixel, 0).x;
    if (d == frame.far_depth) {
        return;
    }
    let p = baseline_rel_position(pixel, d);
    let min_height = frame.plane_epsilon * length(p);
    let layer_pixels = frame.size.x * frame.size.y;
    let source_hash = (pixel.y << 16u) | pixel.x;
    for (var layer = 0u; layer < frame.layer_count; layer = layer + 1u) {
        let plane = layers[layer];
        let height = baseline_plane_distance(plane, p);
        if (height <= min_height) {
            continue;
        }
        let mirrored = p - 2.0 * height * plane.normal;
        let clip = frame.clip_from_rel * vec4<f32>(mirrored, 1.0);
        if (clip.w <= 0.0) {
            continue;
        }
        var ndc = clip.xy / clip.w;
        if (params.stretch == 1u) {
            let angle = saturate(-dot(frame.forward_near.xyz, plane.normal));
            let screen = saturate(abs(ndc.x) - params.stretch_threshold);
            ndc.x = ndc.x * (1.0 + height * angle * screen * params.stretch_intensity);
        }
        let s = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * frame.resolution.xy;
        if (any(s < vec2<f32>(0.0)) || any(s >= frame.resolution.xy)) {
            continue;
        }
        let target_pixel = vec2<u32>(s);
        let index = layer * layer_pixels + target_pixel.y * frame.size.x + target_pixel.x;
        atomicMax(&hash[index], source_hash);
    }
}
