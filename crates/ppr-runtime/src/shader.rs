//! Assembles each pass's WGSL with the shared modules (WGSL has no `#include`).

/// The shared declarations every pass sees: encoding, then frame and shape types.
const SHARED: &str = concat!(
    include_str!("../../../shaders/ppr/encoding.wgsl"),
    "\n",
    include_str!("../../../shaders/ppr/common.wgsl"),
    "\n"
);

/// The source of one pass: the shared modules followed by the pass itself.
pub fn source(pass: &str) -> String {
    let mut s = String::with_capacity(SHARED.len() + pass.len());
    s.push_str(SHARED);
    s.push_str(pass);
    s
}

/// Creates the shader module of a pass.
pub fn module(device: &wgpu::Device, label: &str, pass: &str) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source(pass).into()),
    })
}

#[cfg(test)]
mod tests {
    /// Every pass parses and validates (clear messages without a GPU).
    #[test]
    fn every_pass_validates() {
        for (name, wgsl) in [
            ("clear", include_str!("../../../shaders/ppr/clear.wgsl")),
            ("projection", include_str!("../../../shaders/ppr/projection.wgsl")),
            ("reflection", include_str!("../../../shaders/ppr/reflection.wgsl")),
            ("tile classify", include_str!("../../../shaders/ppr/tile_classify.wgsl")),
        ] {
            let source = super::source(wgsl);
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
