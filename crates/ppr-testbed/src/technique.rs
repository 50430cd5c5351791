//! The interface between the testbed and a screen-space reflection technique under test
//! (PPR from `ppr-runtime`, the baselines): colour and depth in, reflection buffer out.

use ppr_runtime::Camera;

use crate::gbuffer_targets::GBuffer;

/// Format of a technique's output: linear reflection colour, alpha > 0 where one was found
/// (PPR: its confidence in [0, 1]; the baselines: 1).
pub const REFLECTION_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Textures a technique reads and writes in one frame (all the same size).
///
/// Colour, depth and output are what every technique gets; the G-buffer views are
/// optional extras for techniques that need a surface normal or the reflector under a
/// pixel (the ray-marched baselines). Build with [`ReflectionInputs::new`] or, with the
/// extras, [`ReflectionInputs::from_gbuffer`].
pub struct ReflectionInputs<'a> {
    /// Linear HDR scene colour (`Rgba16Float`, texture binding).
    pub color: &'a wgpu::TextureView,
    /// Scene depth (`Depth32Float`, depth-only view, texture binding).
    pub depth: &'a wgpu::TextureView,
    /// Where the reflection goes ([`REFLECTION_FORMAT`], storage binding).
    pub output: &'a wgpu::TextureView,
    /// World normal ([`crate::gbuffer_targets::NORMAL_FORMAT`], texture binding), if the
    /// caller has one.
    pub normal: Option<&'a wgpu::TextureView>,
    /// Reflector id ([`crate::gbuffer_targets::REFLECTOR_ID_FORMAT`]: 0 none, `i + 1` the
    /// set's reflector `i`; texture binding), if the caller has one.
    pub reflector_id: Option<&'a wgpu::TextureView>,
}

impl<'a> ReflectionInputs<'a> {
    /// Colour, depth and output only (no G-buffer extras).
    pub fn new(
        color: &'a wgpu::TextureView,
        depth: &'a wgpu::TextureView,
        output: &'a wgpu::TextureView,
    ) -> Self {
        Self { color, depth, output, normal: None, reflector_id: None }
    }

    /// Every input from the testbed's main `gbuffer`, extras included.
    pub fn from_gbuffer(gbuffer: &'a GBuffer, output: &'a wgpu::TextureView) -> Self {
        Self {
            color: &gbuffer.color.view,
            depth: &gbuffer.depth.view,
            output,
            normal: Some(&gbuffer.normal.view),
            reflector_id: Some(&gbuffer.reflector_id.view),
        }
    }
}

/// A reflection technique the testbed can run and measure.
pub trait ReflectionTechnique {
    /// A short name for reports (`"PPR"`, `"SSR (Hi-Z)"`).
    fn name(&self) -> String;

    /// Uploads what the frame seen by `camera` at `size` needs; returns a description of
    /// the frame's plan for logs.
    fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        camera: &Camera,
        size: [u32; 2],
    ) -> String;

    /// Records the technique's passes (after the G-buffer pass in the same encoder).
    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, inputs: &ReflectionInputs<'_>);

    /// GPU time of the last frame's passes after submission: `(pass name, milliseconds)`
    /// in recording order, one entry per pass that ran (a technique with a separate setup
    /// such as a Hi-Z build gives it its own entry). `None` when the device does not
    /// measure time.
    fn timings(&mut self, device: &wgpu::Device) -> Option<Vec<(String, f64)>>;

    /// Records none of its own pass timestamps (nor their resolve) from now on, and
    /// [`Self::timings`] gives `None`: for a caller that times everything the technique
    /// records between timestamps of its own (`ppr-bench`'s `timing=frame`), whose span
    /// would otherwise hold the technique's timestamp writes and resolve as well.
    fn stop_pass_timing(&mut self);
}

/// `"name 0.123 ms, ..., total 0.456 ms"` for logs.
pub fn format_timings(timings: &[(String, f64)]) -> String {
    let mut s = String::new();
    for (name, ms) in timings {
        s.push_str(&format!("{name} {ms:.3} ms, "));
    }
    let total: f64 = timings.iter().map(|(_, ms)| ms).sum();
    s.push_str(&format!("total {total:.3} ms"));
    s
}
