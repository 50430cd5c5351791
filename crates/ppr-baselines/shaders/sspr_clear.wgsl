// SSPR clear: zeroes the projection hash buffer (every layer) before the projection pass;
// 0 is the empty hash. Stands alone (no shared module).

// Workgroup size (threads); set from Rust.
override GROUP_SIZE: u32 = 256u;

struct ClearParams {
    // u32 values to clear.
    count: u32,
    // Threads per row of the dispatch grid (rows of 65535 workgroups).
    row: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var<uniform> params: ClearParams;
@group(0) @binding(1) var<storage, read_write> hash: array<u32>;

@compute @workgroup_size(GROUP_SIZE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x + gid.y * params.row;
    if (i < params.count) {
        hash[i] = 0u;
    }
}
