//! Pixel-projected reflections from `ppr-runtime` as a [`ReflectionTechnique`].

use ppr_format::{FormatError, ReflectorSet, ValidatedSet};
use ppr_runtime::{Camera, FrameInputs, ReflectionRenderer, ReflectionSettings, RendererDesc};
use ppr_scene_gpu::layout_entries::unfilterable_texture_entry;

use crate::composite::CompositeParams;
use crate::gbuffer_targets::Target;
use crate::previous_frame_feed::{FeedInputs, PREVIOUS_FRAME_COPY, PreviousFrameFeed};
use crate::target_clear::clear_target;
use crate::technique::{ReflectionInputs, ReflectionTechnique};

/// The runtime's [`ReflectionRenderer`] driven by the testbed. Glass and water
/// reflections (the runtime's layer output) are merged over the main reflection, so the
/// technique's output holds one reflection per pixel like the reference.
pub struct PprTechnique {
    renderer: ReflectionRenderer,
    device: wgpu::Device,
    merge: LayerMerge,
    /// The runtime's main and layer outputs when the frame has layers, sized to it.
    layer_targets: Option<LayerTargets>,
    /// The output size of the last `prepare` (the plan's viewport is smaller in a reduced
    /// resolution tier).
    size: [u32; 2],
    /// Frames of the same camera per [`ReflectionTechnique::encode`] (see [`Self::set_bounces`]).
    bounces: u32,
    /// The previous frame's composite, when `bounces > 1`.
    feed: Option<PreviousFrameFeed>,
    /// Whether the feed's copy is timed ([`ReflectionTechnique::stop_pass_timing`]).
    feed_timed: bool,
    queue: wgpu::Queue,
}

/// Textures the runtime writes when a frame has glass or water layers.
struct LayerTargets {
    size: [u32; 2],
    main: wgpu::TextureView,
    layer: wgpu::TextureView,
}

/// The compute pass that copies layer reflections over the main output.
struct LayerMerge {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl LayerMerge {
    fn new(device: &wgpu::Device) -> Self {
        let texture = |binding| unfilterable_texture_entry(binding, wgpu::ShaderStages::COMPUTE);
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("testbed layer merge"),
            entries: &[
                texture(0),
                texture(1),
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format: ppr_runtime::OUTPUT_FORMAT,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
            ],
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("testbed layer merge"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../shaders/layer_merge.wgsl").into()),
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("testbed layer merge"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("testbed layer merge"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        Self { pipeline, layout }
    }

    fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        targets: &LayerTargets,
        output: &wgpu::TextureView,
    ) {
        let [w, h] = targets.size;
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("testbed layer merge"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&targets.main),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&targets.layer),
                },
                wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::TextureView(output) },
            ],
        });
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("testbed layer merge"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(w.div_ceil(16), h.div_ceil(16), 1);
    }
}

impl PprTechnique {
    /// A renderer for `reflectors` with the given reflection-pass steps (timestamps on
    /// where the device has them).
    ///
    /// # Errors
    /// The runtime refuses a set that breaks an invariant of the format.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        reflectors: &ReflectorSet,
        settings: ReflectionSettings,
    ) -> Result<Self, FormatError> {
        let mut renderer = ReflectionRenderer::new(device, queue, &RendererDesc::default());
        renderer.set_reflectors(&ValidatedSet::new(reflectors.clone())?);
        renderer.settings = settings;
        Ok(Self {
            renderer,
            device: device.clone(),
            merge: LayerMerge::new(device),
            layer_targets: None,
            size: [1, 1],
            bounces: 1,
            feed: None,
            feed_timed: true,
            queue: queue.clone(),
        })
    }

    /// The main and layer targets for a frame of `size`, (re)created when it changes.
    fn layer_targets(&mut self, size: [u32; 2]) -> &LayerTargets {
        if self.layer_targets.as_ref().is_none_or(|t| t.size != size) {
            let usage = wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::RENDER_ATTACHMENT;
            let target =
                |label| Target::new(&self.device, label, size, ppr_runtime::OUTPUT_FORMAT, usage).view;
            let (main, layer) = (target("testbed ppr main output"), target("testbed ppr layer output"));
            self.layer_targets = Some(LayerTargets { size, main, layer });
        }
        self.layer_targets.as_ref().expect("created above")
    }

    /// Renders `bounces` frames of the same camera per encode, each after the first reading
    /// the previous frame's composited image (scene colour with that frame's reflection
    /// composited on reflector pixels, [`CompositeParams::default`]) as its colour input:
    /// a mirror seen in a mirror gains one bounce per frame. 1 (the default) is one
    /// ordinary frame. Needs the reflector id in the inputs; without it one frame is run.
    pub fn set_bounces(&mut self, bounces: u32) {
        self.bounces = bounces.max(1);
    }

    /// Frames per encode ([`Self::set_bounces`]).
    pub fn bounces(&self) -> u32 {
        self.bounces
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
        let bounces = match self.bounces {
            1 => String::new(),
            n => format!(", {n} frames fed back"),
        };
        format!(
            "PPR (holes {}, filtering {}, anti-bleeding {}{bounces})",
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
        self.size = size;
        self.renderer.prepare(camera, size).to_string()
    }

    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, inputs: &ReflectionInputs<'_>) {
        let Some(reflector_id) = inputs.reflector_id.filter(|_| self.bounces > 1) else {
            self.encode_frame(encoder, inputs);
            return;
        };
        let mut feed = self
            .feed
            .take()
            .unwrap_or_else(|| PreviousFrameFeed::new(&self.device, &self.queue, CompositeParams::default()));
        for frame in 0..self.bounces {
            let color = match frame {
                0 => inputs.color,
                _ => feed.previous(self.size).expect("the previous frame fed it"),
            };
            let frame_inputs = ReflectionInputs { color, ..*inputs };
            self.encode_frame(encoder, &frame_inputs);
            if frame + 1 < self.bounces {
                let feed_inputs =
                    FeedInputs { scene_color: inputs.color, reflection: inputs.output, reflector_id };
                let timed = self.feed_timed && frame + 2 == self.bounces;
                feed.encode(&self.device, encoder, &feed_inputs, self.size, timed);
            }
        }
        self.feed = Some(feed);
    }

    fn timings(&mut self, device: &wgpu::Device) -> Option<Vec<(String, f64)>> {
        let t = self.renderer.read_timings()?;
        let mut passes: Vec<(String, f64)> =
            t.passes().iter().filter_map(|(name, ms)| ms.map(|ms| ((*name).to_owned(), ms))).collect();
        if let Some(ms) = self.feed.as_ref().filter(|_| self.bounces > 1).and_then(|f| f.read_copy_ms(device))
        {
            passes.push((PREVIOUS_FRAME_COPY.to_owned(), ms));
        }
        Some(passes)
    }

    fn stop_pass_timing(&mut self) {
        self.renderer.stop_timestamps();
        self.feed_timed = false;
    }
}

impl PprTechnique {
    /// One frame: the runtime's passes (and the layer merge) on `inputs`.
    fn encode_frame(&mut self, encoder: &mut wgpu::CommandEncoder, inputs: &ReflectionInputs<'_>) {
        let size = self.size;
        if self.renderer.plan().is_none_or(|p| p.layers.is_empty()) {
            let frame = FrameInputs {
                normals: inputs.normal,
                ..FrameInputs::new(inputs.color, inputs.depth, inputs.output)
            };
            self.renderer.encode(encoder, &frame);
            return;
        }
        self.layer_targets(size);
        let targets = self.layer_targets.as_ref().expect("created above");
        // The runtime writes the layer output only over this frame's layer rectangle (and the
        // main output only in active tiles with indirect dispatch): cleared every frame, or an
        // earlier frame's layer reflections would be merged over this one's.
        for view in [&targets.main, &targets.layer] {
            clear_target(encoder, view, "testbed ppr target clear");
        }
        let frame = FrameInputs {
            normals: inputs.normal,
            layer_output: Some(&targets.layer),
            ..FrameInputs::new(inputs.color, inputs.depth, &targets.main)
        };
        self.renderer.encode(encoder, &frame);
        self.merge.encode(&self.device, encoder, targets, inputs.output);
    }
}
