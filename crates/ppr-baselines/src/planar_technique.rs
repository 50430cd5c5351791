//! The exact planar reflection as a [`ReflectionTechnique`]: the scene rendered again from
//! the mirrored camera of every visible reflector plane (the testbed's
//! [`ppr_testbed::MirrorReference`]), timed like the other techniques. The quality
//! ceiling, and a competitor on cost.

use ppr_format::ReflectorSet;
use ppr_runtime::Camera;
use ppr_testbed::{Level, LevelRenderer, ReflectionInputs, ReflectionTechnique, RenderSettings};

use crate::passes::TextureCopyPass;
use crate::timestamps::PassTimer;

/// Names of the timed passes, in order.
const PASSES: [&str; 2] = ["mirrored views", "copy to output"];

/// Planar reflections by re-rendering the level from mirrored cameras.
///
/// It owns a [`LevelRenderer`] of the level: each frame it records that renderer's main
/// G-buffer (untimed: the same frame the caller already rendered; the reference's resolve
/// reads it), then, timed as `mirrored views`, one mirrored G-buffer raster of the level
/// and one resolve into the main view per visible plane (the resolve also classifies
/// each pixel's reflected point, a little more work than a game's would do), then, timed
/// as `copy to output`, a copy into the output. It ignores the caller's colour and depth.
pub struct PlanarReflectionTechnique {
    device: wgpu::Device,
    renderer: LevelRenderer,
    copy: TextureCopyPass,
    timer: Option<PassTimer>,
    size: Option<[u32; 2]>,
}

impl PlanarReflectionTechnique {
    /// Uploads `level` with `reflectors`, rendered with `settings` (use the caller's, so
    /// that the reflection matches its frame).
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        level: &Level,
        reflectors: &ReflectorSet,
        settings: RenderSettings,
    ) -> Self {
        let mut renderer = LevelRenderer::new(device, queue, level, reflectors);
        renderer.settings = settings;
        Self {
            device: device.clone(),
            renderer,
            copy: TextureCopyPass::new(device),
            timer: PassTimer::new(device, queue, "planar reflection", 2),
            size: None,
        }
    }

    /// The level renderer (its settings, planes and targets).
    pub fn renderer(&mut self) -> &mut LevelRenderer {
        &mut self.renderer
    }
}

impl ReflectionTechnique for PlanarReflectionTechnique {
    fn name(&self) -> String {
        "Planar reflection (mirrored re-render)".to_owned()
    }

    fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        camera: &Camera,
        size: [u32; 2],
    ) -> String {
        let summary = self.renderer.prepare(device, queue, camera, size);
        self.size = Some(summary.size);
        format!("{} of {} planes re-rendered", summary.rendered_planes.len(), summary.planes)
    }

    /// # Panics
    /// Without a prepared frame.
    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, inputs: &ReflectionInputs<'_>) {
        let size = self.size.expect("PlanarReflectionTechnique::prepare before encode");
        self.renderer.encode_gbuffer(encoder);
        if let Some(t) = &self.timer {
            drop(encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("mirrored views: begin"),
                timestamp_writes: Some(t.marker(0, true)),
            }));
        }
        self.renderer.encode_reference(encoder);
        if let Some(t) = &self.timer {
            drop(encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("mirrored views: end"),
                timestamp_writes: Some(t.marker(0, false)),
            }));
        }
        let bind_group =
            self.copy.bind_group(&self.device, &self.renderer.reference().color.view, inputs.output);
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(PASSES[1]),
                timestamp_writes: self.timer.as_ref().map(|t| t.pass(1)),
            });
            self.copy.encode(&mut pass, &bind_group, size);
        }
        if let Some(t) = &self.timer {
            t.resolve(encoder);
        }
    }

    fn timings(&mut self, device: &wgpu::Device) -> Option<Vec<(String, f64)>> {
        self.timer.as_ref()?.read(device, &PASSES.map(Some)).ok()
    }

    fn stop_pass_timing(&mut self) {
        self.timer = None;
    }
}
