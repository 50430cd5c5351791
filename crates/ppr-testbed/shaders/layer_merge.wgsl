// Layer merge: the runtime's layer output (glass and water reflections) over its main
// reflection output, into the technique's output, so that the testbed compares one
// reflection buffer per pixel (the reference renders glass and water as reflectors of
// their own plane).

@group(0) @binding(0) var main_tex: texture_2d<f32>;
@group(0) @binding(1) var layer_tex: texture_2d<f32>;
@group(0) @binding(2) var output: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(16, 16)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = textureDimensions(output);
    if (any(gid.xy >= size)) {
        return;
    }
    let p = vec2<i32>(gid.xy);
    let layer = textureLoad(layer_tex, p, 0);
    // A layer reflection (alpha: its confidence, > 0 wherever one was found) replaces the main one.
    textureStore(output, p, select(textureLoad(main_tex, p, 0), layer, layer.a > 0.0));
}
