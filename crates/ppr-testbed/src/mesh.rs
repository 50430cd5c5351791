//! A level uploaded to the GPU: one vertex and one index buffer, material bind groups, and
//! per-draw camera-relative transforms rewritten every frame.

use std::ops::Range;

use glam::{DMat3, DMat4, DVec3, Mat4};
use wgpu::util::DeviceExt;

use crate::level::{Level, LevelTexture, Vertex, is_reflective};
use crate::scene_layouts::{SceneLayouts, uniform_stride};

/// Per-draw uniform (group 2): camera-relative model matrix, normal matrix and flags.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct DrawUniform {
    /// Relative-from-object: the world transform with `camera.position` subtracted (in f64).
    pub model: [[f32; 4]; 4],
    /// World-from-object for normals: inverse transpose of the linear part (w column unused).
    pub normal_matrix: [[f32; 4]; 4],
    /// x: 1 if the surface counts as reflective for the reflector mask; y, z, w: 0.
    pub flags: [u32; 4],
}
const _: () = assert!(size_of::<DrawUniform>() == 144);

/// Material uniform (group 1, binding 0).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct MaterialUniform {
    /// Linear base colour factor.
    pub base_color: [f32; 4],
    /// Linear emissive colour; w is 1 for unlit materials.
    pub emissive: [f32; 4],
    /// Roughness, metallic, transmission, 1 if textured.
    pub params: [f32; 4],
}
const _: () = assert!(size_of::<MaterialUniform>() == 48);

/// How a draw's triangles are culled.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FaceCulling {
    /// Back faces culled; counter-clockwise triangles are front faces.
    BackCcw,
    /// Back faces culled; clockwise triangles are front faces (mirroring transform).
    BackCw,
    /// Nothing culled (double-sided material); counter-clockwise triangles are front faces
    /// (the shader's `front_facing`, which turns the normal of a back face around).
    None,
    /// Nothing culled; clockwise triangles are front faces (double-sided material with a
    /// mirroring transform, or seen through a mirror).
    NoneCw,
}

impl FaceCulling {
    /// The culling seen through a mirror: the winding flips, double-sided or not (a
    /// double-sided surface must still know its front, or its normal and lighting turn
    /// around in the mirrored view).
    pub fn mirrored(self) -> Self {
        match self {
            Self::BackCcw => Self::BackCw,
            Self::BackCw => Self::BackCcw,
            Self::None => Self::NoneCw,
            Self::NoneCw => Self::None,
        }
    }
}

/// One indexed draw: a primitive of an instance.
#[derive(Clone, Debug)]
pub struct MeshDraw {
    /// Range in the shared index buffer (indices already include the vertex offset).
    pub indices: Range<u32>,
    /// Material bind group index.
    pub material: usize,
    /// Slot in the draw uniform buffer.
    pub slot: u32,
    /// Culling and winding of the draw (unmirrored view).
    pub culling: FaceCulling,
}

/// A level's GPU resources.
pub struct LevelMeshes {
    vertex_buffer: wgpu::Buffer,
    index_buffer: wgpu::Buffer,
    draws: Vec<MeshDraw>,
    /// World transform of each draw (its instance's), kept in f64 for the per-frame update.
    draw_worlds: Vec<DMat4>,
    draw_flags: Vec<[u32; 4]>,
    draw_buffer: wgpu::Buffer,
    draw_stride: u64,
    draw_bind_group: wgpu::BindGroup,
    material_bind_groups: Vec<wgpu::BindGroup>,
    _textures: Vec<wgpu::Texture>,
}

impl LevelMeshes {
    /// Uploads geometry, materials and textures (with CPU-made mip chains).
    ///
    /// # Panics
    /// If the level breaks the invariants of [`Level::validate`].
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, layouts: &SceneLayouts, level: &Level) -> Self {
        let mut vertices: Vec<Vertex> = Vec::new();
        let mut indices: Vec<u32> = Vec::new();
        // Each mesh's primitives are uploaded once; instances share them.
        let mut prim_ranges: Vec<Vec<(Range<u32>, usize)>> = Vec::with_capacity(level.meshes.len());
        for mesh in &level.meshes {
            let mut ranges = Vec::with_capacity(mesh.primitives.len());
            for prim in &mesh.primitives {
                let base = u32::try_from(vertices.len()).expect("fewer than 2^32 vertices");
                let first = u32::try_from(indices.len()).expect("fewer than 2^32 indices");
                vertices.extend_from_slice(&prim.vertices);
                indices.extend(prim.indices.iter().map(|i| i + base));
                ranges.push((first..first + prim.indices.len() as u32, prim.material));
            }
            prim_ranges.push(ranges);
        }
        let mut draws = Vec::new();
        let mut draw_worlds = Vec::new();
        let mut draw_flags = Vec::new();
        for inst in &level.instances {
            for (range, material) in &prim_ranges[inst.mesh] {
                let m = &level.materials[*material];
                let culling = match (m.double_sided, inst.flips_winding()) {
                    (true, false) => FaceCulling::None,
                    (true, true) => FaceCulling::NoneCw,
                    (false, false) => FaceCulling::BackCcw,
                    (false, true) => FaceCulling::BackCw,
                };
                let reflective = inst.reflector_hint.unwrap_or_else(|| is_reflective(m));
                let slot = u32::try_from(draws.len()).expect("fewer than 2^32 draws");
                draws.push(MeshDraw { indices: range.clone(), material: *material, slot, culling });
                draw_worlds.push(inst.world);
                draw_flags.push([u32::from(reflective), 0, 0, 0]);
            }
        }
        if vertices.is_empty() {
            vertices.push(Vertex::default());
        }
        if indices.is_empty() {
            indices.extend([0, 0, 0]);
        }
        let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("level meshes: vertices"),
            contents: bytemuck::cast_slice(&vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let index_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("level meshes: indices"),
            contents: bytemuck::cast_slice(&indices),
            usage: wgpu::BufferUsages::INDEX,
        });
        let draw_stride = uniform_stride(device, size_of::<DrawUniform>());
        let draw_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("level meshes: draw uniforms"),
            size: draw_stride * draws.len().max(1) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let draw_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("level meshes: draw bind group"),
            layout: &layouts.draw,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &draw_buffer,
                    offset: 0,
                    size: wgpu::BufferSize::new(size_of::<DrawUniform>() as u64),
                }),
            }],
        });
        let (material_bind_groups, textures) = upload_materials(device, queue, layouts, level);
        Self {
            vertex_buffer,
            index_buffer,
            draws,
            draw_worlds,
            draw_flags,
            draw_buffer,
            draw_stride,
            draw_bind_group,
            material_bind_groups,
            _textures: textures,
        }
    }

    /// Rewrites every draw's model matrix relative to `camera_position` (f64, then f32).
    pub fn update_camera(&self, queue: &wgpu::Queue, camera_position: DVec3) {
        let mut bytes = vec![0u8; self.draw_stride as usize * self.draws.len()];
        for (k, (world, flags)) in self.draw_worlds.iter().zip(&self.draw_flags).enumerate() {
            let u = draw_uniform(world, camera_position, *flags);
            let at = k * self.draw_stride as usize;
            bytes[at..at + size_of::<DrawUniform>()].copy_from_slice(bytemuck::bytes_of(&u));
        }
        if !bytes.is_empty() {
            queue.write_buffer(&self.draw_buffer, 0, &bytes);
        }
    }

    /// The draws, in level order.
    pub fn draws(&self) -> &[MeshDraw] {
        &self.draws
    }

    /// Records every draw of the given culling into `pass` (pipeline and group 0 already set).
    pub fn record_draws(&self, pass: &mut wgpu::RenderPass<'_>, culling: FaceCulling) {
        pass.set_vertex_buffer(0, self.vertex_buffer.slice(..));
        pass.set_index_buffer(self.index_buffer.slice(..), wgpu::IndexFormat::Uint32);
        for d in self.draws.iter().filter(|d| d.culling == culling) {
            let offset =
                u32::try_from(u64::from(d.slot) * self.draw_stride).expect("draw buffer under 4 GiB");
            pass.set_bind_group(1, &self.material_bind_groups[d.material], &[]);
            pass.set_bind_group(2, &self.draw_bind_group, &[offset]);
            pass.draw_indexed(d.indices.clone(), 0, 0..1);
        }
    }

    /// The vertex buffer layout of [`Vertex`].
    pub fn vertex_layout() -> wgpu::VertexBufferLayout<'static> {
        const ATTRIBUTES: [wgpu::VertexAttribute; 3] =
            wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2];
        wgpu::VertexBufferLayout {
            array_stride: size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &ATTRIBUTES,
        }
    }
}

/// The draw uniform of an object with world transform `world` seen from `camera_position`.
///
/// The translation is subtracted in f64 before rounding, so objects far from the origin
/// keep their precision near the camera.
pub fn draw_uniform(world: &DMat4, camera_position: DVec3, flags: [u32; 4]) -> DrawUniform {
    let mut rel = *world;
    rel.w_axis = (world.w_axis.truncate() - camera_position).extend(1.0);
    let linear = DMat3::from_mat4(*world);
    let normal = if linear.determinant().abs() > 1e-300 { linear.inverse().transpose() } else { linear };
    DrawUniform {
        model: rel.as_mat4().to_cols_array_2d(),
        normal_matrix: Mat4::from_mat3(normal.as_mat3()).to_cols_array_2d(),
        flags,
    }
}

fn upload_materials(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    layouts: &SceneLayouts,
    level: &Level,
) -> (Vec<wgpu::BindGroup>, Vec<wgpu::Texture>) {
    let white = LevelTexture { name: "white".into(), width: 1, height: 1, rgba8: vec![255; 4] };
    let mut textures: Vec<wgpu::Texture> =
        level.textures.iter().map(|t| upload_texture(device, queue, t)).collect();
    textures.push(upload_texture(device, queue, &white));
    let views: Vec<wgpu::TextureView> = textures.iter().map(|t| t.create_view(&Default::default())).collect();
    let white_view = views.last().expect("the white texture was just pushed");
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("level meshes: base colour sampler"),
        address_mode_u: wgpu::AddressMode::Repeat,
        address_mode_v: wgpu::AddressMode::Repeat,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        mipmap_filter: wgpu::MipmapFilterMode::Linear,
        ..Default::default()
    });
    let groups = level
        .materials
        .iter()
        .map(|m| {
            let uniform = MaterialUniform {
                base_color: m.base_color,
                emissive: [m.emissive[0], m.emissive[1], m.emissive[2], if m.unlit { 1.0 } else { 0.0 }],
                params: [
                    m.roughness,
                    m.metallic,
                    m.transmission,
                    if m.base_color_texture.is_some() { 1.0 } else { 0.0 },
                ],
            };
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("level meshes: material uniform"),
                contents: bytemuck::bytes_of(&uniform),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let view = m.base_color_texture.map_or(white_view, |t| &views[t]);
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("level meshes: material bind group"),
                layout: &layouts.material,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(view) },
                    wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::Sampler(&sampler) },
                ],
            })
        })
        .collect();
    (groups, textures)
}

/// Uploads an sRGB RGBA8 texture with a full mip chain (box-filtered on the CPU, in sRGB space).
fn upload_texture(device: &wgpu::Device, queue: &wgpu::Queue, texture: &LevelTexture) -> wgpu::Texture {
    let (w, h) = (texture.width.max(1), texture.height.max(1));
    let mip_count = 32 - w.max(h).leading_zeros();
    let gpu = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("level meshes: base colour texture"),
        size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        mip_level_count: mip_count,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let mut level_image = image::RgbaImage::from_raw(w, h, texture.rgba8.clone())
        .unwrap_or_else(|| image::RgbaImage::from_pixel(w, h, image::Rgba([255, 0, 255, 255])));
    for mip in 0..mip_count {
        let (mw, mh) = level_image.dimensions();
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &gpu,
                mip_level: mip,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            level_image.as_raw(),
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4 * mw), rows_per_image: Some(mh) },
            wgpu::Extent3d { width: mw, height: mh, depth_or_array_layers: 1 },
        );
        let (nw, nh) = ((mw / 2).max(1), (mh / 2).max(1));
        level_image = image::imageops::resize(&level_image, nw, nh, image::imageops::FilterType::Triangle);
    }
    gpu
}
