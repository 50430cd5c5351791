//! The accumulation pass of the exact glossy reference (`shaders/glossy_accumulate.wgsl`):
//! after each view of [`crate::glossy_views`] is drawn, adds its colour at every main-view
//! pixel of the plane's rough reflectors with the weight `f(ω) / p(ω)` to a per-pixel sum.

use ppr_scene_gpu::layout_entries::{storage_entry, texture_entry, uniform_entry};

use crate::TestbedError;
use crate::gbuffer_targets::GBuffer;
use crate::gpu::wait_idle;
use crate::scene_layouts::uniform_stride;

/// Per-view uniform of the accumulation (one dynamic slot per plane and view).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GlossySampleUniform {
    /// The main view's relative-from-clip matrix (pixel rays).
    pub rel_from_main_clip: [[f32; 4]; 4],
    /// xyz: unit normal of the reflecting side; w: `n · X` on the plane (camera-relative).
    pub plane: [f32; 4],
    /// xyz: the view's eye point, camera-relative; w: `1 / q(E)`, m².
    pub eye: [f32; 4],
    /// x: the plane slot of the view.
    pub slot: [u32; 4],
}
const _: () = assert!(size_of::<GlossySampleUniform>() == 112);

/// A reflector as the accumulation reads it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct RoughReflector {
    /// Plane slot (`u32::MAX`: not rendered).
    pub plane: u32,
    /// GGX alpha (`roughness²`); 0 for a mirror, which keeps the mirror reference.
    pub alpha: f32,
}

/// Bytes of one pixel's sums (`Σ wL`, `Σ w`, `Σ w²`, views with `w > 0`, padding).
const ACCUM_BYTES: u64 = 32;
/// Workgroup edge of `cs_accumulate` (`@workgroup_size(8, 8, 1)`).
const WORKGROUP: u32 = 8;

/// Effective sample size of the glossy reference over the pixels it resolved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlossyStats {
    /// Pixels with a positive weight sum.
    pub pixels: usize,
    /// Mean of `(Σ w)² / Σ w²` over those pixels.
    pub mean_ess: f64,
    /// Smallest effective sample size.
    pub min_ess: f64,
    /// Tenth percentile of the effective sample size.
    pub p10_ess: f64,
}

/// Per-frame data of the accumulation: sample uniforms, the reflector table, the sums and
/// the bind group over the main view's ids and the views' colour target.
pub struct GlossyBindings {
    samples: wgpu::Buffer,
    stride: u64,
    slots: u32,
    reflectors: wgpu::Buffer,
    reflector_capacity: usize,
    accum: wgpu::Buffer,
    size: [u32; 2],
    bind_group: wgpu::BindGroup,
}

impl GlossyBindings {
    /// Whether this has room for `slots` views and `reflectors` reflectors at `size`.
    pub fn fits(&self, slots: u32, reflectors: usize, size: [u32; 2]) -> bool {
        slots <= self.slots && reflectors <= self.reflector_capacity && size == self.size
    }

    /// Writes the uniform of view `slot`.
    ///
    /// # Panics
    /// If `slot` is out of range.
    pub fn write_sample(&self, queue: &wgpu::Queue, slot: u32, sample: &GlossySampleUniform) {
        assert!(slot < self.slots, "glossy slot {slot} out of range ({} slots)", self.slots);
        queue.write_buffer(&self.samples, u64::from(slot) * self.stride, bytemuck::bytes_of(sample));
    }

    /// Writes the reflector table (at most the capacity).
    pub fn write_reflectors(&self, queue: &wgpu::Queue, reflectors: &[RoughReflector]) {
        let n = reflectors.len().min(self.reflector_capacity);
        if n > 0 {
            queue.write_buffer(&self.reflectors, 0, bytemuck::cast_slice(&reflectors[..n]));
        }
    }

    /// The per-pixel sums (8 `f32` per pixel, row-major).
    pub fn accum(&self) -> &wgpu::Buffer {
        &self.accum
    }

    /// Reads the sums back (waits for the GPU) and summarises the effective sample size.
    ///
    /// # Errors
    /// [`TestbedError::Readback`] if mapping fails.
    pub fn read_stats(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<GlossyStats, TestbedError> {
        let err = |e: &dyn std::fmt::Display| TestbedError::Readback {
            what: "glossy reference sums".into(),
            reason: e.to_string(),
        };
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("glossy reference: sums readback"),
            size: self.accum.size(),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("glossy sums readback") });
        encoder.copy_buffer_to_buffer(&self.accum, 0, &staging, 0, self.accum.size());
        queue.submit([encoder.finish()]);
        let (sender, receiver) = std::sync::mpsc::channel();
        staging.map_async(wgpu::MapMode::Read, .., move |r| {
            // The receiver waits below; a send error only means it gave up already.
            let _ = sender.send(r);
        });
        wait_idle(device)?;
        receiver.recv().map_err(|e| err(&e))?.map_err(|e| err(&e))?;
        let bytes = staging.get_mapped_range(..).map_err(|e| err(&e))?;
        let values: &[f32] = bytemuck::cast_slice(&bytes);
        let mut ess: Vec<f64> = values
            .chunks_exact(8)
            .filter(|p| p[3] > 0.0 && p[4] > 0.0)
            .map(|p| f64::from(p[3]) * f64::from(p[3]) / f64::from(p[4]))
            .collect();
        ess.sort_by(f64::total_cmp);
        let pixels = ess.len();
        let mean_ess = if pixels == 0 { 0.0 } else { ess.iter().sum::<f64>() / pixels as f64 };
        Ok(GlossyStats {
            pixels,
            mean_ess,
            min_ess: ess.first().copied().unwrap_or(0.0),
            p10_ess: ess.get(pixels / 10).copied().unwrap_or(0.0),
        })
    }
}

/// The accumulation pass (pipeline and layout built once).
pub struct GlossyAccumulatePass {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

impl GlossyAccumulatePass {
    /// Builds the pipeline.
    pub fn new(device: &wgpu::Device) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("glossy accumulate shader"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../shaders/glossy_accumulate.wgsl").into()),
        });
        let compute = wgpu::ShaderStages::COMPUTE;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("glossy accumulate layout"),
            entries: &[
                uniform_entry(0, compute, true),
                storage_entry(1, compute),
                texture_entry(2, compute, wgpu::TextureSampleType::Uint),
                texture_entry(3, compute, wgpu::TextureSampleType::Float { filterable: false }),
                wgpu::BindGroupLayoutEntry {
                    binding: 4,
                    visibility: compute,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: false },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("glossy accumulate pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("glossy accumulate pipeline"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("cs_accumulate"),
            compilation_options: Default::default(),
            cache: None,
        });
        Self { layout, pipeline }
    }

    /// Per-frame data over the main G-buffer `main` and the views' scratch `views`, with room
    /// for `slots` views and `reflectors` reflectors.
    pub fn bindings(
        &self,
        device: &wgpu::Device,
        main: &GBuffer,
        views: &GBuffer,
        slots: u32,
        reflectors: usize,
    ) -> GlossyBindings {
        let slots = slots.max(1);
        let stride = uniform_stride(device, size_of::<GlossySampleUniform>());
        let samples = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("glossy accumulate: sample uniforms"),
            size: stride * u64::from(slots),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let reflector_capacity = reflectors.max(1);
        let reflectors = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("glossy accumulate: reflectors"),
            size: (size_of::<RoughReflector>() * reflector_capacity) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let size = main.size;
        let accum = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("glossy accumulate: sums"),
            size: ACCUM_BYTES * u64::from(size[0]) * u64::from(size[1]),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let view = |binding, view| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(view),
        };
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("glossy accumulate bind group"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &samples,
                        offset: 0,
                        size: wgpu::BufferSize::new(size_of::<GlossySampleUniform>() as u64),
                    }),
                },
                wgpu::BindGroupEntry { binding: 1, resource: reflectors.as_entire_binding() },
                view(2, &main.reflector_id.view),
                view(3, &views.color.view),
                wgpu::BindGroupEntry { binding: 4, resource: accum.as_entire_binding() },
            ],
        });
        GlossyBindings { samples, stride, slots, reflectors, reflector_capacity, accum, size, bind_group }
    }

    /// Records the clearing of the sums (before the frame's first view).
    pub fn encode_clear(&self, encoder: &mut wgpu::CommandEncoder, bindings: &GlossyBindings) {
        encoder.clear_buffer(&bindings.accum, 0, None);
    }

    /// Records the accumulation of the view in `slot` (drawn into the scratch G-buffer).
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, bindings: &GlossyBindings, slot: u32) {
        let offset = u32::try_from(u64::from(slot) * bindings.stride).expect("glossy uniforms under 4 GiB");
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("glossy accumulate pass"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bindings.bind_group, &[offset]);
        pass.dispatch_workgroups(
            bindings.size[0].div_ceil(WORKGROUP),
            bindings.size[1].div_ceil(WORKGROUP),
            1,
        );
    }
}
