// Later bounces of the exact reference (testbed): a deeper mirrored view composited over
// its parent view's colour where the parent shows the deeper view's plane. The blend
// (constant = the composite's reflectivity) makes it mix(parent, child, reflectivity), the
// composite pass's formula with the reference's alpha of 1.

struct Bounce {
    plane: vec4<u32>,  // x: plane group the child view is seen through
}

@group(0) @binding(0) var<uniform> u: Bounce;
@group(0) @binding(1) var<storage, read> plane_of_reflector: array<u32>;
@group(0) @binding(2) var parent_ids: texture_2d<u32>;
@group(0) @binding(3) var child_color: texture_2d<f32>;

// `vs_main`: the full-screen triangle of ppr-scene-gpu's fullscreen_triangle.wgsl.

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let px = vec2<i32>(frag.xy);
    let id = textureLoad(parent_ids, px, 0).x;
    if (id == 0u) {
        discard;
    }
    if (plane_of_reflector[id - 1u] != u.plane.x) {
        discard;
    }
    return vec4<f32>(textureLoad(child_color, px, 0).rgb, 1.0);
}
