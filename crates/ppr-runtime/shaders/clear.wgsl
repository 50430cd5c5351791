// Clear pass: fills the intermediate buffer (or the atlas) with PPR_CLEAR_VALUE, four values
// per thread.

@group(0) @binding(0) var<storage, read_write> intermediate: array<vec4<u32>>;

@compute @workgroup_size(256)
fn clear_all(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = gid.x + gid.y * groups.x * 256u;
    if (i < arrayLength(&intermediate)) {
        intermediate[i] = vec4<u32>(PPR_CLEAR_VALUE);
    }
}
