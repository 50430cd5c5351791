// ssr-glossy's roughness blur (the kind Godot and Bevy ship): the ray-marched SSR of
// ssr_march.wgsl (alpha = hit distance) gathered over a disc whose radius grows with the
// reflector's GGX alpha (roughness², per reflector) and the hit distance: a lobe of
// angular width ~ spread·alpha seen over the reflected path |p| + hit distance, in pixels.
// Taps on a Vogel disc with Gaussian weights, kept on the same reflector and where the
// march found something. Mirrors (alpha 0) pass the march through unchanged.
// Needs common.wgsl.

struct GlossyBlurParams {
    // Radius at the hit in units of alpha × hit distance.
    spread: f32,
    // Largest radius, pixels.
    max_radius: f32,
    // Gather taps besides the centre.
    samples: u32,
    _pad0: u32,
}

// Workgroup edge (threads per side); set from Rust.
override GROUP_EDGE: u32 = 8u;

const GOLDEN_ANGLE: f32 = 2.39996323;

@group(0) @binding(1) var<uniform> params: GlossyBlurParams;
@group(0) @binding(2) var<storage, read> alphas: array<f32>;
@group(0) @binding(3) var depth_tex: texture_2d<f32>;
@group(0) @binding(4) var reflector_tex: texture_2d<u32>;
@group(0) @binding(5) var march_tex: texture_2d<f32>;
@group(0) @binding(6) var output_tex: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(GROUP_EDGE, GROUP_EDGE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let pixel = gid.xy;
    if (any(pixel >= frame.size)) {
        return;
    }
    var out = vec4<f32>(0.0);
    let id = textureLoad(reflector_tex, pixel, 0).x;
    let m = textureLoad(march_tex, pixel, 0);
    if (id != 0u && id <= frame.reflector_count && m.a > 0.0) {
        out = vec4<f32>(m.rgb, 1.0);
        let alpha = alphas[id - 1u];
        if (alpha > 0.0) {
            let p = baseline_rel_position(pixel, textureLoad(depth_tex, pixel, 0).x);
            let px_per_radian = 0.5 * frame.resolution.y * frame.clip_from_rel[1][1];
            let radius = min(params.spread * alpha * m.a / (length(p) + m.a) * px_per_radian, params.max_radius);
            if (radius >= 0.5) {
                var sum = vec4<f32>(m.rgb, 1.0);
                let n = max(params.samples, 1u);
                for (var i = 0u; i < n; i = i + 1u) {
                    let r = radius * sqrt((f32(i) + 0.5) / f32(n));
                    let angle = f32(i) * GOLDEN_ANGLE;
                    let q = vec2<f32>(pixel) + 0.5 + r * vec2<f32>(cos(angle), sin(angle));
                    if (any(q < vec2<f32>(0.0)) || any(q >= frame.resolution.xy)) {
                        continue;
                    }
                    let qp = vec2<u32>(q);
                    if (textureLoad(reflector_tex, qp, 0).x != id) {
                        continue;
                    }
                    let s = textureLoad(march_tex, qp, 0);
                    if (s.a <= 0.0) {
                        continue;
                    }
                    let w = exp(-2.0 * r * r / (radius * radius));
                    sum += vec4<f32>(s.rgb * w, w);
                }
                out = vec4<f32>(sum.rgb / sum.a, 1.0);
            }
        }
    }
    textureStore(output_tex, pixel, out);
}
