// View helpers for passes that declare `frame: FrameUniforms`: pixel <-> camera-relative
// position, and which depths count as rendered.

// Camera-relative position of a pixel centre at a depth.
fn ppr_unproject(pixel: vec2<f32>, depth: f32) -> vec3<f32> {
    let uv = pixel * frame.resolution.zw;
    let h = frame.rel_from_clip * vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, depth, 1.0);
    return h.xyz / h.w;
}

// Pixel coordinates of a camera-relative point, and whether it is in front of the camera.
fn ppr_project(p: vec3<f32>) -> vec3<f32> {
    let clip = frame.clip_from_rel * vec4<f32>(p, 1.0);
    let ndc = clip.xy / clip.w;
    return vec3<f32>((ndc * vec2<f32>(0.5, -0.5) + 0.5) * frame.resolution.xy, select(0.0, 1.0, clip.w > 0.0));
}

// Whether a depth value is a rendered surface: finite, in [0, 1], not the far plane.
fn ppr_is_valid_depth(depth: f32) -> bool {
    return ppr_is_finite(depth) && depth >= 0.0 && depth <= 1.0 && depth != frame.far_depth;
}
