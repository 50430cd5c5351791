//! A level uploaded to the GPU: one vertex and one index buffer, a bind group per material
//! (`material_textures.rs`), and per-draw uniforms in one buffer with dynamic offsets,
//! rewritten each frame camera-relative (`world - camera`, in `f64`).

use std::ops::Range;

use glam::{DMat3, DMat4, DVec3, Mat4};
use ppr_level::AlphaMode;
use wgpu::util::DeviceExt;

use crate::level_data::{LevelData, Material, MeshInstance, Vertex};
use crate::material_textures::material_bind_groups;
use crate::scene_layouts::{SceneLayouts, uniform_stride};

/// Per-draw uniform (group 2): camera-relative model matrix, normal matrix and the pass's
/// own numbers.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct DrawUniform {
    /// Relative-from-object: the world transform with `camera.position` subtracted (in f64).
    pub model: [[f32; 4]; 4],
    /// World-from-object for normals: inverse transpose of the linear part (w column unused).
    pub normal_matrix: [[f32; 4]; 4],
    /// What [`SurfaceRules::draw_params`] gives the draw (`scene_raster.wgsl`'s `Draw.params`).
    pub params: [u32; 4],
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
    /// What [`SurfaceRules::material_params`] gives the material.
    pub params: [f32; 4],
}
const _: () = assert!(size_of::<MaterialUniform>() == 48);

/// The numbers a pass reads per material and per draw besides the shared ones: its rules
/// for which surfaces reflect and how they are shaded.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceRules {
    /// `MaterialUniform::params` of a material.
    pub material_params: fn(&Material) -> [f32; 4],
    /// `DrawUniform::params` of a draw: its material on its instance.
    pub draw_params: fn(&Material, &MeshInstance) -> [u32; 4],
}

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

    /// The pipeline's front face and cull mode.
    pub fn primitive_state(self) -> wgpu::PrimitiveState {
        let (front_face, cull_mode) = match self {
            Self::BackCcw => (wgpu::FrontFace::Ccw, Some(wgpu::Face::Back)),
            Self::BackCw => (wgpu::FrontFace::Cw, Some(wgpu::Face::Back)),
            Self::None => (wgpu::FrontFace::Ccw, None),
            Self::NoneCw => (wgpu::FrontFace::Cw, None),
        };
        wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            front_face,
            cull_mode,
            ..Default::default()
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
    /// Whether the material's alpha mode is `BLEND` (a pass may draw these apart).
    pub blended: bool,
}

/// A level's GPU resources.
pub struct LevelMeshes {
    vertex_buffer: wgpu::Buffer,
    index_buffer: wgpu::Buffer,
    draws: Vec<MeshDraw>,
    /// World transform of each draw (its instance's), kept in f64 for the per-frame update.
    draw_worlds: Vec<DMat4>,
    draw_params: Vec<[u32; 4]>,
    draw_buffer: wgpu::Buffer,
    draw_stride: u64,
    draw_bind_group: wgpu::BindGroup,
    material_bind_groups: Vec<wgpu::BindGroup>,
}

impl LevelMeshes {
    /// Uploads geometry, materials and textures (with CPU-made mip chains); `rules` gives
    /// the pass's own numbers per material and draw.
    ///
    /// # Panics
    /// If the level breaks the invariants of [`LevelData::validate`].
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layouts: &SceneLayouts,
        level: &LevelData,
        rules: &SurfaceRules,
    ) -> Self {
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
        let mut draw_params = Vec::new();
        for inst in &level.instances {
            for (range, material) in &prim_ranges[inst.mesh] {
                let m = &level.materials[*material];
                let culling = match (m.double_sided, inst.flips_winding()) {
                    (true, false) => FaceCulling::None,
                    (true, true) => FaceCulling::NoneCw,
                    (false, false) => FaceCulling::BackCcw,
                    (false, true) => FaceCulling::BackCw,
                };
                let slot = u32::try_from(draws.len()).expect("fewer than 2^32 draws");
                let blended = matches!(m.alpha_mode, AlphaMode::Blend);
                draws.push(MeshDraw { indices: range.clone(), material: *material, slot, culling, blended });
                draw_worlds.push(inst.world);
                draw_params.push((rules.draw_params)(m, inst));
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
        let material_bind_groups = material_bind_groups(device, queue, layouts, level, rules.material_params);
        Self {
            vertex_buffer,
            index_buffer,
            draws,
            draw_worlds,
            draw_params,
            draw_buffer,
            draw_stride,
            draw_bind_group,
            material_bind_groups,
        }
    }

    /// Rewrites every draw's model matrix relative to `camera_position` (f64, then f32).
    pub fn update_camera(&self, queue: &wgpu::Queue, camera_position: DVec3) {
        let mut bytes = vec![0u8; self.draw_stride as usize * self.draws.len()];
        for (k, (world, params)) in self.draw_worlds.iter().zip(&self.draw_params).enumerate() {
            let u = draw_uniform(world, camera_position, *params);
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

    /// Records every draw `keep` accepts into `pass` (pipeline and group 0 already set).
    pub fn record_draws(&self, pass: &mut wgpu::RenderPass<'_>, keep: impl Fn(&MeshDraw) -> bool) {
        pass.set_vertex_buffer(0, self.vertex_buffer.slice(..));
        pass.set_index_buffer(self.index_buffer.slice(..), wgpu::IndexFormat::Uint32);
        for d in self.draws.iter().filter(|d| keep(d)) {
            let offset =
                u32::try_from(u64::from(d.slot) * self.draw_stride).expect("draw buffer under 4 GiB");
            pass.set_bind_group(1, &self.material_bind_groups[d.material], &[]);
            pass.set_bind_group(2, &self.draw_bind_group, &[offset]);
            pass.draw_indexed(d.indices.clone(), 0, 0..1);
        }
    }

    /// The vertex buffer layout of [`Vertex`] (locations 0 position, 1 normal, 2 UV).
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
pub fn draw_uniform(world: &DMat4, camera_position: DVec3, params: [u32; 4]) -> DrawUniform {
    let mut rel = *world;
    rel.w_axis = (world.w_axis.truncate() - camera_position).extend(1.0);
    let linear = DMat3::from_mat4(*world);
    let normal = if linear.determinant().abs() > 1e-300 { linear.inverse().transpose() } else { linear };
    DrawUniform {
        model: rel.as_mat4().to_cols_array_2d(),
        normal_matrix: Mat4::from_mat3(normal.as_mat3()).to_cols_array_2d(),
        params,
    }
}
