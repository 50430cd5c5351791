//! Pixel-projected reflections from `ppr-runtime` as a [`ReflectionTechnique`].

use ppr_format::ReflectorSet;
use ppr_runtime::{Camera, FrameInputs, ReflectionRenderer, ReflectionSettings, RendererDesc};

use crate::technique::{ReflectionInputs, ReflectionTechnique};

/// The runtime's [`ReflectionRenderer`] driven by the testbed.
pub struct PprTechnique {
    renderer: ReflectionRenderer,
}

impl PprTechnique {
    /// A renderer for `reflectors` with the given reflection-pass steps (timestamps on
    /// where the device has them).
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        reflectors: &ReflectorSet,
        settings: ReflectionSettings,
    ) -> Self {
        let mut renderer = ReflectionRenderer::new(device, queue, &RendererDesc::default());
        renderer.set_reflectors(reflectors);
        renderer.settings = settings;
        Self { renderer }
    }

    /// The runtime renderer (for its plan, intermediate buffer and settings).
    pub fn renderer(&mut self) -> &mut ReflectionRenderer {
        &mut self.renderer
    }
}

impl ReflectionTechnique for PprTechnique {
    fn name(&self) -> String {
        let s = self.renderer.settings;
        let on = |b: bool| if b { "on" } else { "off" };
        format!(
            "PPR (holes {}, filtering {}, anti-bleeding {})",
            on(s.holes),
            on(s.filtering),
            on(s.anti_bleeding)
        )
    }

    fn prepare(
        &mut self,
        _device: &wgpu::Device,
        _queue: &wgpu::Queue,
        camera: &Camera,
        size: [u32; 2],
    ) -> String {
        self.renderer.prepare(camera, size).to_string()
    }

    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, inputs: &ReflectionInputs<'_>) {
        let frame = FrameInputs {
            normals: inputs.normal,
            ..FrameInputs::new(inputs.color, inputs.depth, inputs.output)
        };
        self.renderer.encode(encoder, &frame);
    }

    fn timings(&mut self, _device: &wgpu::Device) -> Option<Vec<(String, f64)>> {
        let t = self.renderer.read_timings()?;
        Some(t.passes().iter().filter_map(|(name, ms)| ms.map(|ms| ((*name).to_owned(), ms))).collect())
    }
}
