//! Hi-Z SSR as a [`ReflectionTechnique`]: the min-depth pyramid build and the hierarchical
//! trace, timed apart.

use ppr_format::ReflectorSet;
use ppr_runtime::Camera;
use ppr_testbed::{ReflectionInputs, ReflectionTechnique};

use crate::frame_data::{FrameUniforms, PlaneBuffer};
use crate::gpu_types::{BaselineFrame, HiZUniform};
use crate::hiz_pyramid::HiZPyramid;
use crate::passes::hiz_trace::HiZTraceBindings;
use crate::passes::{HiZBuildPass, HiZTracePass};
use crate::plane_table::PlaneTable;
use crate::required_inputs::reflector_id;
use crate::settings::HiZSettings;
use crate::timestamps::PassTimer;

/// Names of the timed passes, in order.
const PASSES: [&str; 2] = ["hi-z build", "hi-z trace"];

/// Screen-space reflections through a Hi-Z pyramid (passes `hi-z build`, `hi-z trace`).
pub struct HiZSsrTechnique {
    device: wgpu::Device,
    /// How rays walk the pyramid; read at the next [`ReflectionTechnique::prepare`].
    pub settings: HiZSettings,
    table: PlaneTable,
    uniforms: FrameUniforms,
    planes: PlaneBuffer,
    build: HiZBuildPass,
    trace: HiZTracePass,
    pyramid: Option<HiZPyramid>,
    timer: Option<PassTimer>,
}

impl HiZSsrTechnique {
    /// The technique for the reflectors of `reflectors` (their planes give the normals);
    /// timestamps on where the device has them.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        reflectors: &ReflectorSet,
        settings: HiZSettings,
    ) -> Self {
        Self {
            device: device.clone(),
            settings,
            table: PlaneTable::new(reflectors),
            uniforms: FrameUniforms::new(device, "hi-z ssr", size_of::<HiZUniform>()),
            planes: PlaneBuffer::new(device, "hi-z ssr reflector planes"),
            build: HiZBuildPass::new(device),
            trace: HiZTracePass::new(device),
            pyramid: None,
            timer: PassTimer::new(device, queue, "hi-z ssr", 2),
        }
    }

    /// The pyramid of the last frame (after [`ReflectionTechnique::prepare`]), to inspect.
    pub fn pyramid(&self) -> Option<&HiZPyramid> {
        self.pyramid.as_ref()
    }
}

impl ReflectionTechnique for HiZSsrTechnique {
    fn name(&self) -> String {
        "SSR (Hi-Z)".to_owned()
    }

    fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        camera: &Camera,
        size: [u32; 2],
    ) -> String {
        let count = u32::try_from(self.table.reflector_count()).expect("fewer than 2^32 reflectors");
        let frame = BaselineFrame::new(camera, size, count, 0);
        if self.pyramid.as_ref().is_none_or(|p| p.size() != frame.size) {
            self.pyramid = Some(HiZPyramid::new(device, &self.build, frame.size));
        }
        let levels = HiZPyramid::level_count(frame.size);
        self.uniforms.write(queue, &frame, &self.settings.uniform(levels));
        self.planes.write(device, queue, &self.table.gpu_planes(camera, &[]));
        let s = &self.settings;
        let thickness = s.thickness.map_or("none".to_owned(), |t| format!("{t} m"));
        format!(
            "{levels} pyramid levels (climbs to {}), up to {} iterations, thickness {thickness}, {count} reflectors",
            s.top_level.min(levels - 1),
            s.max_iterations
        )
    }

    /// # Panics
    /// Without a prepared frame, or without `inputs.reflector_id`.
    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, inputs: &ReflectionInputs<'_>) {
        let pyramid = self.pyramid.as_ref().expect("HiZSsrTechnique::prepare before encode");
        let device = &self.device;
        let level0 = self.build.level0_bind_group(device, &self.uniforms.frame, inputs.depth, pyramid);
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("hi-z build"),
                timestamp_writes: self.timer.as_ref().map(|t| t.pass(0)),
            });
            self.build.encode(&mut pass, &level0, pyramid);
        }
        let bind_group = self.trace.bind_group(
            device,
            &HiZTraceBindings {
                frame: &self.uniforms.frame,
                params: &self.uniforms.params,
                planes: self.planes.buffer(),
                pyramid: pyramid.view(),
                levels: pyramid.levels_uniform(),
                depth: inputs.depth,
                reflector_id: reflector_id(inputs, "HiZSsrTechnique"),
                color: inputs.color,
                output: inputs.output,
            },
        );
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("hi-z trace"),
                timestamp_writes: self.timer.as_ref().map(|t| t.pass(1)),
            });
            self.trace.encode(&mut pass, &bind_group, pyramid.size());
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
