//! Assembles each pass's WGSL with the shared module (WGSL has no `#include`).

/// The shared declarations of the baseline passes: frame uniform, reflector planes,
/// position reconstruction, projection and the screen-space ray.
pub const COMMON: &str = include_str!("../../../shaders/baselines/common.wgsl");

/// The layout of the Hi-Z pyramid's atlas, shared by the two Hi-Z passes (after [`COMMON`]).
pub const HIZ_LAYOUT: &str = include_str!("../../../shaders/baselines/hiz_layout.wgsl");

/// Source of the ray-march pass (brute-force and low-quality SSR).
pub const SSR_MARCH: &str = include_str!("../../../shaders/baselines/ssr_march.wgsl");
/// Source of the Hi-Z pyramid build.
pub const HIZ_BUILD: &str = include_str!("../../../shaders/baselines/hiz_build.wgsl");
/// Source of the Hi-Z trace.
pub const HIZ_TRACE: &str = include_str!("../../../shaders/baselines/hiz_trace.wgsl");
/// Source of the SSPR hash clear (stands alone).
pub const SSPR_CLEAR: &str = include_str!("../../../shaders/baselines/sspr_clear.wgsl");
/// Source of the SSPR projection.
pub const SSPR_PROJECT: &str = include_str!("../../../shaders/baselines/sspr_project.wgsl");
/// Source of the SSPR resolve.
pub const SSPR_RESOLVE: &str = include_str!("../../../shaders/baselines/sspr_resolve.wgsl");
/// Source of the texture copy (stands alone).
pub const TEXTURE_COPY: &str = include_str!("../../../shaders/baselines/texture_copy.wgsl");

/// The complete source of a pass: the shared `modules` in order, then the pass.
pub fn assemble(modules: &[&str], pass: &str) -> String {
    let mut s = String::new();
    for m in modules {
        s.push_str(m);
        s.push('\n');
    }
    s.push_str(pass);
    s
}

/// [`assemble`] with [`COMMON`] alone.
pub fn with_common(pass: &str) -> String {
    assemble(&[COMMON], pass)
}

/// [`assemble`] with [`COMMON`] and [`HIZ_LAYOUT`].
pub fn with_hiz_layout(pass: &str) -> String {
    assemble(&[COMMON, HIZ_LAYOUT], pass)
}

/// Creates the shader module of a pass from its complete `source`.
pub fn module(device: &wgpu::Device, label: &str, source: String) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    })
}

/// Every pass's complete source with its name (for validation tests and tools).
pub fn all_sources() -> Vec<(&'static str, String)> {
    vec![
        ("ssr_march", with_common(SSR_MARCH)),
        ("hiz_build", with_hiz_layout(HIZ_BUILD)),
        ("hiz_trace", with_hiz_layout(HIZ_TRACE)),
        ("sspr_clear", SSPR_CLEAR.to_owned()),
        ("sspr_project", with_common(SSPR_PROJECT)),
        ("sspr_resolve", with_common(SSPR_RESOLVE)),
        ("texture_copy", TEXTURE_COPY.to_owned()),
    ]
}

#[cfg(test)]
mod tests {
    /// Every pass parses and validates (clear messages without a GPU).
    #[test]
    fn every_pass_validates() {
        for (name, source) in super::all_sources() {
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
}
