//! The G-buffer extras of [`ReflectionInputs`] that the screen-space baselines need.

use ppr_testbed::ReflectionInputs;

/// The reflector-id view of `inputs`.
///
/// # Panics
/// When the caller gave none: the screen-space baselines take each pixel's plane from the
/// reflector under it, so they need [`ReflectionInputs::from_gbuffer`] (or a
/// `reflector_id` set by hand).
pub fn reflector_id<'a>(inputs: &ReflectionInputs<'a>, technique: &str) -> &'a wgpu::TextureView {
    inputs.reflector_id.unwrap_or_else(|| {
        panic!("{technique} needs ReflectionInputs::reflector_id (build the inputs with ReflectionInputs::from_gbuffer)")
    })
}
