// SSPR resolve (seed 002): every reflector pixel reads the projection hash of its plane's
// layer, decodes the source pixel (x = low 16 bits, y = high 16 bits) and takes its
// colour; 0 is an empty hash (no reflection, alpha 0). No temporal fill.
// Needs common.wgsl.

// Workgroup edge (threads per side); set from Rust.
override GROUP_EDGE: u32 = 8u;

@group(0) @binding(1) var<storage, read> planes: array<ReflectorPlane>;
@group(0) @binding(2) var reflector_tex: texture_2d<u32>;
@group(0) @binding(3) var color_tex: texture_2d<f32>;
@group(0) @binding(4) var<storage, read> hash: array<u32>;
@group(0) @binding(5) var output_tex: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(GROUP_EDGE, GROUP_EDGE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let pixel = gid.xy;
    if (any(pixel >= frame.size)) {
        return;
    }
    var out = vec4<f32>(0.0);
    let id = textureLoad(reflector_tex, pixel, 0).x;
    if (id != 0u && id <= frame.reflector_count) {
        let layer = planes[id - 1u].layer;
        if (layer < frame.layer_count) {
            let h = hash[layer * frame.size.x * frame.size.y + pixel.y * frame.size.x + pixel.x];
            if (h != 0u) {
                let source = vec2<u32>(h & 0xffffu, h >> 16u);
                out = vec4<f32>(textureLoad(color_tex, source, 0).rgb, 1.0);
            }
        }
    }
    textureStore(output_tex, pixel, out);
}
