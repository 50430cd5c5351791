//! The level on the GPU: one vertex and one index buffer, a bind group per material (base
//! colour texture with a CPU-made mip chain), and per-draw uniforms in one buffer with
//! dynamic offsets, rewritten each frame camera-relative (`world - camera`, in `f64`).

use std::ops::Range;

use glam::{DMat3, DMat4, DVec3};
use wgpu::util::DeviceExt;

use crate::forward_layouts::ForwardLayouts;
use crate::gltf_level::{AlphaBlend, LevelData, Texture, Vertex};
use crate::reflectivity::reflectivity;

/// Which faces a draw culls.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Culling {
    /// Back faces culled, counter-clockwise front faces.
    BackCcw,
    /// Back faces culled, clockwise front faces (a mirroring transform).
    BackCw,
    /// Nothing culled (double-sided material).
    None,
}

impl Culling {
    /// Every culling mode, in the order pipelines are built.
    pub const ALL: [Culling; 3] = [Culling::BackCcw, Culling::BackCw, Culling::None];
}

/// Per-draw uniform (group 2, dynamic offset).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct DrawUniform {
    model: [[f32; 4]; 4],
    normal_matrix: [[f32; 4]; 4],
    params: [f32; 4],
}
const _: () = assert!(size_of::<DrawUniform>() == 144);

/// Material uniform (group 1, binding 0).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct MaterialUniform {
    base_color: [f32; 4],
    emissive: [f32; 4],
    params: [f32; 4],
}
const _: () = assert!(size_of::<MaterialUniform>() == 48);

struct MeshDraw {
    indices: Range<u32>,
    material: usize,
    culling: Culling,
    blend: AlphaBlend,
    world: DMat4,
    reflectivity: f32,
}

/// The level's GPU resources and its draw list.
pub struct LevelMeshes {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    draws: Vec<MeshDraw>,
    draw_uniforms: wgpu::Buffer,
    draw_stride: u64,
    draw_group: wgpu::BindGroup,
    material_groups: Vec<wgpu::BindGroup>,
}

impl LevelMeshes {
    /// Uploads geometry, materials and textures.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layouts: &ForwardLayouts,
        level: &LevelData,
    ) -> Self {
        let mut vertices: Vec<Vertex> = Vec::new();
        let mut indices: Vec<u32> = Vec::new();
        let mut ranges: Vec<Vec<(Range<u32>, usize)>> = Vec::new();
        for mesh in &level.meshes {
            let mut mesh_ranges = Vec::new();
            for prim in mesh {
                let base = vertices.len() as u32;
                let first = indices.len() as u32;
                vertices.extend_from_slice(&prim.vertices);
                indices.extend(prim.indices.iter().map(|i| i + base));
                mesh_ranges.push((first..indices.len() as u32, prim.material));
            }
            ranges.push(mesh_ranges);
        }
        let mut draws = Vec::new();
        for inst in &level.instances {
            for (range, material) in &ranges[inst.mesh] {
                let m = &level.materials[*material];
                draws.push(MeshDraw {
                    indices: range.clone(),
                    material: *material,
                    culling: match (m.double_sided, inst.flips_winding()) {
                        (true, _) => Culling::None,
                        (false, false) => Culling::BackCcw,
                        (false, true) => Culling::BackCw,
                    },
                    blend: AlphaBlend::of(m),
                    world: inst.world,
                    reflectivity: reflectivity(m, inst.reflector_hint),
                });
            }
        }
        if vertices.is_empty() {
            vertices.push(Vertex::default());
            indices.extend([0, 0, 0]);
        }
        let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("walkthrough level vertices"),
            contents: bytemuck::cast_slice(&vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("walkthrough level indices"),
            contents: bytemuck::cast_slice(&indices),
            usage: wgpu::BufferUsages::INDEX,
        });
        let align = u64::from(device.limits().min_uniform_buffer_offset_alignment);
        let draw_stride = (size_of::<DrawUniform>() as u64).next_multiple_of(align);
        let draw_uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("walkthrough draw uniforms"),
            size: draw_stride * draws.len().max(1) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let draw_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("walkthrough draw uniforms"),
            layout: &layouts.draw,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &draw_uniforms,
                    offset: 0,
                    size: wgpu::BufferSize::new(size_of::<DrawUniform>() as u64),
                }),
            }],
        });
        let material_groups = material_groups(device, queue, layouts, level);
        Self { vertices, indices, draws, draw_uniforms, draw_stride, draw_group, material_groups }
    }

    /// Writes every draw's camera-relative matrices: the camera position is subtracted in
    /// `f64` before anything is rounded to `f32`.
    pub fn update_camera(&self, queue: &wgpu::Queue, camera_position: DVec3) {
        if self.draws.is_empty() {
            return;
        }
        let mut bytes = vec![0u8; self.draw_stride as usize * self.draws.len()];
        for (k, d) in self.draws.iter().enumerate() {
            let mut model = d.world;
            model.w_axis -= camera_position.extend(0.0);
            let normal = DMat3::from_mat4(d.world).inverse().transpose();
            let uniform = DrawUniform {
                model: model.as_mat4().to_cols_array_2d(),
                normal_matrix: DMat4::from_mat3(normal).as_mat4().to_cols_array_2d(),
                params: [d.reflectivity, 0.0, 0.0, 0.0],
            };
            let at = k * self.draw_stride as usize;
            bytes[at..at + size_of::<DrawUniform>()].copy_from_slice(bytemuck::bytes_of(&uniform));
        }
        queue.write_buffer(&self.draw_uniforms, 0, &bytes);
    }

    /// Records the draws with this culling and blending (pipeline and group 0 already set).
    pub fn record(&self, pass: &mut wgpu::RenderPass<'_>, culling: Culling, blend: AlphaBlend) {
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
        for (k, d) in self.draws.iter().enumerate() {
            if d.culling != culling || d.blend != blend {
                continue;
            }
            pass.set_bind_group(1, &self.material_groups[d.material], &[]);
            pass.set_bind_group(2, &self.draw_group, &[(k as u64 * self.draw_stride) as u32]);
            pass.draw_indexed(d.indices.clone(), 0, 0..1);
        }
    }
}

fn material_groups(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    layouts: &ForwardLayouts,
    level: &LevelData,
) -> Vec<wgpu::BindGroup> {
    let white = Texture { width: 1, height: 1, rgba8: vec![255; 4] };
    let views: Vec<wgpu::TextureView> = level
        .textures
        .iter()
        .chain([&white])
        .map(|t| upload_texture(device, queue, t).create_view(&Default::default()))
        .collect();
    let white_view = &views[views.len() - 1];
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("walkthrough base colour sampler"),
        address_mode_u: wgpu::AddressMode::Repeat,
        address_mode_v: wgpu::AddressMode::Repeat,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        mipmap_filter: wgpu::MipmapFilterMode::Linear,
        ..Default::default()
    });
    level
        .materials
        .iter()
        .map(|m| {
            let uniform = MaterialUniform {
                base_color: m.base_color,
                emissive: [m.emissive[0], m.emissive[1], m.emissive[2], f32::from(u8::from(m.unlit))],
                params: [m.metallic, f32::from(u8::from(AlphaBlend::of(m) == AlphaBlend::Blend)), 0.0, 0.0],
            };
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("walkthrough material"),
                contents: bytemuck::bytes_of(&uniform),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let view = m.base_color_texture.and_then(|t| views.get(t)).unwrap_or(white_view);
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("walkthrough material"),
                layout: &layouts.material,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(view) },
                    wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::Sampler(&sampler) },
                ],
            })
        })
        .collect()
}

/// Uploads an sRGB RGBA8 texture with a full mip chain, box-filtered on the CPU.
fn upload_texture(device: &wgpu::Device, queue: &wgpu::Queue, texture: &Texture) -> wgpu::Texture {
    let (w, h) = (texture.width.max(1), texture.height.max(1));
    let mip_count = 32 - w.max(h).leading_zeros();
    let gpu = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("walkthrough base colour"),
        size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        mip_level_count: mip_count,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let mut image = image::RgbaImage::from_raw(w, h, texture.rgba8.clone())
        .unwrap_or_else(|| image::RgbaImage::from_pixel(w, h, image::Rgba([255, 0, 255, 255])));
    for mip in 0..mip_count {
        let (mw, mh) = image.dimensions();
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &gpu,
                mip_level: mip,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            image.as_raw(),
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4 * mw), rows_per_image: Some(mh) },
            wgpu::Extent3d { width: mw, height: mh, depth_or_array_layers: 1 },
        );
        image = image::imageops::resize(
            &image,
            (mw / 2).max(1),
            (mh / 2).max(1),
            image::imageops::FilterType::Triangle,
        );
    }
    gpu
}
