//! The untimed renders a breakdown needs: one PPR renderer switched between raw, hole
//! filling, full without the border fade and full, on the level renderer's current frame,
//! with raw PPR's intermediate buffer decoded into source pixels.

use glam::IVec2;
use image::Rgba32FImage;
use ppr_format::ReflectorSet;
use ppr_runtime::encoding::decode;
use ppr_runtime::{Camera, Choice, PlanParams, ReflectionSettings};
use ppr_testbed::gbuffer_targets::Target;
use ppr_testbed::readback::read_rgba_f32;
use ppr_testbed::technique::REFLECTION_FORMAT;
use ppr_testbed::{LevelRenderer, ReflectionInputs};

use crate::buffer_readback::read_buffer_u32;
use crate::error::BenchError;
use crate::ppr_runner::PprRunner;
use crate::technique::{BenchFrame, BenchTechnique};
use crate::technique_spec::{TechniqueSpec, ppr_settings};

/// Full PPR's frame and the steps before it, read back.
pub struct PprVariants {
    /// Raw PPR (no hole filling, filtering or fade).
    pub raw: Rgba32FImage,
    /// Per pixel (row-major), the source pixel of raw PPR's reflection; `None` without data.
    pub raw_sources: Vec<Option<IVec2>>,
    /// PPR with hole filling (and the spec's replace-far rule), no fade.
    pub holes: Rgba32FImage,
    /// Full PPR without the border fade.
    pub unfaded: Rgba32FImage,
    /// Full PPR as the spec asks.
    pub full: Rgba32FImage,
    /// Whether the plan had the parallel-shape rule on.
    pub parallel_rule: bool,
    /// With the rule on: raw PPR with it off, and its sources.
    pub without_rule: Option<(Rgba32FImage, Vec<Option<IVec2>>)>,
}

/// Renders [`PprVariants`] for one full-PPR spec, reusing its pipelines across frames.
pub struct CauseRunner {
    runner: PprRunner,
    settings: ReflectionSettings,
    params: PlanParams,
    output: Option<Target>,
}

impl CauseRunner {
    /// A runner for `spec` when it is full PPR (`ppr`, any settings); `None` otherwise.
    ///
    /// # Errors
    /// The spec's settings do not parse, or the set is invalid.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        reflectors: &ReflectorSet,
        spec: &TechniqueSpec,
        base: PlanParams,
    ) -> Result<Option<Self>, BenchError> {
        // Fed-back frames (`bounces=`) are scored against a deeper reference than the
        // breakdown's variants, which run one frame: no breakdown for them.
        if spec.name != "ppr" || crate::technique_spec::reference_bounces(spec)? > 1 {
            return Ok(None);
        }
        let Some((settings, params)) = ppr_settings(spec, base)? else { return Ok(None) };
        let runner = PprRunner::new(device, queue, reflectors, spec.label(), settings, params)?;
        Ok(Some(Self { runner, settings, params, output: None }))
    }

    /// Renders the variants of the frame `level` holds (prepared for `camera` at `size`,
    /// G-buffer encoded and submitted).
    ///
    /// # Errors
    /// A readback fails.
    pub fn render(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        level: &LevelRenderer,
        camera: &Camera,
        size: [u32; 2],
    ) -> Result<PprVariants, BenchError> {
        if self.output.as_ref().is_none_or(|t| [t.texture.width(), t.texture.height()] != size) {
            let usage = wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST;
            self.output = Some(Target::new(device, "error-cause output", size, REFLECTION_FORMAT, usage));
        }
        let unfaded = ReflectionSettings { border_fade: 0.0, ..self.settings };
        let raw = ReflectionSettings {
            holes: false,
            replace_far_reflections: false,
            filtering: false,
            anti_bleeding: false,
            ..unfaded
        };
        let holes = ReflectionSettings {
            holes: true,
            replace_far_reflections: self.settings.replace_far_reflections,
            ..raw
        };
        let (raw_image, raw_sources, parallel_rule) =
            self.frame(device, queue, level, camera, size, raw, self.params, true)?;
        let without_rule = if parallel_rule {
            let params = PlanParams { parallel_rule: Choice::Off, ..self.params };
            let (img, src, _) = self.frame(device, queue, level, camera, size, raw, params, true)?;
            Some((img, src))
        } else {
            None
        };
        let params = self.params;
        let holes = self.frame(device, queue, level, camera, size, holes, params, false)?.0;
        let unfaded = self.frame(device, queue, level, camera, size, unfaded, params, false)?.0;
        let full = self.frame(device, queue, level, camera, size, self.settings, params, false)?.0;
        self.runner.renderer().settings = self.settings;
        Ok(PprVariants { raw: raw_image, raw_sources, holes, unfaded, full, parallel_rule, without_rule })
    }

    /// One frame with `settings` and `params`: the output, the decoded sources when asked,
    /// and whether the plan had the parallel rule on.
    #[allow(clippy::too_many_arguments)]
    fn frame(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        level: &LevelRenderer,
        camera: &Camera,
        size: [u32; 2],
        settings: ReflectionSettings,
        params: PlanParams,
        sources: bool,
    ) -> Result<(Rgba32FImage, Vec<Option<IVec2>>, bool), BenchError> {
        let output = self.output.as_ref().expect("created by render");
        // Cleared to "no reflection": with indirect dispatch PPR writes only active tiles.
        let zeros = vec![0u8; (size[0] * size[1]) as usize * 8];
        queue.write_texture(
            output.texture.as_image_copy(),
            &zeros,
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(size[0] * 8), rows_per_image: None },
            output.texture.size(),
        );
        let renderer = self.runner.renderer();
        renderer.settings = settings;
        renderer.plan_params = params;
        self.runner.prepare(device, queue, camera, size);
        let frame =
            BenchFrame { level, reflection: ReflectionInputs::from_gbuffer(level.gbuffer(), &output.view) };
        let mut encoder = device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("error-cause frame") });
        self.runner.encode(&mut encoder, &frame);
        queue.submit([encoder.finish()]);
        let image = read_rgba_f32(device, queue, &output.texture)?;
        let renderer = self.runner.renderer();
        let (layout, rule) = match renderer.plan() {
            Some(p) => (p.encoding, p.parallel_rule),
            None => return Ok((image, vec![None; (size[0] * size[1]) as usize], false)),
        };
        let mut decoded = Vec::new();
        if sources && let Some(buffer) = renderer.intermediate_buffer() {
            let words = read_buffer_u32(device, queue, buffer)?;
            let w = size[0] as usize;
            decoded = (0..(size[0] * size[1]) as usize)
                .map(|i| {
                    // Only pixels with data: with indirect dispatch other tiles are stale.
                    let (x, y) = ((i % w) as u32, (i / w) as u32);
                    if image.get_pixel(x, y).0[3] <= 0.0 {
                        return None;
                    }
                    let d = decode(*words.get(i)?, &layout)?;
                    Some(IVec2::new(x as i32, y as i32) - d.whole_offset().round().as_ivec2())
                })
                .collect();
        }
        Ok((image, decoded, rule))
    }
}
