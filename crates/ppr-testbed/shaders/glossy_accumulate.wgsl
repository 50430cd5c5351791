// Exact glossy reference, accumulation (testbed): a self-normalised importance-sampling sum over views
// rendered from eye points E_j behind a rough reflector plane (glossy_views.rs).
//
// `cs_accumulate`, once per view: the view shows, at main-view pixel x (on the plane), the
// radiance arriving at x from ω = normalize(x − E_j). Its weight is f(ω) / p(ω):
//   f(ω) = D(h) (n·h) / (4 |v·h|)     GGX density of reflected directions (alpha =
//                                       roughness², h = normalize(v + ω)), the lobe the
//                                       CPU reference samples (ω·n > 0 always holds here);
//   p(ω) = q(E_j) |x − E_j|² / |n·ω|  the density the eye points induce at x.
// Per pixel: sum.rgb += w L, sum.a += w, moments.x += w² (effective sample size).
// glossy_resolve.wgsl divides.

struct Sample {
    rel_from_main_clip: mat4x4<f32>,
    plane: vec4<f32>,   // xyz: unit normal (reflecting side), w: n · X on the plane (camera-relative)
    eye: vec4<f32>,     // xyz: E_j camera-relative, w: 1 / q(E_j) (m²)
    slot: vec4<u32>,    // x: plane slot of this view
}

struct RoughReflector {
    plane: u32,  // plane slot (0xffffffff: none)
    alpha: f32,  // GGX alpha; 0: a mirror (not accumulated)
}

struct Accum {
    sum: vec4<f32>,      // rgb: Σ w L, a: Σ w
    moments: vec4<f32>,  // x: Σ w², y: views with w > 0
}

const PI: f32 = 3.14159265358979;

@group(0) @binding(0) var<uniform> s: Sample;
@group(0) @binding(1) var<storage, read> reflectors: array<RoughReflector>;
@group(0) @binding(2) var main_ids: texture_2d<u32>;
@group(0) @binding(3) var view_color: texture_2d<f32>;
@group(0) @binding(4) var<storage, read_write> accum: array<Accum>;

fn ggx_reflection_density(alpha: f32, n: vec3<f32>, v: vec3<f32>, w: vec3<f32>) -> f32 {
    let h = normalize(v + w);
    let c = dot(n, h);
    if (c <= 0.0) {
        return 0.0;
    }
    // sin² from the tangential part: exact near the peak, where 1 − c² cancels.
    let t = h - c * n;
    let a2 = alpha * alpha;
    let denom = a2 * c * c + dot(t, t);
    let d = a2 / (PI * denom * denom);
    return d * c / (4.0 * max(abs(dot(v, h)), 1e-8));
}

@compute @workgroup_size(8, 8, 1)
fn cs_accumulate(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = textureDimensions(main_ids);
    if (gid.x >= size.x || gid.y >= size.y) {
        return;
    }
    let px = vec2<i32>(gid.xy);
    let id = textureLoad(main_ids, px, 0).x;
    if (id == 0u) {
        return;
    }
    let r = reflectors[id - 1u];
    if (r.plane != s.slot.x || r.alpha <= 0.0) {
        return;
    }
    let fsize = vec2<f32>(size);
    let ndc = vec2<f32>((f32(gid.x) + 0.5) / fsize.x * 2.0 - 1.0, 1.0 - (f32(gid.y) + 0.5) / fsize.y * 2.0);
    let hp = s.rel_from_main_clip * vec4<f32>(ndc, 0.5, 1.0);
    let dir = normalize(hp.xyz / hp.w);
    let n = s.plane.xyz;
    let dn = dot(n, dir);
    if (dn >= 0.0) {
        return;
    }
    let x = dir * (s.plane.w / dn);
    let to_x = x - s.eye.xyz;
    let dist2 = dot(to_x, to_x);
    let w_dir = to_x * inverseSqrt(dist2);
    let f = ggx_reflection_density(r.alpha, n, -dir, w_dir);
    let weight = f * abs(dot(n, w_dir)) * s.eye.w / dist2;
    let l = textureLoad(view_color, px, 0).rgb;
    let i = gid.y * size.x + gid.x;
    var a = accum[i];
    a.sum += vec4<f32>(weight * l, weight);
    a.moments += vec4<f32>(weight * weight, select(0.0, 1.0, weight > 0.0), 0.0, 0.0);
    accum[i] = a;
}
