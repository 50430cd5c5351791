//! The exact planar reflection: per reflector plane, the scene rendered from the mirrored
//! camera (see [`crate::mirror_camera`]), resolved into main-view pixels with the reflected
//! point's position and whether the main view shows that point.

use ppr_runtime::Camera;
use ppr_scene_gpu::layout_entries::{storage_entry, texture_entry, uniform_entry};
use ppr_scene_gpu::screen_pass::screen_pass_module;

use crate::gbuffer_targets::{GBuffer, Target};
use crate::mirror_camera::MirroredView;
use crate::scene_layouts::uniform_stride;

/// Format of the reference reflection colour (linear HDR; alpha 1 on reflector pixels).
pub const REFERENCE_COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Format of the reflected point: xyz are the bits of its `f32` camera-relative position,
/// w its [`ReflectedPointClass`] (integer targets are renderable on every backend; 32-bit
/// float ones are not on GL without `EXT_color_buffer_float`).
pub const REFERENCE_POINT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;

/// What a main-view pixel's reflection shows, as stored in the class texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u32)]
pub enum ReflectedPointClass {
    /// Not on a reflector (or on one whose plane was not rendered).
    NotReflector = 0,
    /// The reflected point is visible in the main view: a screen-space method can get it.
    OnScreen = 1,
    /// The reflected point is outside the viewport or hidden behind something.
    OffScreen = 2,
    /// The reflection shows the background (no geometry hit).
    Background = 3,
}

impl ReflectedPointClass {
    /// The class stored as `value`; unknown values read as `NotReflector`.
    pub fn from_u32(value: u32) -> Self {
        match value {
            1 => Self::OnScreen,
            2 => Self::OffScreen,
            3 => Self::Background,
            _ => Self::NotReflector,
        }
    }
}

/// Tolerances of the on-screen test: the main view's surface at the pixel where the
/// reflected point projects must be the reflected point's surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OnScreenTolerance {
    /// Largest distance of the reflected point from the main view's surface plane, metres
    /// (also added to the distance test below).
    pub plane: f32,
    /// Added to `plane` per metre of distance from the camera (depth precision).
    pub plane_per_metre: f32,
    /// Largest distance to the main view's surface point at that pixel, in pixel
    /// footprints at the point's distance.
    pub distance_pixels: f32,
    /// Smallest cosine between the reflected surface's normal and the main view's normal.
    pub min_normal_cos: f32,
}

impl Default for OnScreenTolerance {
    fn default() -> Self {
        Self { plane: 0.005, plane_per_metre: 0.005, distance_pixels: 3.0, min_normal_cos: 0.7 }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct ResolveUniform {
    rel_from_mirror_clip: [[f32; 4]; 4],
    main_clip_from_rel: [[f32; 4]; 4],
    rel_from_main_clip: [[f32; 4]; 4],
    size: [f32; 4],
    plane: [u32; 4],
    depth: [f32; 4],
    normals: [f32; 4],
}
const _: () = assert!(size_of::<ResolveUniform>() == 256);

/// The outputs of the reference for one frame size, and the mirrored view's scratch G-buffer.
pub struct ReferenceTargets {
    /// Width and height in pixels.
    pub size: [u32; 2],
    /// Reflected colour on reflector pixels (alpha 1), zero elsewhere.
    pub color: Target,
    /// Reflected point ([`REFERENCE_POINT_FORMAT`]): position bits and class.
    pub point: Target,
    /// Scratch targets of the mirrored views (reused for every plane).
    pub mirror: GBuffer,
}

impl ReferenceTargets {
    /// Allocates the targets.
    pub fn new(device: &wgpu::Device, size: [u32; 2]) -> Self {
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC;
        let size = [size[0].max(1), size[1].max(1)];
        Self {
            size,
            color: Target::new(device, "reference: colour", size, REFERENCE_COLOR_FORMAT, usage),
            point: Target::new(device, "reference: reflected point", size, REFERENCE_POINT_FORMAT, usage),
            mirror: GBuffer::new(device, size, "reference: mirrored view"),
        }
    }
}

/// Per-frame GPU data of the resolve: one uniform slot per plane, the reflector -> plane
/// table, and the bind group over the main G-buffer and the reference targets.
pub struct ReferenceBindings {
    uniforms: wgpu::Buffer,
    stride: u64,
    slots: u32,
    plane_of_reflector: wgpu::Buffer,
    reflector_capacity: usize,
    bind_group: wgpu::BindGroup,
}

impl ReferenceBindings {
    /// Writes the resolve uniform of plane `slot`.
    ///
    /// # Panics
    /// If `slot` is out of range.
    pub fn write_plane(
        &self,
        queue: &wgpu::Queue,
        slot: u32,
        camera: &Camera,
        size: [u32; 2],
        mirrored: &MirroredView,
        tolerance: &OnScreenTolerance,
    ) {
        assert!(slot < self.slots, "plane slot {slot} out of range ({} slots)", self.slots);
        let aspect = size[0] as f32 / size[1] as f32;
        let main = camera.clip_from_relative(aspect);
        let u = ResolveUniform {
            rel_from_mirror_clip: mirrored.rel_from_clip.as_mat4().to_cols_array_2d(),
            main_clip_from_rel: main.to_cols_array_2d(),
            rel_from_main_clip: main.as_dmat4().inverse().as_mat4().to_cols_array_2d(),
            size: [size[0] as f32, size[1] as f32, 1.0 / size[0] as f32, 1.0 / size[1] as f32],
            plane: [slot, 0, 0, 0],
            depth: [
                camera.projection.far_depth(),
                tolerance.plane,
                tolerance.plane_per_metre,
                tolerance.distance_pixels * footprint_per_metre(camera, size),
            ],
            normals: [tolerance.min_normal_cos, 0.0, 0.0, 0.0],
        };
        queue.write_buffer(&self.uniforms, u64::from(slot) * self.stride, bytemuck::bytes_of(&u));
    }

    /// The reflector → plane slot table (`u32` per reflector), for passes that need it.
    pub fn plane_of_reflector(&self) -> &wgpu::Buffer {
        &self.plane_of_reflector
    }

    /// Writes which plane slot each reflector belongs to (`u32::MAX` for none).
    pub fn write_plane_of_reflector(&self, queue: &wgpu::Queue, plane_of: &[u32]) {
        let n = plane_of.len().min(self.reflector_capacity);
        if n > 0 {
            queue.write_buffer(&self.plane_of_reflector, 0, bytemuck::cast_slice(&plane_of[..n]));
        }
    }
}

/// The resolve pass of the exact reference (pipeline and layout built once).
pub struct MirrorReference {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

impl MirrorReference {
    /// Builds the resolve pipeline.
    pub fn new(device: &wgpu::Device) -> Self {
        let shader =
            screen_pass_module(device, "reference resolve shader", include_str!("../shaders/reference.wgsl"));
        let tex = |binding, sample_type| texture_entry(binding, wgpu::ShaderStages::FRAGMENT, sample_type);
        let float = wgpu::TextureSampleType::Float { filterable: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("reference resolve layout"),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::FRAGMENT, true),
                storage_entry(1, wgpu::ShaderStages::FRAGMENT),
                tex(2, wgpu::TextureSampleType::Uint),
                tex(3, float),
                tex(4, float),
                tex(5, float),
                tex(6, float),
                tex(7, float),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("reference resolve pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("reference resolve pipeline"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(REFERENCE_COLOR_FORMAT.into()), Some(REFERENCE_POINT_FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        Self { layout, pipeline }
    }

    /// Per-frame resolve data over `main` and `targets`, with room for `planes` planes and
    /// `reflectors` reflectors.
    pub fn bindings(
        &self,
        device: &wgpu::Device,
        main: &GBuffer,
        targets: &ReferenceTargets,
        planes: u32,
        reflectors: usize,
    ) -> ReferenceBindings {
        let slots = planes.max(1);
        let stride = uniform_stride(device, size_of::<ResolveUniform>());
        let uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("reference resolve: uniforms"),
            size: stride * u64::from(slots),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let reflector_capacity = reflectors.max(1);
        let plane_of_reflector = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("reference resolve: plane of reflector"),
            size: 4 * reflector_capacity as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let view = |binding, view| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(view),
        };
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("reference resolve bind group"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &uniforms,
                        offset: 0,
                        size: wgpu::BufferSize::new(size_of::<ResolveUniform>() as u64),
                    }),
                },
                wgpu::BindGroupEntry { binding: 1, resource: plane_of_reflector.as_entire_binding() },
                view(2, &main.reflector_id.view),
                view(3, &main.depth.view),
                view(4, &main.normal.view),
                view(5, &targets.mirror.color.view),
                view(6, &targets.mirror.depth.view),
                view(7, &targets.mirror.normal.view),
            ],
        });
        ReferenceBindings { uniforms, stride, slots, plane_of_reflector, reflector_capacity, bind_group }
    }

    /// Records the resolve of plane `slot` (clearing the outputs first when `clear`).
    pub fn encode_resolve(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        targets: &ReferenceTargets,
        bindings: &ReferenceBindings,
        slot: u32,
        clear: bool,
    ) {
        let mut pass = begin_output_pass(encoder, targets, clear, "reference resolve pass");
        let offset = u32::try_from(u64::from(slot) * bindings.stride).expect("resolve uniforms under 4 GiB");
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bindings.bind_group, &[offset]);
        pass.draw(0..3, 0..1);
    }

    /// Records a pass that only clears the outputs (a frame where no plane is visible).
    pub fn encode_clear(&self, encoder: &mut wgpu::CommandEncoder, targets: &ReferenceTargets) {
        drop(begin_output_pass(encoder, targets, true, "reference clear pass"));
    }
}

fn begin_output_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    targets: &ReferenceTargets,
    clear: bool,
    label: &str,
) -> wgpu::RenderPass<'e> {
    let load = if clear { wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT) } else { wgpu::LoadOp::Load };
    let attachment = |view| {
        Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations { load, store: wgpu::StoreOp::Store },
        })
    };
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[attachment(&targets.color.view), attachment(&targets.point.view)],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

/// Size of one pixel per metre of distance from the camera (vertical field of view over
/// the height in pixels).
pub fn footprint_per_metre(camera: &Camera, size: [u32; 2]) -> f32 {
    2.0 * (camera.projection.fov_y * 0.5).tan() / size[1].max(1) as f32
}
