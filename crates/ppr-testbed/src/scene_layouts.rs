//! The G-buffer's bind-group layouts: `ppr-scene-gpu`'s material (1) and draw (2) groups,
//! and its own view group (0): the view uniform in dynamic slots and the reflector shapes.

use ppr_scene_gpu::layout_entries::{storage_entry, uniform_entry};
pub use ppr_scene_gpu::{SceneLayouts, uniform_stride};

/// The layouts of the G-buffer pass, shared by [`crate::GBufferPass`],
/// [`crate::LevelMeshes`] and [`crate::ViewBindings`], so bind groups made by one fit the
/// pipelines of the other.
pub fn gbuffer_layouts(device: &wgpu::Device) -> SceneLayouts {
    let view = [
        uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT, true),
        storage_entry(1, wgpu::ShaderStages::FRAGMENT),
    ];
    SceneLayouts::new(device, "scene raster", &view)
}
