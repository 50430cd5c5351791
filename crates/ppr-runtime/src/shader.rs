//! Assembles each pass's WGSL with the shared modules (WGSL has no `#include`).
//!
//! Every pass gets `encoding.wgsl` and `common.wgsl`; passes that declare
//! `frame: FrameUniforms` may add [`VIEW`]; the tile-culling passes add [`TILE_TEST`], the
//! reflection passes [`SHADING`].

/// The shared declarations every pass sees: encoding, then frame and shape types.
const SHARED: &str =
    concat!(include_str!("../shaders/encoding.wgsl"), "\n", include_str!("../shaders/common.wgsl"), "\n");

/// Pixel ↔ camera-relative position and depth validity (needs `frame`).
pub const VIEW: &str = include_str!("../shaders/view.wgsl");

/// Tile culling: the box test, the tile box, ordered compaction, the super-tile grid
/// (needs `frame`, `depth_tex` and [`VIEW`]).
pub const TILE_TEST: &str = include_str!("../shaders/tile_test.wgsl");

/// Hole filling, sampling, anti-bleeding (needs `frame`, `color_tex`, `linear_sampler`
/// and [`VIEW`]).
pub const SHADING: &str = include_str!("../shaders/shading.wgsl");

/// The source of a pass: the shared modules, then `modules`, then the pass itself.
pub fn source_with(modules: &[&str], pass: &str) -> String {
    let mut s =
        String::with_capacity(SHARED.len() + pass.len() + modules.iter().map(|m| m.len() + 1).sum::<usize>());
    s.push_str(SHARED);
    for m in modules {
        s.push_str(m);
        s.push('\n');
    }
    s.push_str(pass);
    s
}

/// The source of a pass (or a test kernel) with only the shared modules.
pub fn source(pass: &str) -> String {
    source_with(&[], pass)
}

/// Creates the shader module of a pass with extra shared modules.
pub fn module_with(device: &wgpu::Device, label: &str, modules: &[&str], pass: &str) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source_with(modules, pass).into()),
    })
}

/// Creates the shader module of a pass (or a test kernel) with only the shared modules.
pub fn module(device: &wgpu::Device, label: &str, pass: &str) -> wgpu::ShaderModule {
    module_with(device, label, &[], pass)
}

/// Every pass's WGSL with the modules it is built with (for validation).
pub fn all_passes() -> Vec<(&'static str, String)> {
    use crate::passes::*;
    vec![
        ("clear", source(clear::WGSL)),
        ("tile classify", source_with(&[VIEW], tile_classify::WGSL)),
        ("super-tile lists", source_with(&[VIEW, TILE_TEST], super_tile_lists::WGSL)),
        ("block lists", source_with(&[VIEW, TILE_TEST], block_lists::WGSL)),
        ("projection", source_with(&[VIEW, TILE_TEST], projection::WGSL)),
        ("reflection", source_with(&[VIEW, SHADING], reflection::WGSL)),
        ("layer reflection", source_with(&[VIEW, SHADING], layer_reflection::WGSL)),
        ("downsample", source_with(&[VIEW], downsample::WGSL)),
        ("upsample", source_with(&[VIEW], upsample::WGSL)),
    ]
}

#[cfg(test)]
mod tests {
    /// Every pass parses and validates (clear messages without a GPU).
    #[test]
    fn every_pass_validates() {
        for (name, source) in super::all_passes() {
            let module = naga::front::wgsl::parse_str(&source)
                .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(&source)));
            naga::valid::Validator::new(
                naga::valid::ValidationFlags::all(),
                naga::valid::Capabilities::all(),
            )
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(&source)));
        }
    }

    /// The WGSL structs the Rust side uploads have the sizes of their `#[repr(C)]` mirrors
    /// (a field added on one side only would shift every field after it).
    #[test]
    fn shared_structs_match_their_rust_mirrors() {
        use crate::gpu_types::{FrameUniforms, GpuLayer, GpuShape};
        let source = super::source("");
        let module =
            naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)));
        let size = |name: &str| {
            module
                .types
                .iter()
                .find_map(|(_, t)| match &t.inner {
                    naga::TypeInner::Struct { span, .. } if t.name.as_deref() == Some(name) => {
                        Some(*span as usize)
                    }
                    _ => None,
                })
                .unwrap_or_else(|| panic!("no struct {name} in the shared WGSL"))
        };
        assert_eq!(size("FrameUniforms"), std::mem::size_of::<FrameUniforms>());
        assert_eq!(size("Shape"), std::mem::size_of::<GpuShape>());
        assert_eq!(size("Layer"), std::mem::size_of::<GpuLayer>());
        assert_eq!(size("EncodingParams"), std::mem::size_of::<crate::encoding::EncodingParams>());
    }
}
