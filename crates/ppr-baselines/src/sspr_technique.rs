//! Screen-space planar reflections (Ghost Recon Wildlands) as a [`ReflectionTechnique`]:
//! clear the projection hash, project every pixel through each visible plane, resolve.

use ppr_format::ReflectorSet;
use ppr_runtime::Camera;
use ppr_testbed::{ReflectionInputs, ReflectionTechnique};

use crate::frame_data::{FrameUniforms, PlaneBuffer};
use crate::gpu_types::{BaselineFrame, ClearUniform, SsprUniform};
use crate::passes::sspr_project::SsprProjectBindings;
use crate::passes::sspr_resolve::SsprResolveBindings;
use crate::passes::{SsprClearPass, SsprProjectPass, SsprResolvePass};
use crate::plane_table::PlaneTable;
use crate::required_inputs::reflector_id;
use crate::settings::SsprSettings;
use crate::timestamps::PassTimer;

/// Names of the timed passes, in order.
const PASSES: [&str; 3] = ["sspr clear", "sspr projection", "sspr resolve"];

/// Largest width or height the hash `y << 16 | x` can address.
pub const MAX_SIZE: u32 = 0xffff;

/// What [`ReflectionTechnique::prepare`] decided for a frame.
#[derive(Clone, Debug, PartialEq, Eq)]
struct SsprFrame {
    size: [u32; 2],
    /// Plane groups with a hash layer, in layer order.
    layered: Vec<usize>,
}

/// The SSPR projection hash (passes `sspr clear`, `sspr projection`, `sspr resolve`).
pub struct SsprTechnique {
    device: wgpu::Device,
    /// How pixels are projected; read at the next [`ReflectionTechnique::prepare`].
    pub settings: SsprSettings,
    table: PlaneTable,
    uniforms: FrameUniforms,
    clear_uniform: wgpu::Buffer,
    planes: PlaneBuffer,
    layers: PlaneBuffer,
    hash: Option<wgpu::Buffer>,
    clear: SsprClearPass,
    project: SsprProjectPass,
    resolve: SsprResolvePass,
    timer: Option<PassTimer>,
    frame: Option<SsprFrame>,
}

impl SsprTechnique {
    /// The technique for the reflectors of `reflectors`; timestamps on where the device
    /// has them.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        reflectors: &ReflectorSet,
        settings: SsprSettings,
    ) -> Self {
        Self {
            device: device.clone(),
            settings,
            table: PlaneTable::new(reflectors),
            uniforms: FrameUniforms::new(device, "sspr", size_of::<SsprUniform>()),
            clear_uniform: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("sspr clear params"),
                size: size_of::<ClearUniform>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            planes: PlaneBuffer::new(device, "sspr reflector planes"),
            layers: PlaneBuffer::new(device, "sspr layer planes"),
            hash: None,
            clear: SsprClearPass::new(device),
            project: SsprProjectPass::new(device),
            resolve: SsprResolvePass::new(device),
            timer: PassTimer::new(device, queue, "sspr", 3),
            frame: None,
        }
    }

    /// The projection hash of the last frame: per layer, one `u32` per pixel (row-major),
    /// `y << 16 | x` of the winning source pixel or 0. For tests and debug views.
    pub fn hash_buffer(&self) -> Option<&wgpu::Buffer> {
        self.hash.as_ref()
    }

    /// Hash layers of the last prepared frame.
    pub fn layer_count(&self) -> usize {
        self.frame.as_ref().map_or(0, |f| f.layered.len())
    }

    fn hash_values(&self) -> u32 {
        self.frame.as_ref().map_or(0, |f| f.size[0] * f.size[1] * f.layered.len() as u32)
    }
}

impl ReflectionTechnique for SsprTechnique {
    fn name(&self) -> String {
        match self.settings.edge_stretch {
            None => "SSPR (projection hash)".to_owned(),
            Some(_) => "SSPR (projection hash, edge stretch)".to_owned(),
        }
    }

    /// # Panics
    /// If `size` is wider or taller than [`MAX_SIZE`] (the hash holds 16-bit coordinates).
    fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        camera: &Camera,
        size: [u32; 2],
    ) -> String {
        assert!(
            size[0] <= MAX_SIZE && size[1] <= MAX_SIZE,
            "SSPR hashes 16-bit pixel coordinates: {size:?} is too large"
        );
        let layered = self.table.visible_groups(camera, size, self.settings.max_layers as usize);
        let count = u32::try_from(self.table.reflector_count()).expect("fewer than 2^32 reflectors");
        let layer_count = u32::try_from(layered.len()).expect("fewer than 2^32 layers");
        let frame = BaselineFrame::new(camera, size, count, layer_count);
        self.uniforms.write(queue, &frame, &self.settings.uniform());
        self.planes.write(device, queue, &self.table.gpu_planes(camera, &layered));
        self.layers.write(device, queue, &self.table.gpu_layers(camera, &layered));
        let values = u64::from(frame.size[0]) * u64::from(frame.size[1]) * u64::from(layer_count.max(1));
        let bytes = values * 4;
        if self.hash.as_ref().is_none_or(|h| h.size() < bytes) {
            self.hash = Some(device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("sspr projection hash"),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }));
        }
        let description = format!(
            "{} of {} planes hashed{}",
            layered.len(),
            self.table.groups().len(),
            if self.settings.edge_stretch.is_some() { ", edge stretch" } else { "" }
        );
        self.frame = Some(SsprFrame { size: frame.size, layered });
        let values = self.hash_values();
        queue.write_buffer(&self.clear_uniform, 0, bytemuck::bytes_of(&SsprClearPass::uniform(values)));
        description
    }

    /// # Panics
    /// Without a prepared frame, or without `inputs.reflector_id`.
    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, inputs: &ReflectionInputs<'_>) {
        let frame = self.frame.as_ref().expect("SsprTechnique::prepare before encode");
        let hash = self.hash.as_ref().expect("prepare allocates the hash");
        let device = &self.device;
        let timestamps = |i| self.timer.as_ref().map(|t| t.pass(i));
        if !frame.layered.is_empty() {
            let bind_group = self.clear.bind_group(device, &self.clear_uniform, hash);
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(PASSES[0]),
                timestamp_writes: timestamps(0),
            });
            self.clear.encode(&mut pass, &bind_group, self.hash_values());
        }
        if !frame.layered.is_empty() {
            let bind_group = self.project.bind_group(
                device,
                &SsprProjectBindings {
                    frame: &self.uniforms.frame,
                    params: &self.uniforms.params,
                    layers: self.layers.buffer(),
                    depth: inputs.depth,
                    hash,
                },
            );
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(PASSES[1]),
                timestamp_writes: timestamps(1),
            });
            self.project.encode(&mut pass, &bind_group, frame.size);
        }
        {
            let bind_group = self.resolve.bind_group(
                device,
                &SsprResolveBindings {
                    frame: &self.uniforms.frame,
                    planes: self.planes.buffer(),
                    reflector_id: reflector_id(inputs, "SsprTechnique"),
                    color: inputs.color,
                    hash,
                    output: inputs.output,
                },
            );
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(PASSES[2]),
                timestamp_writes: timestamps(2),
            });
            self.resolve.encode(&mut pass, &bind_group, frame.size);
        }
        if let Some(t) = &self.timer {
            t.resolve(encoder);
        }
    }

    fn timings(&mut self, device: &wgpu::Device) -> Option<Vec<(String, f64)>> {
        let hashed = self.frame.as_ref().is_some_and(|f| !f.layered.is_empty());
        let ran = [hashed.then_some(PASSES[0]), hashed.then_some(PASSES[1]), Some(PASSES[2])];
        self.timer.as_ref()?.read(device, &ran).ok()
    }

    fn stop_pass_timing(&mut self) {
        self.timer = None;
    }
}
