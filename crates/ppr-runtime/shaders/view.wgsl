// View helpers for passes that declare `frame: FrameUniforms`: pixel <-> camera-relative
// position, and which depths count as rendered.

// The homogeneous camera-relative point of a pixel centre at a depth (ppr_unproject
// divides its xyz by its w).
fn ppr_unproject_homogeneous(pixel: vec2<f32>, depth: f32) -> vec4<f32> {
    let uv = pixel * frame.resolution.zw;
    return frame.rel_from_clip * vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, depth, 1.0);
}

// Camera-relative position of a pixel centre at a depth.
fn ppr_unproject(pixel: vec2<f32>, depth: f32) -> vec3<f32> {
    let h = ppr_unproject_homogeneous(pixel, depth);
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

// How far from a plane a reconstructed point may lie and still be on it: the larger of the
// f32 error of the unprojection (frame.plane_epsilon times the distance) and the distance
// along the view ray that four depth-buffer steps (ulps) at this depth cover. With
// standard Z the second dominates far from the camera (the depth buffer's resolution falls
// with distance squared), so pixels of a reflector within depth error of its own plane are
// never reflected by it (they would land on themselves). The distance is the
// unprojection's derivative in depth times the four steps: with `h` the homogeneous point
// (`p = h.xyz / h.w`) and `c` the inverse projection's depth column, `dp / ddepth =
// (c.xyz - p * c.w) / h.w` (a second unprojection four steps away, what this replaced,
// gave the same to within the steps' curvature for twice the arithmetic).
fn ppr_on_plane_tolerance(depth: f32, h_w: f32, p: vec3<f32>) -> f32 {
    let ulps = 4.0 * 1.1920929e-7 * max(abs(depth), 1.0e-30);
    let c = frame.rel_from_clip[2];
    var along = length(c.xyz - p * c.w) * (ulps / abs(h_w));
    if (!ppr_is_finite(along)) {
        along = 0.0;
    }
    return max(frame.plane_epsilon * length(p), along) + 1.0e-30;
}
