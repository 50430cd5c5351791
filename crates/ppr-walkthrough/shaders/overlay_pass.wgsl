// The on-screen text: an RGBA image (rasterised on the CPU) drawn 1:1 at a pixel position,
// alpha blended over the composited frame.

struct Overlay {
    origin: vec2<f32>,       // top-left corner, pixels
    size: vec2<f32>,         // image size, pixels
    target_size: vec2<f32>,  // output size, pixels
    encode_srgb: u32,        // 1: the target is not sRGB, encode here
    _pad: u32,
}

@group(0) @binding(0) var<uniform> overlay: Overlay;
@group(0) @binding(1) var text: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    // Two triangles: corners (0,0) (1,0) (0,1) / (0,1) (1,0) (1,1).
    var corners = array<vec2<f32>, 6>(
        vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 0.0), vec2<f32>(0.0, 1.0),
        vec2<f32>(0.0, 1.0), vec2<f32>(1.0, 0.0), vec2<f32>(1.0, 1.0),
    );
    let px = overlay.origin + corners[i] * overlay.size;
    let ndc = px / overlay.target_size * vec2<f32>(2.0, -2.0) + vec2<f32>(-1.0, 1.0);
    return vec4<f32>(ndc, 0.0, 1.0);
}

fn linear_to_srgb(c: vec3<f32>) -> vec3<f32> {
    let low = c * 12.92;
    let high = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(high, low, c <= vec3<f32>(0.0031308));
}

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(position.xy - overlay.origin);
    var c = textureLoad(text, p, 0);
    if (overlay.encode_srgb == 1u) {
        c = vec4<f32>(linear_to_srgb(c.rgb), c.a);
    }
    return c;
}
