//! The bind-group layouts of a scene raster pass: view (group 0, the pass's own),
//! material (group 1) and draw (group 2), the last two those [`crate::LevelMeshes`] binds.

use wgpu::ShaderStages;

use crate::layout_entries::{sampler_entry, texture_entry, uniform_entry};

/// Bind-group layouts of a scene raster pass (group 0 view, group 1 material, group 2 draw).
///
/// Made once per device and shared by the pass and the [`crate::LevelMeshes`] it draws, so
/// bind groups made by one fit the pipelines of the other.
pub struct SceneLayouts {
    /// Group 0: the pass's view (its uniform and whatever else its shader reads).
    pub view: wgpu::BindGroupLayout,
    /// Group 1: material uniform, base colour texture and its sampler.
    pub material: wgpu::BindGroupLayout,
    /// Group 2: the per-draw uniform (dynamic offset).
    pub draw: wgpu::BindGroupLayout,
}

impl SceneLayouts {
    /// Creates the three layouts; `view` lists group 0's entries, `label` names the pass.
    pub fn new(device: &wgpu::Device, label: &str, view: &[wgpu::BindGroupLayoutEntry]) -> Self {
        let layout = |what: &str, entries: &[wgpu::BindGroupLayoutEntry]| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(&format!("{label}: {what} layout")),
                entries,
            })
        };
        let fragment = ShaderStages::FRAGMENT;
        let base_colour = wgpu::TextureSampleType::Float { filterable: true };
        Self {
            view: layout("view", view),
            material: layout(
                "material",
                &[
                    uniform_entry(0, fragment, false),
                    texture_entry(1, fragment, base_colour),
                    sampler_entry(2, fragment),
                ],
            ),
            draw: layout("draw", &[uniform_entry(0, ShaderStages::VERTEX_FRAGMENT, true)]),
        }
    }
}

/// `size` rounded up to the device's uniform offset alignment (the stride of dynamic slots).
pub fn uniform_stride(device: &wgpu::Device, size: usize) -> u64 {
    let align = u64::from(device.limits().min_uniform_buffer_offset_alignment.max(16));
    (size as u64).div_ceil(align) * align
}
