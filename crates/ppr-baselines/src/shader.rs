//! Assembles each pass's WGSL with the shared module (WGSL has no `#include`).

/// The shared declarations of the baseline passes: frame uniform, reflector planes,
/// position reconstruction, projection and the screen-space ray.
pub const COMMON: &str = include_str!("../shaders/common.wgsl");

/// The layout of the Hi-Z pyramid's atlas, shared by the two Hi-Z passes (after [`COMMON`]).
pub const HIZ_LAYOUT: &str = include_str!("../shaders/hiz_layout.wgsl");

/// Source of the ray-march pass (brute-force and low-quality SSR).
pub const SSR_MARCH: &str = include_str!("../shaders/ssr_march.wgsl");
/// Source of ssr-glossy's roughness blur.
pub const SSR_GLOSSY_BLUR: &str = include_str!("../shaders/ssr_glossy_blur.wgsl");
/// Source of the Hi-Z pyramid build.
pub const HIZ_BUILD: &str = include_str!("../shaders/hiz_build.wgsl");
/// Source of the Hi-Z trace.
pub const HIZ_TRACE: &str = include_str!("../shaders/hiz_trace.wgsl");
/// Source of the SSPR hash clear (stands alone).
pub const SSPR_CLEAR: &str = include_str!("../shaders/sspr_clear.wgsl");
/// Source of the SSPR projection.
pub const SSPR_PROJECT: &str = include_str!("../shaders/sspr_project.wgsl");
/// Source of the SSPR resolve.
pub const SSPR_RESOLVE: &str = include_str!("../shaders/sspr_resolve.wgsl");
/// Source of the texture copy (stands alone).
pub const TEXTURE_COPY: &str = include_str!("../shaders/texture_copy.wgsl");

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

/// Creates the shader module of a pass from its complete `source`, with the runtime's
/// checks ([`ppr_runtime::shader::runtime_checks`]), so that PPR and the baselines are
/// timed alike.
pub fn module(device: &wgpu::Device, label: &str, source: String) -> wgpu::ShaderModule {
    ppr_runtime::shader::create_module(device, label, source)
}

/// Every pass's complete source with its name (for validation tests and tools).
pub fn all_sources() -> Vec<(&'static str, String)> {
    vec![
        ("ssr_march", with_common(SSR_MARCH)),
        ("ssr_glossy_blur", with_common(SSR_GLOSSY_BLUR)),
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
    use super::*;
    use crate::gpu_types::{
        BaselineFrame, ClearUniform, GlossyBlurUniform, GpuReflectorPlane, HiZUniform, NO_LAYER, SsprUniform,
        SsrUniform,
    };
    use crate::hiz_pyramid::{DownsampleUniform, HIZ_MAX_LEVELS, HiZLevelsUniform, SKY_DEPTH};

    fn parse(source: &str) -> naga::Module {
        naga::front::wgsl::parse_str(source).unwrap_or_else(|e| panic!("{}", e.emit_to_string(source)))
    }

    /// Size of the WGSL struct `name` in `module`.
    fn struct_size(module: &naga::Module, name: &str) -> usize {
        module
            .types
            .iter()
            .find_map(|(_, t)| match &t.inner {
                naga::TypeInner::Struct { span, .. } if t.name.as_deref() == Some(name) => {
                    Some(*span as usize)
                }
                _ => None,
            })
            .unwrap_or_else(|| panic!("no struct {name}"))
    }

    /// The literal value of the WGSL constant `name` in `module`.
    fn constant(module: &naga::Module, name: &str) -> naga::Literal {
        let c = module
            .constants
            .iter()
            .find(|(_, c)| c.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("no constant {name}"))
            .1;
        match module.global_expressions[c.init] {
            naga::Expression::Literal(l) => l,
            ref e => panic!("{name} is not a literal: {e:?}"),
        }
    }

    /// The numbers both sides use: every uniform and storage struct has the size of its
    /// `#[repr(C)]` mirror, and the shared constants have the Rust values.
    #[test]
    fn wgsl_structs_and_constants_match_rust() {
        let trace = parse(&with_hiz_layout(HIZ_TRACE));
        let build = parse(&with_hiz_layout(HIZ_BUILD));
        for (name, size) in [
            ("BaselineFrame", size_of::<BaselineFrame>()),
            ("ReflectorPlane", size_of::<GpuReflectorPlane>()),
            ("HiZParams", size_of::<HiZUniform>()),
            ("HiZLevels", size_of::<HiZLevelsUniform>()),
        ] {
            assert_eq!(struct_size(&trace, name), size, "{name}");
        }
        assert_eq!(struct_size(&build, "DownsampleParams"), size_of::<DownsampleUniform>());
        assert_eq!(struct_size(&parse(&with_common(SSR_MARCH)), "SsrParams"), size_of::<SsrUniform>());
        assert_eq!(
            struct_size(&parse(&with_common(SSR_GLOSSY_BLUR)), "GlossyBlurParams"),
            size_of::<GlossyBlurUniform>()
        );
        assert_eq!(struct_size(&parse(&with_common(SSPR_PROJECT)), "SsprParams"), size_of::<SsprUniform>());
        assert_eq!(struct_size(&parse(SSPR_CLEAR), "ClearParams"), size_of::<ClearUniform>());
        assert_eq!(constant(&trace, "BASELINE_SKY_DEPTH"), naga::Literal::F32(SKY_DEPTH));
        assert_eq!(constant(&trace, "BASELINE_NO_LAYER"), naga::Literal::U32(NO_LAYER));
        assert_eq!(constant(&trace, "HIZ_MAX_LEVELS"), naga::Literal::U32(HIZ_MAX_LEVELS as u32));
    }

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
