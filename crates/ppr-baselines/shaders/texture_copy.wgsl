// Copies a reflection rendered elsewhere (the exact planar reflection's resolve target)
// into a technique's storage output, texel for texel. Stands alone (no shared module).

// Workgroup edge (threads per side); set from Rust.
override GROUP_EDGE: u32 = 8u;

@group(0) @binding(0) var source_tex: texture_2d<f32>;
@group(0) @binding(1) var output_tex: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(GROUP_EDGE, GROUP_EDGE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = textureDimensions(output_tex);
    if (any(gid.xy >= size)) {
        return;
    }
    textureStore(output_tex, gid.xy, textureLoad(source_tex, gid.xy, 0));
}
