//! Projection pass: mirror every pixel against the candidate reflectors and `atomicMin`
//! the encoded offset into the intermediate buffer. Shader variants are pipelines built
//! on first use from the WGSL's override constants.

use std::collections::HashMap;

use super::{compute_pipeline, flag, loaded_texture_entry, storage_entry, tile_groups, uniform_entry};

pub const WGSL: &str = include_str!("../../../../shaders/ppr/projection.wgsl");

/// Which projection shader runs (the WGSL's override constants).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct ProjectionVariant {
    /// Per-tile shape lists in workgroup memory.
    pub tile_culling: bool,
    /// With `tile_culling`: tiles take their candidates from their super-tile's list
    /// ([`super::SuperTileListPass`], dispatched first).
    pub super_tiles: bool,
    /// Only the nearest of parallel shapes reflects a pixel.
    pub parallel_rule: bool,
    /// Occluder tests.
    pub occluder_tests: bool,
    /// Glass and water layers exist this frame.
    pub layers: bool,
    /// Record per source pixel which visible shapes it wrote for.
    pub debug_writes: bool,
    /// Record per pixel its tile's candidate-list length instead (needs `debug_writes`).
    pub debug_tile_lists: bool,
}

/// Buffers and views the projection pass reads and writes.
pub struct ProjectionBindings<'a> {
    pub uniforms: &'a wgpu::Buffer,
    pub depth: &'a wgpu::TextureView,
    pub shapes: &'a wgpu::Buffer,
    pub visible: &'a wgpu::Buffer,
    pub occluders: &'a wgpu::Buffer,
    pub intermediate: &'a wgpu::Buffer,
    pub debug_writes: &'a wgpu::Buffer,
    pub layers: &'a wgpu::Buffer,
    pub atlas: &'a wgpu::Buffer,
    /// Super-tile counts and lists (read with `super_tiles`; any buffer otherwise).
    pub super_lists: &'a wgpu::Buffer,
}

/// The projection pass.
pub struct ProjectionPass {
    module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    pipelines: HashMap<ProjectionVariant, wgpu::ComputePipeline>,
}

impl ProjectionPass {
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ppr projection"),
            entries: &[
                uniform_entry(0),
                loaded_texture_entry(1),
                storage_entry(2, true),
                storage_entry(3, true),
                storage_entry(4, true),
                storage_entry(5, false),
                storage_entry(6, false),
                storage_entry(7, true),
                storage_entry(8, false),
                storage_entry(9, true),
            ],
        });
        let module = crate::shader::module_with(
            device,
            "ppr projection",
            &[crate::shader::VIEW, crate::shader::TILE_TEST],
            WGSL,
        );
        let mut pass = Self { module, layout, pipelines: HashMap::new() };
        pass.prepare_variant(device, ProjectionVariant::default());
        pass
    }

    /// Builds the pipeline of `variant` unless it exists.
    pub fn prepare_variant(&mut self, device: &wgpu::Device, v: ProjectionVariant) {
        if self.pipelines.contains_key(&v) {
            return;
        }
        let constants = [
            ("TILE_CULLING", flag(v.tile_culling)),
            ("SUPER_TILES", flag(v.tile_culling && v.super_tiles)),
            ("PARALLEL_RULE", flag(v.parallel_rule)),
            ("OCCLUDER_TESTS", flag(v.occluder_tests)),
            ("LAYERS", flag(v.layers)),
            ("DEBUG_WRITES", flag(v.debug_writes)),
            ("DEBUG_TILE_LISTS", flag(v.debug_tile_lists)),
        ];
        let label = format!("ppr projection {v:?}");
        let pipeline = compute_pipeline(device, &label, &self.layout, &self.module, "main", &constants);
        self.pipelines.insert(v, pipeline);
    }

    pub fn bind_group(&self, device: &wgpu::Device, b: &ProjectionBindings<'_>) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ppr projection"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: b.uniforms.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(b.depth) },
                wgpu::BindGroupEntry { binding: 2, resource: b.shapes.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 3, resource: b.visible.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 4, resource: b.occluders.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 5, resource: b.intermediate.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 6, resource: b.debug_writes.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 7, resource: b.layers.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 8, resource: b.atlas.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 9, resource: b.super_lists.as_entire_binding() },
            ],
        })
    }

    /// Records the pass with `variant` (prepared beforehand).
    ///
    /// # Panics
    /// If [`Self::prepare_variant`] was not called for `variant`.
    pub fn encode(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        bind_group: &wgpu::BindGroup,
        viewport: [u32; 2],
        variant: ProjectionVariant,
    ) {
        let (x, y) = tile_groups(viewport);
        pass.set_pipeline(self.pipelines.get(&variant).expect("variant prepared in prepare()"));
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }
}
