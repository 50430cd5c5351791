//! `ReflectionRenderer`: what a game creates once and calls twice per frame.

use glam::DMat4;
use ppr_format::ReflectorSet;
use wgpu::util::DeviceExt;

use crate::camera::Camera;
use crate::encoding::CLEAR_VALUE;
use crate::gpu_types::{FLAG_OCCLUDER_TESTS, FrameUniforms, GpuShape};
use crate::passes::projection::ProjectionBindings;
use crate::passes::reflection::ReflectionBindings;
use crate::passes::{ClearPass, ProjectionPass, ReflectionPass};
use crate::plan::FramePlan;
use crate::settings::{ReflectionSettings, WriteMode};
use crate::shapes::ShapeTable;
use crate::timestamps::{PassTimer, PassTimings};

/// Pixels within this fraction of their camera distance from a reflector's plane count as
/// lying on it and are not reflected by it (else a reflector reflects itself). 1e-4 covers
/// the position error of an f32 depth buffer at 1000× the near-plane distance.
pub const PLANE_EPSILON: f32 = 1e-4;

/// How a renderer is created.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RendererDesc {
    /// Write GPU timestamps around each pass when the device supports them.
    pub timestamps: bool,
}

impl Default for RendererDesc {
    fn default() -> Self {
        Self { timestamps: true }
    }
}

/// The textures one frame reads and writes.
///
/// - `color`: the lit scene, `Rgba16Float` (any filterable float format works),
///   `TEXTURE_BINDING`;
/// - `depth`: the scene's depth, `Depth32Float`, `TEXTURE_BINDING`, a depth-only view,
///   written with the camera's [`crate::Projection`] (standard or reversed Z);
/// - `output`: `Rgba16Float` with `STORAGE_BINDING`, same size: reflected colour, alpha 1
///   where a reflection was found and 0 elsewhere. Not written when the plan is empty.
pub struct FrameInputs<'a> {
    pub color: &'a wgpu::TextureView,
    pub depth: &'a wgpu::TextureView,
    pub output: &'a wgpu::TextureView,
}

/// GPU buffers sized for a viewport and a set.
struct FrameBuffers {
    uniforms: wgpu::Buffer,
    shapes: wgpu::Buffer,
    visible: wgpu::Buffer,
    occluders: wgpu::Buffer,
    intermediate: wgpu::Buffer,
    viewport: [u32; 2],
}

/// Renders pixel-projected reflections for one view.
///
/// ```ignore
/// let mut ppr = ReflectionRenderer::new(&device, &queue, &RendererDesc::default());
/// ppr.set_reflectors(&set);
/// // every frame:
/// let plan = ppr.prepare(&camera, [width, height]);
/// ppr.encode(&mut encoder, &FrameInputs { color, depth, output });
/// queue.submit([encoder.finish()]);
/// let timings = ppr.read_timings(); // optional, waits for the GPU
/// ```
pub struct ReflectionRenderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    /// Steps of the reflection pass; change at any time.
    pub settings: ReflectionSettings,
    /// How the projection pass writes (debug: shows the write-order artefact).
    pub write_mode: WriteMode,
    clear: ClearPass,
    projection: ProjectionPass,
    reflection: ReflectionPass,
    table: ShapeTable,
    table_dirty: bool,
    buffers: Option<FrameBuffers>,
    plan: Option<FramePlan>,
    timer: Option<PassTimer>,
}

impl ReflectionRenderer {
    /// Builds the pipelines (once).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, desc: &RendererDesc) -> Self {
        Self {
            device: device.clone(),
            queue: queue.clone(),
            settings: ReflectionSettings::default(),
            write_mode: WriteMode::default(),
            clear: ClearPass::new(device),
            projection: ProjectionPass::new(device),
            reflection: ReflectionPass::new(device),
            table: ShapeTable::default(),
            table_dirty: true,
            buffers: None,
            plan: None,
            timer: if desc.timestamps { PassTimer::new(device, queue) } else { None },
        }
    }

    /// Replaces the reflectors (a validated set; e.g. from [`ReflectorSet::load`]).
    pub fn set_reflectors(&mut self, set: &ReflectorSet) {
        self.table = ShapeTable::from_set(set);
        self.table_dirty = true;
    }

    /// The reflectors as the runtime holds them.
    pub fn shapes(&self) -> &ShapeTable {
        &self.table
    }

    /// Plans the frame and uploads what the GPU needs. Call once per frame before
    /// [`Self::encode`].
    pub fn prepare(&mut self, camera: &Camera, viewport: [u32; 2]) -> &FramePlan {
        let plan = FramePlan::build(&self.table, camera, viewport);
        self.upload(camera, &plan);
        self.plan.insert(plan)
    }

    /// The plan of the last [`Self::prepare`].
    pub fn plan(&self) -> Option<&FramePlan> {
        self.plan.as_ref()
    }

    fn upload(&mut self, camera: &Camera, plan: &FramePlan) {
        let (device, queue) = (&self.device, &self.queue);
        let [w, h] = plan.viewport;
        let shapes = self.table.gpu_shapes(camera.position);
        let needs_new = match &self.buffers {
            None => true,
            Some(b) => {
                b.viewport != plan.viewport
                    || b.shapes.size() < byte_len(&shapes).max(16)
                    || b.visible.size() < (4 * self.table.shapes.len() as u64).max(16)
                    || self.table_dirty
            }
        };
        if needs_new {
            self.buffers = Some(FrameBuffers::new(device, &self.table, plan.viewport));
            self.table_dirty = false;
        }
        let b = self.buffers.as_ref().expect("allocated above");

        let aspect = w as f32 / h.max(1) as f32;
        let clip_from_rel = camera.clip_from_relative(aspect);
        // Invert in f64: the reversed-Z and infinite projections are badly conditioned.
        let rel_from_clip = DMat4::from_cols_array(&clip_from_rel.to_cols_array().map(f64::from)).inverse();
        let uniforms = FrameUniforms {
            clip_from_rel: clip_from_rel.to_cols_array_2d(),
            rel_from_clip: rel_from_clip.as_mat4().to_cols_array_2d(),
            resolution: [w as f32, h as f32, 1.0 / w as f32, 1.0 / h as f32],
            size: [w, h],
            visible_count: plan.visible.len() as u32,
            flags: self.settings.flags()
                | self.write_mode.flags()
                | if plan.occluder_tests { FLAG_OCCLUDER_TESTS } else { 0 },
            far_depth: camera.projection.far_depth(),
            plane_epsilon: PLANE_EPSILON,
            _pad: [0; 2],
            encoding: plan.encoding.gpu_params(),
        };
        queue.write_buffer(&b.uniforms, 0, bytemuck::bytes_of(&uniforms));
        if !shapes.is_empty() {
            queue.write_buffer(&b.shapes, 0, bytemuck::cast_slice(&shapes));
        }
        if !plan.visible.is_empty() {
            queue.write_buffer(&b.visible, 0, bytemuck::cast_slice(&plan.visible));
        }
    }

    /// Records the frame's passes into `encoder` (nothing when the plan is empty).
    ///
    /// # Panics
    /// If [`Self::prepare`] was not called first.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, inputs: &FrameInputs<'_>) {
        let device = &self.device;
        let plan = self.plan.as_ref().expect("prepare() before encode()");
        if plan.is_empty() {
            return;
        }
        let b = self.buffers.as_ref().expect("prepare() allocates the buffers");
        let clear_bg = self.clear.bind_group(device, &b.intermediate);
        let projection_bg = self.projection.bind_group(
            device,
            &ProjectionBindings {
                uniforms: &b.uniforms,
                depth: inputs.depth,
                shapes: &b.shapes,
                visible: &b.visible,
                occluders: &b.occluders,
                intermediate: &b.intermediate,
            },
        );
        let reflection_bg = self.reflection.bind_group(
            device,
            &ReflectionBindings {
                uniforms: &b.uniforms,
                intermediate: &b.intermediate,
                color: inputs.color,
                output: inputs.output,
            },
        );
        let timestamps = |i| self.timer.as_ref().map(|t| t.writes(i));
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("ppr clear"),
                timestamp_writes: timestamps(0),
            });
            self.clear.encode(&mut pass, &clear_bg, (b.intermediate.size() / 16) as u32);
        }
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("ppr projection"),
                timestamp_writes: timestamps(1),
            });
            self.projection.encode(&mut pass, &projection_bg, plan.viewport);
        }
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("ppr reflection"),
                timestamp_writes: timestamps(2),
            });
            self.reflection.encode(&mut pass, &reflection_bg, plan.viewport);
        }
        if let Some(t) = &self.timer {
            t.resolve(encoder);
        }
    }

    /// Whether GPU timestamps are recorded (the device has `TIMESTAMP_QUERY`).
    pub fn has_timestamps(&self) -> bool {
        self.timer.is_some()
    }

    /// Waits for the last submitted frame and returns its GPU time per pass, when the
    /// device supports timestamps and the last plan ran passes.
    pub fn read_timings(&self) -> Option<PassTimings> {
        if self.plan.as_ref().is_none_or(|p| p.is_empty()) {
            return None;
        }
        self.timer.as_ref()?.read(&self.device)
    }

    /// The intermediate buffer (one u32 per pixel, row-major, padded to 16 bytes), for
    /// debug views and tests. `None` before the first [`Self::prepare`].
    pub fn intermediate_buffer(&self) -> Option<&wgpu::Buffer> {
        self.buffers.as_ref().map(|b| &b.intermediate)
    }
}

impl FrameBuffers {
    fn new(device: &wgpu::Device, table: &ShapeTable, [w, h]: [u32; 2]) -> Self {
        let storage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
        let buffer = |label: &str, size: u64, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        let pixels = u64::from(w) * u64::from(h);
        let occluders =
            if table.occluder_indices.is_empty() { vec![0u32; 4] } else { table.occluder_indices.clone() };
        Self {
            uniforms: buffer(
                "ppr frame uniforms",
                std::mem::size_of::<FrameUniforms>() as u64,
                wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            ),
            shapes: buffer(
                "ppr shapes",
                (table.shapes.len() * std::mem::size_of::<GpuShape>()).max(std::mem::size_of::<GpuShape>())
                    as u64,
                storage,
            ),
            visible: buffer("ppr visible shapes", (4 * table.shapes.len() as u64).max(16), storage),
            occluders: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("ppr occluder lists"),
                contents: bytemuck::cast_slice(&occluders),
                usage: storage,
            }),
            intermediate: buffer(
                "ppr intermediate buffer",
                (pixels * 4).next_multiple_of(16).max(16),
                storage | wgpu::BufferUsages::COPY_SRC,
            ),
            viewport: [w, h],
        }
    }
}

fn byte_len(shapes: &[GpuShape]) -> u64 {
    std::mem::size_of_val(shapes) as u64
}

const _: () = assert!(CLEAR_VALUE == u32::MAX);
