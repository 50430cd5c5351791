// Debug view of PPR's intermediate buffer: one u32 per pixel, the encoded screen offset
// from each reflecting pixel to the pixel it reflects (see shaders/ppr/encoding.wgsl).
// Black: the clear value (nothing projected here). Otherwise the decoded whole offset:
// red = x, green = y (0.5 = zero, full range = ±`range` pixels), blue = packing basis.

struct IntermediateView {
    size: vec2<u32>,
    major_int_bits: u32,
    major_frac_bits: u32,
    minor_int_bits: u32,
    minor_frac_bits: u32,
    encode_srgb: u32,
    range: f32,
}

@group(0) @binding(0) var<uniform> params: IntermediateView;
@group(0) @binding(1) var<storage, read> intermediate: array<u32>;

// `vs_main`: the full-screen triangle of ppr-scene-gpu's fullscreen_triangle.wgsl.

// Packing basis (minor, major) -> screen space, as ppr_to_screen.
fn to_screen(v: vec2<f32>, basis: u32) -> vec2<f32> {
    switch basis {
        case 0u: { return vec2<f32>(v.y, -v.x); }
        case 1u: { return vec2<f32>(-v.y, v.x); }
        case 2u: { return v; }
        default: { return -v; }
    }
}

fn linear_to_srgb(c: vec3<f32>) -> vec3<f32> {
    let low = c * 12.92;
    let high = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(high, low, c <= vec3<f32>(0.0031308));
}

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<u32>(position.xy);
    let value = intermediate[p.y * params.size.x + p.x];
    var rgb = vec3<f32>(0.0);
    if (value != 0xffffffffu) {
        let basis = value & 3u;
        let rest = value >> 2u;
        let minor_bits = params.minor_int_bits + params.minor_frac_bits;
        let minor_field = rest & ((1u << minor_bits) - 1u);
        let major_field = rest >> minor_bits;
        let major = f32(major_field >> params.major_frac_bits);
        let bias = i32(1u << (params.minor_int_bits - 1u));
        let minor = f32(i32(minor_field >> params.minor_frac_bits) - bias);
        let offset = to_screen(vec2<f32>(minor, major), basis);
        let o = clamp(offset / params.range, vec2<f32>(-1.0), vec2<f32>(1.0));
        rgb = vec3<f32>(0.5 + 0.5 * o.x, 0.5 + 0.5 * o.y, 0.25 + 0.25 * f32(basis));
    }
    if (params.encode_srgb == 1u) {
        rgb = linear_to_srgb(rgb);
    }
    return vec4<f32>(rgb, 1.0);
}
