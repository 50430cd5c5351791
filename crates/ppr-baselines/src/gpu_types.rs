//! `#[repr(C)]` mirrors of the WGSL structs in `crates/ppr-baselines/shaders/common.wgsl`, sizes asserted.

use glam::{DMat4, DVec4};
use ppr_runtime::Camera;

/// Layer of a reflector whose plane has no SSPR hash layer (`BASELINE_NO_LAYER` in WGSL).
pub const NO_LAYER: u32 = u32::MAX;

/// Pixels closer to a reflector's plane than this fraction of their camera distance lie on
/// it (the SSPR projection skips them: a plane does not reflect itself). The same value as
/// `ppr-runtime`'s plane epsilon, for the same reason (f32 depth precision).
pub const PLANE_EPSILON: f32 = ppr_runtime::renderer::PLANE_EPSILON;

/// `BaselineFrame` of `common.wgsl`: the camera and viewport of one frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct BaselineFrame {
    /// Clip from camera-relative world.
    pub clip_from_rel: [[f32; 4]; 4],
    /// Camera-relative world from clip (inverted in f64).
    pub rel_from_clip: [[f32; 4]; 4],
    /// Width, height, 1 / width, 1 / height.
    pub resolution: [f32; 4],
    /// xyz: the camera's forward direction; w: the near-plane distance.
    pub forward_near: [f32; 4],
    /// Width and height in pixels.
    pub size: [u32; 2],
    /// Depth of a pixel where nothing was drawn.
    pub far_depth: f32,
    /// `d = depth_a + depth_b / w` ties device depth `d` to linear view depth `w`.
    pub depth_a: f32,
    /// See [`Self::depth_a`].
    pub depth_b: f32,
    /// See [`PLANE_EPSILON`].
    pub plane_epsilon: f32,
    /// Reflectors in the plane table.
    pub reflector_count: u32,
    /// SSPR hash layers this frame.
    pub layer_count: u32,
}
const _: () = assert!(size_of::<BaselineFrame>() == 192);

impl BaselineFrame {
    /// The frame seen by `camera` at `size`, with `reflector_count` reflectors in the plane
    /// table and `layer_count` SSPR layers.
    pub fn new(camera: &Camera, size: [u32; 2], reflector_count: u32, layer_count: u32) -> Self {
        let [w, h] = [size[0].max(1), size[1].max(1)];
        let aspect = w as f32 / h as f32;
        let clip_from_rel = camera.clip_from_relative(aspect);
        // Invert in f64: the reversed-Z and infinite projections are badly conditioned.
        let rel_from_clip = clip_from_rel.as_dmat4().inverse();
        let (depth_a, depth_b) = depth_linearisation(camera.projection.clip_from_view(aspect).as_dmat4());
        let forward = camera.forward();
        Self {
            clip_from_rel: clip_from_rel.to_cols_array_2d(),
            rel_from_clip: rel_from_clip.as_mat4().to_cols_array_2d(),
            resolution: [w as f32, h as f32, 1.0 / w as f32, 1.0 / h as f32],
            forward_near: [forward.x, forward.y, forward.z, camera.projection.near],
            size: [w, h],
            far_depth: camera.projection.far_depth(),
            depth_a: depth_a as f32,
            depth_b: depth_b as f32,
            plane_epsilon: PLANE_EPSILON,
            reflector_count,
            layer_count,
        }
    }
}

/// `(a, b)` with device depth `d = a + b / w` for linear view depth `w` (clip w), for any
/// perspective `clip_from_view` (standard, reversed, finite or infinite far plane).
pub fn depth_linearisation(clip_from_view: DMat4) -> (f64, f64) {
    let depth_at = |w: f64| {
        let c = clip_from_view * DVec4::new(0.0, 0.0, -w, 1.0);
        c.z / c.w
    };
    let (d1, d2) = (depth_at(1.0), depth_at(2.0));
    let b = 2.0 * (d1 - d2);
    (d1 - b, b)
}

/// `ReflectorPlane` of `common.wgsl`: one reflector's plane, camera-relative.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuReflectorPlane {
    /// Unit normal (the reflecting side).
    pub normal: [f32; 3],
    /// `dot(normal, point on the plane)` for camera-relative points, computed in f64.
    pub offset: f32,
    /// SSPR hash layer of the plane, or [`NO_LAYER`].
    pub layer: u32,
    /// Padding.
    pub _pad: [u32; 3],
}
const _: () = assert!(size_of::<GpuReflectorPlane>() == 32);

/// `SsrParams` of `ssr_march.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SsrUniform {
    /// Pixels per step (≥ 1).
    pub stride: f32,
    /// Most steps (0: until the ray leaves the screen).
    pub max_steps: u32,
    /// Bisection steps.
    pub refine_steps: u32,
    /// Metres of view depth.
    pub thickness: f32,
    /// Metres.
    pub max_distance: f32,
    /// Padding.
    pub _pad: [u32; 3],
}
const _: () = assert!(size_of::<SsrUniform>() == 32);

/// `GlossyBlurParams` of `ssr_glossy_blur.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GlossyBlurUniform {
    /// Blur radius at the hit in units of `alpha × hit distance`.
    pub spread: f32,
    /// Largest radius, pixels.
    pub max_radius: f32,
    /// Gather taps besides the centre.
    pub samples: u32,
    /// Padding.
    pub _pad: u32,
}
const _: () = assert!(size_of::<GlossyBlurUniform>() == 16);

/// `HiZParams` of `hiz_trace.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct HiZUniform {
    /// Most cell visits per ray.
    pub max_iterations: u32,
    /// Highest level climbed to (below the pyramid's level count).
    pub top_level: u32,
    /// Metres of view depth (`f32::MAX`: no rejection).
    pub thickness: f32,
    /// Metres.
    pub max_distance: f32,
}
const _: () = assert!(size_of::<HiZUniform>() == 16);

/// `SsprParams` of `sspr_project.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SsprUniform {
    /// 1: edge stretch on.
    pub stretch: u32,
    /// |NDC x| where the stretch starts.
    pub stretch_threshold: f32,
    /// Stretch per metre.
    pub stretch_intensity: f32,
    /// Padding.
    pub _pad: u32,
}
const _: () = assert!(size_of::<SsprUniform>() == 16);

/// `ClearParams` of `sspr_clear.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ClearUniform {
    /// Values to clear.
    pub count: u32,
    /// Threads per row of the dispatch grid.
    pub row: u32,
    /// Padding.
    pub _pad: [u32; 2],
}
const _: () = assert!(size_of::<ClearUniform>() == 16);

#[cfg(test)]
mod tests {
    use glam::{DVec3, Vec3};
    use ppr_runtime::{DepthMode, Projection};

    use super::*;

    /// The linearisation inverts every projection the runtime supports.
    #[test]
    fn linearisation_recovers_view_depth() {
        let base = Projection::default();
        for projection in [
            base,
            Projection { depth: DepthMode::Reversed, ..base },
            Projection { far: None, ..base },
            Projection { far: None, depth: DepthMode::Reversed, ..base },
        ] {
            let camera = Camera::look_at(DVec3::ZERO, DVec3::NEG_Z, Vec3::Y, projection);
            let p = camera.projection.clip_from_view(1.5).as_dmat4();
            let (a, b) = depth_linearisation(p);
            for w in [0.06, 1.0, 7.5, 80.0, 400.0] {
                let c = p * DVec4::new(0.0, 0.0, -w, 1.0);
                let d = c.z / c.w;
                let back = b / (d - a);
                assert!((back - w).abs() < 1e-9 * w.max(1.0), "{projection:?}: w {w} -> d {d} -> {back}");
            }
        }
    }
}
