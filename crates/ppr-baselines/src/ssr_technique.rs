//! Ray-marched SSR as a [`ReflectionTechnique`]: brute force at pixel granularity or low
//! quality with coarse steps and binary refinement, as its [`SsrSettings`] say.

use ppr_format::ReflectorSet;
use ppr_runtime::Camera;
use ppr_testbed::{ReflectionInputs, ReflectionTechnique};

use crate::frame_data::{FrameUniforms, PlaneBuffer};
use crate::gpu_types::{BaselineFrame, SsrUniform};
use crate::passes::SsrMarchPass;
use crate::passes::ssr_march::SsrMarchBindings;
use crate::plane_table::PlaneTable;
use crate::required_inputs::reflector_id;
use crate::settings::SsrSettings;
use crate::timestamps::PassTimer;

/// Screen-space reflections by ray marching (one pass: `ssr march`).
pub struct SsrTechnique {
    device: wgpu::Device,
    /// How rays are marched; read at the next [`ReflectionTechnique::prepare`].
    pub settings: SsrSettings,
    table: PlaneTable,
    uniforms: FrameUniforms,
    planes: PlaneBuffer,
    pass: SsrMarchPass,
    timer: Option<PassTimer>,
    size: Option<[u32; 2]>,
}

impl SsrTechnique {
    /// The technique for the reflectors of `reflectors` (their planes give the normals);
    /// timestamps on where the device has them.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        reflectors: &ReflectorSet,
        settings: SsrSettings,
    ) -> Self {
        Self {
            device: device.clone(),
            settings,
            table: PlaneTable::new(reflectors),
            uniforms: FrameUniforms::new(device, "ssr", size_of::<SsrUniform>()),
            planes: PlaneBuffer::new(device, "ssr reflector planes"),
            pass: SsrMarchPass::new(device),
            timer: PassTimer::new(device, queue, "ssr", 1),
            size: None,
        }
    }
}

impl ReflectionTechnique for SsrTechnique {
    fn name(&self) -> String {
        let s = &self.settings;
        if s.stride <= 1 {
            "SSR (brute force, 1 px steps)".to_owned()
        } else {
            format!("SSR (low quality, {} px steps, {} refinements)", s.stride, s.refine_steps)
        }
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
        self.uniforms.write(queue, &frame, &self.settings.uniform());
        self.planes.write(device, queue, &self.table.gpu_planes(camera, &[]));
        self.size = Some(frame.size);
        let s = &self.settings;
        let steps =
            if s.max_steps == 0 { "to the screen edge".to_owned() } else { format!("up to {}", s.max_steps) };
        format!(
            "{} px steps {steps}, {} refinements, thickness {} m, {count} reflectors",
            s.stride.max(1),
            s.refine_steps,
            s.thickness
        )
    }

    /// # Panics
    /// Without a prepared frame, or without `inputs.reflector_id`.
    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, inputs: &ReflectionInputs<'_>) {
        let size = self.size.expect("SsrTechnique::prepare before encode");
        let bind_group = self.pass.bind_group(
            &self.device,
            &SsrMarchBindings {
                frame: &self.uniforms.frame,
                params: &self.uniforms.params,
                planes: self.planes.buffer(),
                depth: inputs.depth,
                reflector_id: reflector_id(inputs, "SsrTechnique"),
                color: inputs.color,
                output: inputs.output,
            },
        );
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("ssr march"),
                timestamp_writes: self.timer.as_ref().map(|t| t.pass(0)),
            });
            self.pass.encode(&mut pass, &bind_group, size);
        }
        if let Some(t) = &self.timer {
            t.resolve(encoder);
        }
    }

    fn timings(&mut self, device: &wgpu::Device) -> Option<Vec<(String, f64)>> {
        self.timer.as_ref()?.read(device, &[Some("ssr march")]).ok()
    }

    fn stop_pass_timing(&mut self) {
        self.timer = None;
    }
}
