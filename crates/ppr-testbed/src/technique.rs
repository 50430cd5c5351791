//! The interface between the testbed and a screen-space reflection technique under test
//! (PPR from `ppr-runtime`, the baselines): colour and depth in, reflection buffer out.

use ppr_runtime::Camera;

/// Format of a technique's output: linear reflection colour, alpha 1 where one was found.
pub const REFLECTION_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Textures a technique reads and writes in one frame (all the same size).
pub struct ReflectionInputs<'a> {
    /// Linear HDR scene colour (`Rgba16Float`, texture binding).
    pub color: &'a wgpu::TextureView,
    /// Scene depth (`Depth32Float`, depth-only view, texture binding).
    pub depth: &'a wgpu::TextureView,
    /// Where the reflection goes ([`REFLECTION_FORMAT`], storage binding).
    pub output: &'a wgpu::TextureView,
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

    /// GPU time of the last frame's passes, if the device measures it (after submission).
    fn timings(&mut self, device: &wgpu::Device) -> Option<String>;
}
