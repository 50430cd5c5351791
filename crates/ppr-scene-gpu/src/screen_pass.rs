//! The tools' screen passes (composites, resolves, debug views) share their vertex shader:
//! one triangle covering the screen (`shaders/fullscreen_triangle.wgsl`).

/// The full-screen triangle's `vs_main`.
pub const FULLSCREEN_TRIANGLE_WGSL: &str = include_str!("../shaders/fullscreen_triangle.wgsl");

/// `pass_wgsl` (its bindings and `fs_main`) after the full-screen triangle's `vs_main`.
pub fn with_fullscreen_triangle(pass_wgsl: &str) -> String {
    format!("{FULLSCREEN_TRIANGLE_WGSL}\n{pass_wgsl}")
}

/// The shader module of a screen pass: [`with_fullscreen_triangle`] of `pass_wgsl`.
pub fn screen_pass_module(device: &wgpu::Device, label: &str, pass_wgsl: &str) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(with_fullscreen_triangle(pass_wgsl).into()),
    })
}
