//! Glossy SSR as a [`ReflectionTechnique`]: the ray march of [`crate::SsrTechnique`] (its
//! alpha the hit distance) into a scratch texture, then a blur whose radius grows with the
//! reflector's roughness (from the reflector set) and the hit distance. Mirrors (roughness
//! 0) come out as plain SSR.

use ppr_format::ReflectorSet;
use ppr_runtime::Camera;
use ppr_testbed::technique::REFLECTION_FORMAT;
use ppr_testbed::{ReflectionInputs, ReflectionTechnique};

use crate::frame_data::{FrameUniforms, PlaneBuffer};
use crate::gpu_types::{BaselineFrame, GlossyBlurUniform, SsrUniform};
use crate::passes::ssr_glossy_blur::SsrGlossyBlurBindings;
use crate::passes::ssr_march::SsrMarchBindings;
use crate::passes::{MarchAlpha, SsrGlossyBlurPass, SsrMarchPass};
use crate::plane_table::PlaneTable;
use crate::required_inputs::reflector_id;
use crate::settings::SsrGlossySettings;
use crate::timestamps::PassTimer;

/// Glossy screen-space reflections (two passes: `ssr march`, `ssr glossy blur`).
pub struct SsrGlossyTechnique {
    device: wgpu::Device,
    /// How rays are marched and blurred; read at the next [`ReflectionTechnique::prepare`].
    pub settings: SsrGlossySettings,
    table: PlaneTable,
    uniforms: FrameUniforms,
    blur_params: wgpu::Buffer,
    alphas: wgpu::Buffer,
    planes: PlaneBuffer,
    march: SsrMarchPass,
    blur: SsrGlossyBlurPass,
    scratch: Option<(wgpu::Texture, wgpu::TextureView)>,
    timer: Option<PassTimer>,
    size: Option<[u32; 2]>,
}

impl SsrGlossyTechnique {
    /// The technique for the reflectors of `reflectors` (their planes give the normals,
    /// their roughness the blur); timestamps on where the device has them.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        reflectors: &ReflectorSet,
        settings: SsrGlossySettings,
    ) -> Self {
        let mut alphas: Vec<f32> = reflectors
            .reflectors
            .iter()
            .map(|r| if r.enabled { (r.roughness * r.roughness) as f32 } else { 0.0 })
            .collect();
        if alphas.is_empty() {
            alphas.push(0.0);
        }
        let alpha_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ssr glossy: reflector alphas"),
            size: (alphas.len() * size_of::<f32>()) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        queue.write_buffer(&alpha_buffer, 0, bytemuck::cast_slice(&alphas));
        let blur_params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ssr glossy: blur params"),
            size: size_of::<GlossyBlurUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self {
            device: device.clone(),
            settings,
            table: PlaneTable::new(reflectors),
            uniforms: FrameUniforms::new(device, "ssr glossy", size_of::<SsrUniform>()),
            blur_params,
            alphas: alpha_buffer,
            planes: PlaneBuffer::new(device, "ssr glossy reflector planes"),
            march: SsrMarchPass::with_alpha(device, MarchAlpha::HitDistance),
            blur: SsrGlossyBlurPass::new(device),
            scratch: None,
            timer: PassTimer::new(device, queue, "ssr glossy", 2),
            size: None,
        }
    }

    fn scratch(&mut self, size: [u32; 2]) -> &wgpu::TextureView {
        let fits = self.scratch.as_ref().is_some_and(|(t, _)| t.width() == size[0] && t.height() == size[1]);
        if !fits {
            let texture = self.device.create_texture(&wgpu::TextureDescriptor {
                label: Some("ssr glossy: marched reflection"),
                size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: REFLECTION_FORMAT,
                usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            });
            let view = texture.create_view(&Default::default());
            self.scratch = Some((texture, view));
        }
        &self.scratch.as_ref().expect("allocated above").1
    }
}

impl ReflectionTechnique for SsrGlossyTechnique {
    fn name(&self) -> String {
        let s = &self.settings;
        let march = if s.march.stride <= 1 {
            "1 px steps".to_owned()
        } else {
            format!("{} px steps, {} refinements", s.march.stride, s.march.refine_steps)
        };
        format!("SSR glossy ({march}; blur spread {}, {} taps)", s.spread, s.samples)
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
        self.uniforms.write(queue, &frame, &self.settings.march.uniform());
        queue.write_buffer(&self.blur_params, 0, bytemuck::bytes_of(&self.settings.blur_uniform()));
        self.planes.write(device, queue, &self.table.gpu_planes(camera, &[]));
        self.size = Some(frame.size);
        self.scratch(frame.size);
        let s = &self.settings;
        format!(
            "{} px steps, {} refinements, thickness {} m; blur spread {} × alpha × hit distance, at most {} px, \
             {} taps; {count} reflectors",
            s.march.stride.max(1),
            s.march.refine_steps,
            s.march.thickness,
            s.spread,
            s.max_radius,
            s.samples
        )
    }

    /// # Panics
    /// Without a prepared frame, or without `inputs.reflector_id`.
    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, inputs: &ReflectionInputs<'_>) {
        let size = self.size.expect("SsrGlossyTechnique::prepare before encode");
        let ids = reflector_id(inputs, "SsrGlossyTechnique");
        let scratch = &self.scratch.as_ref().expect("allocated in prepare").1;
        let march = self.march.bind_group(
            &self.device,
            &SsrMarchBindings {
                frame: &self.uniforms.frame,
                params: &self.uniforms.params,
                planes: self.planes.buffer(),
                depth: inputs.depth,
                reflector_id: ids,
                color: inputs.color,
                output: scratch,
            },
        );
        let blur = self.blur.bind_group(
            &self.device,
            &SsrGlossyBlurBindings {
                frame: &self.uniforms.frame,
                params: &self.blur_params,
                alphas: &self.alphas,
                depth: inputs.depth,
                reflector_id: ids,
                march: scratch,
                output: inputs.output,
            },
        );
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("ssr march"),
                timestamp_writes: self.timer.as_ref().map(|t| t.pass(0)),
            });
            self.march.encode(&mut pass, &march, size);
        }
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("ssr glossy blur"),
                timestamp_writes: self.timer.as_ref().map(|t| t.pass(1)),
            });
            self.blur.encode(&mut pass, &blur, size);
        }
        if let Some(t) = &self.timer {
            t.resolve(encoder);
        }
    }

    fn timings(&mut self, device: &wgpu::Device) -> Option<Vec<(String, f64)>> {
        self.timer.as_ref()?.read(device, &[Some("ssr march"), Some("ssr glossy blur")]).ok()
    }

    fn stop_pass_timing(&mut self) {
        self.timer = None;
    }
}
