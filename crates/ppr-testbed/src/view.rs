//! Per-view GPU data of the scene raster: view uniforms in dynamic slots (the main view and
//! one per mirrored view) and the reflector shapes, camera-relative.

use glam::{DVec3, Mat4};
use ppr_format::ReflectorSet;

use crate::scene_layouts::{SceneLayouts, uniform_stride};

/// Lighting of the G-buffer pass: one directional light plus ambient, no shadows
/// (`ppr-scene-gpu`'s, the walkthrough's too).
pub use ppr_scene_gpu::Lighting;

/// How reflector pixels are recognised in the G-buffer pass (see [`ViewUniform::mask`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReflectorMaskParams {
    /// Largest distance of a fragment from a reflector's plane, metres, at the camera.
    pub plane_tolerance: f32,
    /// Added to `plane_tolerance` per metre of distance from the camera.
    pub plane_tolerance_per_metre: f32,
    /// Smallest cosine between the fragment's normal and the reflector's normal.
    pub min_normal_cos: f32,
    /// Only surfaces whose draw is reflective (material or `extras.ppr.reflector`) count;
    /// when false any surface on a reflector's plane inside its rectangle counts.
    pub require_reflective_material: bool,
}

impl Default for ReflectorMaskParams {
    fn default() -> Self {
        Self {
            plane_tolerance: 0.004,
            plane_tolerance_per_metre: 2e-4,
            min_normal_cos: 0.95,
            require_reflective_material: true,
        }
    }
}

/// View uniform (group 0, binding 0), one per view slot.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ViewUniform {
    /// Clip-from-relative matrix (for mirrored views: mirror and oblique projection included).
    pub clip_from_rel: [[f32; 4]; 4],
    /// xyz: unit direction towards the light; w: its intensity.
    pub light: [f32; 4],
    /// rgb: ambient colour; w: unused.
    pub ambient: [f32; 4],
    /// Reflector mask: x = number of shapes tested (0 disables the mask), y = 1 if the
    /// draw must be reflective, z, w unused.
    pub mask: [u32; 4],
    /// Reflector mask tolerances: plane distance, its growth per metre, min normal cosine, unused.
    pub tolerance: [f32; 4],
}
const _: () = assert!(size_of::<ViewUniform>() == 128);

impl ViewUniform {
    /// A view with the given matrix, lighting and mask (`shape_count` 0 disables the mask).
    pub fn new(
        clip_from_rel: Mat4,
        lighting: &Lighting,
        mask: &ReflectorMaskParams,
        shape_count: u32,
    ) -> Self {
        let (light, ambient) = lighting.uniform_vectors();
        Self {
            clip_from_rel: clip_from_rel.to_cols_array_2d(),
            light,
            ambient,
            mask: [shape_count, u32::from(mask.require_reflective_material), 0, 0],
            tolerance: [mask.plane_tolerance, mask.plane_tolerance_per_metre, mask.min_normal_cos, 0.0],
        }
    }
}

/// A reflector rectangle as the shaders read it (storage buffer element, 64 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ReflectorShape {
    /// xyz: centre relative to the camera; w: 1 if enabled, 0 if disabled.
    pub center: [f32; 4],
    /// xyz: unit axis u; w: half extent along u.
    pub axis_u: [f32; 4],
    /// xyz: unit axis v; w: half extent along v.
    pub axis_v: [f32; 4],
    /// xyz: unit normal of the reflecting side; w: unused.
    pub normal: [f32; 4],
}

impl ReflectorShape {
    /// The shapes of `set` relative to `camera_position` (differences taken in f64).
    pub fn from_set(set: &ReflectorSet, camera_position: DVec3) -> Vec<Self> {
        set.reflectors
            .iter()
            .map(|r| {
                let c = (r.center - camera_position).as_vec3();
                let (u, v, n) = (r.axis_u.as_vec3(), r.axis_v.as_vec3(), r.normal.as_vec3());
                Self {
                    center: [c.x, c.y, c.z, if r.enabled { 1.0 } else { 0.0 }],
                    axis_u: [u.x, u.y, u.z, r.half_extents.x as f32],
                    axis_v: [v.x, v.y, v.z, r.half_extents.y as f32],
                    normal: [n.x, n.y, n.z, 0.0],
                }
            })
            .collect()
    }
}

/// The view slots and reflector shapes of a frame, and their bind group.
pub struct ViewBindings {
    uniforms: wgpu::Buffer,
    shapes: wgpu::Buffer,
    stride: u64,
    slots: u32,
    shape_capacity: u64,
    bind_group: wgpu::BindGroup,
}

impl ViewBindings {
    /// Room for `slots` views and `shapes` reflectors (both at least 1).
    pub fn new(device: &wgpu::Device, layouts: &SceneLayouts, slots: u32, shapes: usize) -> Self {
        let slots = slots.max(1);
        let stride = uniform_stride(device, size_of::<ViewUniform>());
        let shape_capacity = shapes.max(1) as u64;
        let uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("scene raster: view uniforms"),
            size: stride * u64::from(slots),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let shapes = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("scene raster: reflector shapes"),
            size: shape_capacity * size_of::<ReflectorShape>() as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("scene raster: view bind group"),
            layout: &layouts.view,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &uniforms,
                        offset: 0,
                        size: wgpu::BufferSize::new(size_of::<ViewUniform>() as u64),
                    }),
                },
                wgpu::BindGroupEntry { binding: 1, resource: shapes.as_entire_binding() },
            ],
        });
        Self { uniforms, shapes, stride, slots, shape_capacity, bind_group }
    }

    /// Whether this has room for `slots` views and `shapes` reflectors.
    pub fn fits(&self, slots: u32, shapes: usize) -> bool {
        slots <= self.slots && shapes as u64 <= self.shape_capacity
    }

    /// Writes the view uniform of `slot`.
    ///
    /// # Panics
    /// If `slot` is out of range.
    pub fn write_view(&self, queue: &wgpu::Queue, slot: u32, view: &ViewUniform) {
        assert!(slot < self.slots, "view slot {slot} out of range ({} slots)", self.slots);
        queue.write_buffer(&self.uniforms, u64::from(slot) * self.stride, bytemuck::bytes_of(view));
    }

    /// Writes the reflector shapes (at most the capacity given to [`ViewBindings::new`]).
    pub fn write_shapes(&self, queue: &wgpu::Queue, shapes: &[ReflectorShape]) {
        let n = shapes.len().min(self.shape_capacity as usize);
        if n > 0 {
            queue.write_buffer(&self.shapes, 0, bytemuck::cast_slice(&shapes[..n]));
        }
    }

    /// Binds group 0 for the view in `slot`.
    pub fn bind(&self, pass: &mut wgpu::RenderPass<'_>, slot: u32) {
        let offset = u32::try_from(u64::from(slot) * self.stride).expect("view buffer under 4 GiB");
        pass.set_bind_group(0, &self.bind_group, &[offset]);
    }
}
