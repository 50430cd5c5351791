// Clear pass: fills the intermediate buffer with PPR_CLEAR_VALUE.
// `clear_all`: the whole buffer, four values per thread.
// `clear_tiles`: only the active tiles (indirect dispatch, one workgroup per tile).


@group(0) @binding(0) var<storage, read_write> intermediate: array<vec4<u32>>;
@group(0) @binding(1) var<uniform> frame: FrameUniforms;
@group(0) @binding(2) var<storage, read> active_tiles: ActiveTileList;

@compute @workgroup_size(256)
fn clear_all(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = gid.x + gid.y * groups.x * 256u;
    if (i < arrayLength(&intermediate)) {
        intermediate[i] = vec4<u32>(PPR_CLEAR_VALUE);
    }
}

// One workgroup per active tile, one thread per pixel.
@compute @workgroup_size(16, 16)
fn clear_tiles(@builtin(local_invocation_id) lid: vec3<u32>, @builtin(workgroup_id) wid: vec3<u32>) {
    let slot = ppr_active_slot(wid);
    if (slot >= active_tiles.count) {
        return;
    }
    let tiles_x = (frame.size.x + 15u) / 16u;
    let tile = active_tiles.tiles[slot];
    let px = vec2<u32>(tile % tiles_x, tile / tiles_x) * 16u + lid.xy;
    if (all(px < frame.size)) {
        let i = px.x + px.y * frame.size.x;
        // Write one u32 lane of a vec4: the buffer is viewed as vec4<u32>.
        intermediate[i / 4u][i % 4u] = PPR_CLEAR_VALUE;
    }
}
